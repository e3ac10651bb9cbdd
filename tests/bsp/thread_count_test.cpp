// Results do not depend on the thread count (docs/bsp.md, "What runs in parallel"): set
// operations large enough to take the parallel boundary merge, or the cell path (bsp/local/), give
// the same mesh, vertex for vertex and face for face, on one thread and on every core.
#include <gtest/gtest.h>

#include <cstdio>
#include <optional>

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

}  // namespace
}  // namespace sculpt
