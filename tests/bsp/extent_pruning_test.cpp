// Extent pruning (bsp/extent_pruning.hpp): in A − B and A ∩ B, B's planes with all of A on one
// closed side are dropped before the merge, and B's fragments on them are dropped from the
// boundary. Checked by the sides themselves (boxes with exactly known extents), the pruned tree,
// and the results against exact references: voxel counts and classification at voxel centres
// for grid boxes whose faces often lie on A's extent, and symmetric parts of a sphere.
#include <gtest/gtest.h>

#include <random>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/merge/extent_pruning.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/fragment_boxes.hpp"
#include "support/mesh_checks.hpp"
#include "support/solid_checks.hpp"

namespace sculpt {
namespace {

using checks::vol;

using bsp::detail::FragmentBox;
using bsp::detail::FragmentBoxes;
using bsp::detail::fragment_box;

using checks::EdgesManifoldAndOriented;
using kernel::Side;

// A's sides of every plane of B (both in one arena, as a set operation has them).
struct Sides {
  bsp::detail::Arena arena;
  bsp::detail::ExtentSides sides;
  TreeRef b = kOut;
  FragmentList a_faces;  // A's boundary on the arena's planes
  Side of(const kernel::Plane& p) const {  // the side for B's plane equal to p (Both if none)
    for (std::int32_t i = 0; i < arena.planes.size(); ++i)
      if (arena.planes[i] == p && sides.of(i) != Side::Both) return sides.of(i);
    return Side::Both;
  }
};
Sides sides_of(const Solid& a, const Solid& b) {
  Sides s;
  const TreeRef ra = s.arena.append(a);
  s.a_faces = s.arena.boundary_of(a);
  const FragmentList& fa = s.a_faces;
  s.b = s.arena.append(b);
  const FragmentList fb = s.arena.boundary_of(b);
  FragmentBoxes boxes;
  bsp::detail::complete_boxes(fa, boxes);
  s.sides = bsp::detail::extent_sides(s.arena, ra, fa, boxes, s.b, fb);
  return s;
}

kernel::Plane axis_plane(int axis, std::int64_t sign, double at) {  // sign * (x_axis - at) <= 0
  std::int64_t n[3] = {0, 0, 0};
  n[axis] = sign;
  return kernel::make_plane(n[0], n[1], n[2], -kernel::Int128(sign * kernel::snap(at)));
}

TEST(ExtentPruning, SidesOfPlanesTouchingCrossingAndMissingABox) {
  const Solid a = box({0, 0, 0}, {1, 1, 1});
  // B = [0.5, 2] x [0, 1] x [-3, 1]: its faces x = 2, y = 0, y = 1, z = 1 have A on one closed
  // side (touching or apart); x = 0.5 crosses A; z = -3 misses it.
  Sides s = sides_of(a, box({0.5, 0, -3}, {2, 1, 1}));
  EXPECT_EQ(s.of(axis_plane(0, 1, 2)), Side::Negative);   // x <= 2: A has x <= 1
  EXPECT_EQ(s.of(axis_plane(0, -1, 0.5)), Side::Both);    // x >= 0.5 crosses A
  EXPECT_EQ(s.of(axis_plane(1, -1, 0)), Side::Negative);  // -y <= 0: A touches y = 0 from above
  EXPECT_EQ(s.of(axis_plane(1, 1, 1)), Side::Negative);   // y <= 1: touching
  EXPECT_EQ(s.of(axis_plane(2, 1, 1)), Side::Negative);   // z <= 1: touching
  EXPECT_EQ(s.of(axis_plane(2, -1, -3)), Side::Negative);  // -z - 3 <= 0: apart
  // Pruned, B's tree keeps only the crossing plane.
  const TreeRef pruned = bsp::detail::prune_to_extent(s.arena, s.b, s.sides);
  ASSERT_FALSE(is_leaf(pruned));
  const BspNode& n = s.arena.nodes[std::size_t(pruned)];
  EXPECT_TRUE(s.arena.planes[n.plane] == axis_plane(0, -1, 0.5));
  EXPECT_TRUE(is_leaf(n.negative) && is_leaf(n.positive));
  // B touching A along a face only: every plane is one-sided, B collapses to its out leaf.
  Sides t = sides_of(a, box({1, 0, 0}, {2, 1, 1}));
  EXPECT_EQ(t.of(axis_plane(0, -1, 1)), Side::Positive);  // 1 - x <= 0 holds B; A is on x <= 1
  EXPECT_EQ(bsp::detail::prune_to_extent(t.arena, t.b, t.sides), kOut);
  // An unbounded A (a complement) has no extent: nothing is one-sided.
  Sides u = sides_of(complement(a), box({2, 0, 0}, {3, 1, 1}));
  EXPECT_TRUE(u.sides.none());
}

TEST(ExtentPruning, CornerTouchingAndTiltedPlanesAreDecidedExactly) {
  const Solid a = box({0, 0, 0}, {1, 1, 1});
  // x + y + z <= 3 touches A only at (1, 1, 1); x + y + z <= 2.9 cuts the corner off.
  auto tetrahedron = [](double sum) {
    return convex_polytope({{{1, 1, 1}, -sum}, {{-1, 0, 0}, -5.0}, {{0, -1, 0}, -5.0}, {{0, 0, -1}, -5.0}});
  };
  const Solid touching = tetrahedron(3.0), cutting = tetrahedron(2.9);
  EXPECT_EQ(sides_of(a, touching).of(kernel::plane_from_normal({1, 1, 1}, -3.0)), Side::Negative);
  EXPECT_EQ(sides_of(a, cutting).of(kernel::plane_from_normal({1, 1, 1}, -2.9)), Side::Both);
  EXPECT_EQ(sides_of(a, cutting).of(kernel::plane_from_normal({-1, 0, 0}, -5.0)), Side::Negative);
  EXPECT_NEAR(vol(a - touching), 0.0, 1e-12);
  EXPECT_NEAR(vol(a & touching), 1.0, 1e-12);
  const double corner = 0.1 * 0.1 * 0.1 / 6.0;  // the tetrahedron beyond x + y + z = 2.9
  EXPECT_NEAR(vol(a - cutting), corner, 1e-9);
  EXPECT_NEAR(vol(a & cutting), 1.0 - corner, 1e-9);
}

// Grid boxes: A a union of integer boxes in [0, 8]^3, B an integer box in [-1, 9]^3 whose
// faces often lie on A's extent (its bounding box) or outside it. Volumes against voxel counts,
// classification at every voxel centre against the voxels, meshes closed.
TEST(ExtentPruning, DifferencesAndIntersectionsOfGridBoxesMatchVoxels) {
  constexpr int N = 8;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> corner(0, N - 1), size(1, 4), coin(0, 2);
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    std::vector<char> in_a(N * N * N, 0);
    Solid a;
    int lo_a[3] = {N, N, N}, hi_a[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k) {
      int lo[3], hi[3];
      for (int i = 0; i < 3; ++i) {
        lo[i] = corner(rng), hi[i] = std::min(N, lo[i] + size(rng));
        lo_a[i] = std::min(lo_a[i], lo[i]), hi_a[i] = std::max(hi_a[i], hi[i]);
      }
      a = std::move(a) | box({double(lo[0]), double(lo[1]), double(lo[2])}, {double(hi[0]), double(hi[1]), double(hi[2])});
      for (int x = lo[0]; x < hi[0]; ++x)
        for (int y = lo[1]; y < hi[1]; ++y)
          for (int z = lo[2]; z < hi[2]; ++z) in_a[std::size_t((x * N + y) * N + z)] = 1;
    }
    // B's bounds: on A's extent, one step outside it, or anywhere in the grid.
    int lo_b[3], hi_b[3];
    for (int i = 0; i < 3; ++i) {
      const int pick = coin(rng);
      lo_b[i] = pick == 0 ? lo_a[i] : (pick == 1 ? lo_a[i] - 1 : corner(rng));
      const int pick2 = coin(rng);
      hi_b[i] = pick2 == 0 ? hi_a[i] : (pick2 == 1 ? hi_a[i] + 1 : std::min(N, lo_b[i] + size(rng)));
      if (hi_b[i] <= lo_b[i]) hi_b[i] = lo_b[i] + 1;
    }
    const Solid b = box({double(lo_b[0]), double(lo_b[1]), double(lo_b[2])}, {double(hi_b[0]), double(hi_b[1]), double(hi_b[2])});
    auto in_b = [&](int x, int y, int z) {
      return x >= lo_b[0] && x < hi_b[0] && y >= lo_b[1] && y < hi_b[1] && z >= lo_b[2] && z < hi_b[2];
    };
    const Solid diff = a - b, both = a & b, diff_in_place = Solid(a) - b;
    double expected_diff = 0, expected_both = 0;
    for (int x = 0; x < N; ++x)
      for (int y = 0; y < N; ++y)
        for (int z = 0; z < N; ++z) {
          const bool ia = in_a[std::size_t((x * N + y) * N + z)] != 0, ib = in_b(x, y, z);
          expected_diff += ia && !ib;
          expected_both += ia && ib;
          const Eigen::Vector3d centre(x + 0.5, y + 0.5, z + 0.5);
          ASSERT_EQ(classify(diff, centre).location == Location::Inside, ia && !ib) << centre.transpose();
          ASSERT_EQ(classify(both, centre).location == Location::Inside, ia && ib) << centre.transpose();
        }
    EXPECT_EQ(vol(diff), expected_diff);
    EXPECT_EQ(vol(diff_in_place), expected_diff);
    EXPECT_EQ(vol(both), expected_both);
    if (expected_diff > 0) {
      EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(diff)));
    }
    if (expected_both > 0) {
      EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(both)));
    }
  }
}

