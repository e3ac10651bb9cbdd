// Results do not depend on the thread count (docs/bsp.md, "What runs in parallel"): set
// operations large enough to take the parallel boundary merge, or the cell path (bsp/local/), give
// the same mesh, vertex for vertex and face for face, on one thread and on every core.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <vector>

#include "base/parallel.hpp"
#include "bsp/boundary.hpp"
#include "bsp/local/cell_merge.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

PolygonMesh run(int op, bool classic) {
  std::optional<bsp::detail::ScopedCellMergeThreshold> path;
  if (classic) path.emplace(bsp::detail::kClassicMergeOnly);
  // 96 segments: about 4600 faces each, past the parallel merge's threshold (boundary_merge.cpp)
  // and the cell path's (local/cell_merge.hpp).
  const Solid a = sphere(1.0, {.segments = 96});
  const Solid b = translate(sphere(1.0, {.segments = 96}), {0.3, 0.2, 0.1});
  switch (op) {
    case 0:
      return to_mesh(a | b);
    case 1:
      return to_mesh(a - b);
    default:
      return to_mesh(a & b);
  }
}

TEST(ThreadCount, SetOperationsGiveTheSameMeshOnOneThreadAndOnEvery) {
  if (thread_count() < 2) std::printf("note: one core here: both runs are serial\n");
  for (int k = 0; k < 6; ++k) {
    const int op = k % 3;
    const bool classic = k >= 3;
    PolygonMesh serial;
    {
      ThreadLimit one(1);
      serial = run(op, classic);
    }
    const PolygonMesh parallel = run(op, classic);
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(parallel)) << k;
    ASSERT_EQ(serial.vertices.size(), parallel.vertices.size()) << k;
    ASSERT_EQ(serial.faces.size(), parallel.faces.size()) << k;
    for (std::size_t i = 0; i < serial.vertices.size(); ++i)
      ASSERT_EQ(serial.vertices[i], parallel.vertices[i]) << k << " vertex " << i;
    for (std::size_t i = 0; i < serial.faces.size(); ++i)
      ASSERT_EQ(serial.faces[i], parallel.faces[i]) << k << " face " << i;
  }
}

TEST(ThreadCount, BoundaryExtractionGivesTheSameMeshOnOneThreadAndOnEvery) {
  // A 2000-sided prism carries no boundary: to_mesh pushes its 2002 node polygons down the tree in
  // chunks of 512 nodes (bsp/tree/boundary_fragments.cpp), in parallel.
  std::vector<Eigen::Vector2d> polygon;
  for (int k = 0; k < 2000; ++k) {  // radius 500: each edge bulges out ~20 grid steps (stays convex)
    const double t = 2 * std::numbers::pi * k / 2000;
    polygon.emplace_back(500 * std::cos(t), 500 * std::sin(t));
  }
  const Solid p = prism(polygon, 0, 1);
  PolygonMesh serial;
  {
    ThreadLimit one(1);
    serial = to_mesh(p, {.clean = false});
  }
  const PolygonMesh parallel = to_mesh(p, {.clean = false});
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(parallel));
  EXPECT_EQ(parallel.faces.size(), 2002u);
  EXPECT_EQ(serial.vertices, parallel.vertices);
  EXPECT_EQ(serial.faces, parallel.faces);
}

TEST(ThreadCount, UnionOfManySolidsGivesTheSameMeshOnOneThreadAndOnEvery) {
  // unite_all of more than two solids (bsp/merge/batch_union.cpp): the operands' deferred trees are
  // built side by side, then each operand's boundary is clipped by the others on its own core.
  auto run = [] {
    std::vector<Solid> parts;
    for (int k = 0; k < 40; ++k) {
      const Eigen::Vector3d axis = Eigen::Vector3d(1 + k % 3, 2 - k % 5, 1 + k % 7).normalized();
      const Eigen::Affine3d turn = Eigen::Translation3d(0.4 * (k % 5), 0.3 * (k % 4), 0.25 * (k % 6)) *
                                   Eigen::AngleAxisd(0.37 * k, axis) * Eigen::Translation3d(-0.5, -0.5, -0.5);
      parts.push_back(transform(box({0, 0, 0}, {1, 1, 1}), turn));
    }
    parts.push_back(translate(sphere(0.8, {.segments = 24}), {1, 1, 1}));
    return to_mesh(unite_all(std::move(parts)));
  };
  PolygonMesh serial;
  {
    ThreadLimit one(1);
    serial = run();
  }
  const PolygonMesh parallel = run();
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(parallel));
  EXPECT_EQ(serial.vertices, parallel.vertices);
  EXPECT_EQ(serial.faces, parallel.faces);
}

}  // namespace
}  // namespace sculpt
