#include "bsp/set_operations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/transform.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using checks::EdgesManifoldAndOriented;
using checks::GenusIs;
using checks::VolumeNear;

Solid cube(double x, double y, double z, double s) { return box({x, y, z}, {x + s, y + s, z + s}); }

double vol(const Solid& s) { return double(checks::reference_signed_volume(to_mesh(s))); }

TEST(SetOperations, DisjointUnionHasTwoComponents) {
  const Solid u = cube(0, 0, 0, 1) | cube(2, 0, 0, 1);
  const PolygonMesh m = to_mesh(u);
  EXPECT_TRUE(GenusIs(m, 0, 2));
  EXPECT_TRUE(VolumeNear(m, 2.0, 1e-15));
}

TEST(SetOperations, OverlappingBoxes) {
  const Solid a = cube(0, 0, 0, 2), b = cube(1, 1, 1, 2);
  for (const auto& [s, v] : {std::pair{a | b, 15.0}, {a & b, 1.0}, {a - b, 7.0}, {b - a, 7.0}}) {
    const PolygonMesh m = to_mesh(s);
    EXPECT_TRUE(EdgesManifoldAndOriented(m));
    EXPECT_TRUE(GenusIs(m, 0));
    EXPECT_TRUE(VolumeNear(m, v, 1e-14));
  }
}

TEST(SetOperations, SelfSubtractIsEmptyAndSelfUnionIsSame) {
  const Solid a = sphere(1.0, {.segments = 16});
  EXPECT_TRUE((a - a).is_empty());
  const Solid u = a | a;
  EXPECT_NEAR(vol(u), vol(a), 1e-12);
  EXPECT_EQ(to_mesh(u).faces.size(), to_mesh(a).faces.size());
  EXPECT_NEAR(vol(a & a), vol(a), 1e-12);
}

TEST(SetOperations, AbsorptionAndDeMorgan) {
  const Solid a = sphere(1.0, {.segments = 12}), b = cube(0, 0, 0, 1.5);
  EXPECT_NEAR(vol((a | b) & a), vol(a), 1e-12);
  // De Morgan: complement(a | b) = complement(a) & complement(b); compare through a bounded window.
  const Solid window = cube(-3, -3, -3, 6);
  const Solid lhs = window & complement(a | b);
  const Solid rhs = window & (complement(a) & complement(b));
  EXPECT_NEAR(vol(lhs), vol(rhs), 1e-12);
  EXPECT_NEAR(vol(lhs), 216.0 - vol(a | b), 1e-12);
  EXPECT_TRUE(vol(lhs - rhs) == 0.0 && (lhs - rhs).is_empty());
}

TEST(SetOperations, SharedFaceUnionIsOneBox) {
  const PolygonMesh m = to_mesh(cube(0, 0, 0, 1) | cube(1, 0, 0, 1));
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0));
  EXPECT_TRUE(VolumeNear(m, 2.0, 1e-15));
}

TEST(SetOperations, SharedEdgeUnionIsTwoSheets) {
  const PolygonMesh m = to_mesh(cube(0, 0, 0, 1) | cube(1, 1, 0, 1));
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0, 2));  // touching along an edge: vertices duplicated per sheet
  EXPECT_TRUE(VolumeNear(m, 2.0, 1e-15));
}

TEST(SetOperations, SharedCornerUnion) {
  const PolygonMesh m = to_mesh(cube(0, 0, 0, 1) | cube(1, 1, 1, 1));
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0, 2));
  EXPECT_TRUE(VolumeNear(m, 2.0, 1e-15));
}

TEST(SetOperations, SphereMinusCornerCube) {
  for (int n : {16, 32}) {
    const Solid s = sphere(1.0, {.segments = n});
    const Solid d = s - cube(0, 0, 0, 1);
    const PolygonMesh m = to_mesh(d);
    EXPECT_TRUE(EdgesManifoldAndOriented(m));
    EXPECT_TRUE(GenusIs(m, 0));
    // The removed part is exactly one octant by symmetry of the sphere (n divisible by 4).
    EXPECT_NEAR(vol(d), vol(s) * 7.0 / 8.0, 1e-9);
  }
}

TEST(SetOperations, HundredBoxesWithTinyOffsets) {
  Solid acc;
  const double step = 1.0 / 32768;  // one grid step
  for (int i = 0; i < 100; ++i) acc = acc | cube(i * step, (i % 7) * step, (i % 3) * step, 1.0);
  const PolygonMesh m = to_mesh(acc);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0));
  EXPECT_GT(vol(acc), 1.0);
}

}  // namespace
}  // namespace sculpt

