// Results do not depend on the thread count (docs/bsp.md, "What runs in parallel"): set
// operations large enough to take the parallel boundary merge give the same mesh, vertex for
// vertex and face for face, on one thread and on every core.
#include <gtest/gtest.h>

#include <cstdio>

#include "base/parallel.hpp"
#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

PolygonMesh run(int op) {
  // 96 segments: about 4600 faces each, past the parallel merge's threshold (boundary_merge.cpp).
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
  for (int op = 0; op < 3; ++op) {
    PolygonMesh serial;
    {
      ThreadLimit one(1);
      serial = run(op);
    }
    const PolygonMesh parallel = run(op);
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(parallel)) << op;
    ASSERT_EQ(serial.vertices.size(), parallel.vertices.size()) << op;
    ASSERT_EQ(serial.faces.size(), parallel.faces.size()) << op;
    for (std::size_t i = 0; i < serial.vertices.size(); ++i)
      ASSERT_EQ(serial.vertices[i], parallel.vertices[i]) << op << " vertex " << i;
    for (std::size_t i = 0; i < serial.faces.size(); ++i)
      ASSERT_EQ(serial.faces[i], parallel.faces[i]) << op << " face " << i;
  }
}

}  // namespace
}  // namespace sculpt