// A sphere cut by boxes through its centre and touching its extreme vertices: its octants and
// halves, against the sphere's own volume (the sphere is symmetric in the three coordinate
// planes: its vertices are mirror images).
TEST(ExtentPruning, SpherePartsBoundedByTouchingPlanes) {
  for (const int n : {16, 32, 48}) {
    SCOPED_TRACE(testing::Message() << "segments " << n);
    const Solid s = sphere(1.0, {.segments = n});
    const double v = vol(s);
    const Solid octant = box({0, 0, 0}, {1, 1, 1});  // x = 1 etc. touch the sphere's extreme vertices
    const Solid half = box({0, -1, -1}, {1, 1, 1});
    EXPECT_NEAR(vol(s & octant), v / 8, 1e-9);
    EXPECT_NEAR(vol(s - octant), 7 * v / 8, 1e-9);
    EXPECT_NEAR(vol(s & half), v / 2, 1e-9);
    EXPECT_NEAR(vol(s - half), v / 2, 1e-9);
    EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(s - octant)));
    EXPECT_TRUE(checks::VerticesManifold(to_mesh(s - octant)));
  }
}

// The side of every plane of B against a brute-force reference: every corner of A's boundary
// by the exact predicate, no boxes. A has many fragments (a sphere of 48 and 72 segments: 1,100
// and 2,600 fragments, so the block boxes form hierarchies of 7 and 8 levels), B a sphere or a box
// placed to cross A, to touch it from outside or inside, or to miss it. With 128 segments (8,000
// fragments, 250 blocks) B is small beside A, as a carving tool is: balls cutting into A's
// surface, one just off it, and a thin slab grazing the pole; their planes are decided through
// witnesses near B and the hierarchy over A's blocks.
TEST(ExtentPruning, SidesOfManyPlanesMatchEveryCornerExactly) {
  for (const int n : {48, 72, 128}) {
    const Solid a = sphere(1.0, {.segments = n});
    const Eigen::Vector3d on_surface = Eigen::Vector3d(0.3, 0.5, 0.8).normalized();
    const std::vector<Solid> others =
        n < 128 ? std::vector<Solid>{
                      translate(sphere(1.0, {.segments = n}), {0.5, 0.375, 0.25}),  // crossing
                      translate(sphere(0.5, {.segments = n / 2}), {0, 0, 0.25}),     // inside
                      translate(sphere(1.0, {.segments = n}), {2.0, 0, 0}),          // touching at the equator vertex
                      translate(sphere(0.75, {.segments = n}), {3.0, 1.0, 0.5}),     // apart
                      box({-0.25, -0.25, 0.5}, {0.25, 0.25, 1.0}),                   // top face near the pole
                      box({-2, -2, -2}, {2, 2, -1}),                                 // touching the bottom
                  }
                : std::vector<Solid>{
                      translate(sphere(0.1, {.segments = 12}), on_surface),                 // cutting in
                      translate(sphere(0.1, {.segments = 12}), 0.95 * on_surface) |         // a short stroke
                          translate(sphere(0.1, {.segments = 12}), Eigen::Vector3d(0.35, 0.45, 0.8).normalized()),
                      translate(sphere(0.05, {.segments = 12}), 1.1 * on_surface),          // just off A
                      box({-0.1, -0.1, 0.999}, {0.1, 0.1, 1.2}),                            // grazing the pole
                  };
    for (std::size_t k = 0; k < others.size(); ++k) {
      SCOPED_TRACE(testing::Message() << "segments " << n << ", other solid " << k);
      Sides s = sides_of(a, others[k]);
      const FragmentList& fa = s.a_faces;
      ASSERT_GT(fa.size(), 1000u);
      // Every plane of B's nodes.
      std::vector<std::int32_t> planes;
      std::vector<TreeRef> stack{s.b};
      while (!stack.empty()) {
        const TreeRef t = stack.back();
        stack.pop_back();
        if (is_leaf(t)) continue;
        const BspNode& node = s.arena.nodes[std::size_t(t)];
        planes.push_back(node.plane);
        stack.push_back(node.negative);
        stack.push_back(node.positive);
      }
      ASSERT_GE(planes.size(), 6u);
      std::size_t one_sided = 0;
      for (const std::int32_t p : planes) {
        const kernel::Plane& h = s.arena.planes[p];
        bool neg = false, pos = false;
        for (const FragmentRef f : fa)
          for (const kernel::Corner& c : f.polygon.corners) {
            const kernel::Sign g =
                kernel::orient(s.arena.planes[f.polygon.support], s.arena.planes[c.p], s.arena.planes[c.q], c.at(), h);
            neg |= g == kernel::Sign::Negative;
            pos |= g == kernel::Sign::Positive;
          }
        const Side expected = neg == pos ? Side::Both : (neg ? Side::Negative : Side::Positive);
        EXPECT_EQ(s.sides.of(p), expected) << "plane " << p;
        one_sided += expected != Side::Both;
      }
      if (n == 128) {
        EXPECT_GT(one_sided, 0u);  // faces of the tool outside A
      } else if (k == 0) {
        EXPECT_GT(one_sided, 0u);  // faces of B far from A
      } else if (k == 2 || k == 3) {
        EXPECT_GT(one_sided, planes.size() / 4);
      }
    }
  }
}

}  // namespace
}  // namespace sculpt