namespace sculpt {
namespace {

TEST(SetOperations, AlmostCoplanarFacesFromATinyRotation) {
  const Solid a = box({-1, -1, -1}, {1, 1, 1});
  for (double degrees : {1e-3, 1e-6}) {
    const Solid b = rotate(a, {0, 0, 1}, degrees);
    for (const Solid& s : {a | b, a & b, a - b}) {
      const PolygonMesh m = to_mesh(s);
      if (m.faces.empty()) continue;
      EXPECT_TRUE(checks::EdgesManifoldAndOriented(m)) << degrees;
    }
    // Volumes: |a ∪ b| + |a ∩ b| = |a| + |b| (inclusion-exclusion, independent of the mesh).
    EXPECT_NEAR(volume(a | b) + volume(a & b), volume(a) + volume(b), 1e-9) << degrees;
    EXPECT_NEAR(volume(a - b), volume(a) - volume(a & b), 1e-9) << degrees;
  }
}

}  // namespace
}  // namespace sculpt

namespace sculpt {
namespace {

TEST(SetOperations, InPlaceOperationsMatchTheCopyingOnesEvenWhenAliased) {
  Solid acc = box({0, 0, 0}, {1, 1, 1});
  Solid copy = acc;
  for (int i = 1; i < 20; ++i) {
    const Solid b = box({i * 0.25, 0, 0}, {i * 0.25 + 1, 1, 1 + i * 0.125});
    copy = copy | b;
    acc = std::move(acc) | b;
  }
  EXPECT_EQ(volume(acc), volume(copy));
  EXPECT_EQ(tree_stats(acc).nodes, tree_stats(copy).nodes);
  Solid self = sphere(1.0, {.segments = 8});
  const double v = volume(self);
  self = unite(std::move(self), self);  // aliased operands
  EXPECT_NEAR(volume(self), v, 1e-12);
  EXPECT_NEAR(volume(unite_all({box({0, 0, 0}, {1, 1, 1}), box({2, 0, 0}, {3, 1, 1}), box({0.5, 0, 0}, {2.5, 1, 1})})), 3.0, 1e-15);
}

TEST(SetOperations, CompactedResultsAreDepthFirstWithoutUnusedNodesOrPlanes) {
  // Copying operations compact their result (in the arena's own buffers): the root is node 0,
  // the nodes are in pre-order (positive child first), every node is reachable, every plane
  // beyond the world box is used, and each node's polygon lies on its plane. Checked on results
  // whose arenas held many dropped nodes (a sphere cut by boxes, a chain of unions).
  Solid chain = cube(0, 0, 0, 1);
  for (int i = 1; i < 12; ++i) chain = chain | cube(0.375 * i, 0.25 * (i % 3), 0.125 * (i % 5), 1);
  const Solid s16 = sphere(1.0, {.segments = 16}), s12 = sphere(1.0, {.segments = 12});  // lvalues:
  const Solid cases[] = {s16 - cube(0, 0, 0, 1), chain, intersect(s12, cube(-0.5, -0.5, -0.5, 1))};  // copying
  for (const Solid& s : cases) {
    ASSERT_FALSE(is_leaf(s.root()));
    EXPECT_EQ(s.root(), 0);
    std::vector<TreeRef> stack{s.root()};
    std::vector<bool> plane_used(std::size_t(s.planes().size()), false);
    TreeRef expected = 0;
    while (!stack.empty()) {
      const TreeRef r = stack.back();
      stack.pop_back();
      if (is_leaf(r)) continue;
      EXPECT_EQ(r, expected++);
      const BspNode& n = s.nodes()[std::size_t(r)];
      const auto& poly = s.polygons()[std::size_t(r)];
      EXPECT_EQ(poly.support, n.plane);
      plane_used[std::size_t(n.plane)] = true;
      for (const auto& c : poly.corners) plane_used[std::size_t(c.edge)] = plane_used[std::size_t(c.p)] = plane_used[std::size_t(c.q)] = true;
      stack.push_back(n.negative);
      stack.push_back(n.positive);
    }
    EXPECT_EQ(std::size_t(expected), s.nodes().size());  // no unreachable node
    for (const auto& f : s.boundary()) {
      plane_used[std::size_t(f.polygon.support)] = true;
      for (const auto& c : f.polygon.corners) plane_used[std::size_t(c.edge)] = plane_used[std::size_t(c.p)] = plane_used[std::size_t(c.q)] = true;
    }
    for (std::size_t i = 6; i < plane_used.size(); ++i) EXPECT_TRUE(plane_used[i]) << "unused plane " << i;
  }
}

}  // namespace
}  // namespace sculpt
