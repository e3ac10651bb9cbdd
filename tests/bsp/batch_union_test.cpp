// unite_all (the union of many solids at once: boundaries clipped by each other, then a fresh
// tree built from the union's boundary). Checked against exact volumes (voxel counts, coordinate
// compression), the pairwise union by exact point classification, and the tree's own boundary.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "bench/peers/cases.hpp"
#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/solid_access.hpp"
#include "support/mesh_checks.hpp"
#include "support/mesh_validity.hpp"
#include "support/solid_checks.hpp"

namespace sculpt {
namespace {

using checks::vol;

using checks::EdgesManifoldAndOriented;
using checks::GenusIs;

Solid pairwise(const std::vector<Solid>& solids) {
  Solid acc;
  for (const Solid& s : solids) acc = std::move(acc) | s;
  return acc;
}

// The same tree without the carried boundary: to_mesh then extracts the boundary from the tree.
Solid tree_only(const Solid& s) { return bsp::detail::SolidAccess::make(s.planes(), s.nodes(), s.polygons(), s.root()); }

// Exact classifications of both solids agree at every point of a grid that includes the
// coordinates of faces, edges and corners (steps of `step`), and at random points.
::testing::AssertionResult SameSet(const Solid& a, const Solid& b, double lo, double hi, double step,
                                   int random_points = 2000) {
  std::vector<Eigen::Vector3d> points;
  for (double x = lo; x <= hi; x += step)
    for (double y = lo; y <= hi; y += step)
      for (double z = lo; z <= hi; z += step) points.emplace_back(x, y, z);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(lo, hi);
  for (int i = 0; i < random_points; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  for (const Eigen::Vector3d& p : points) {
    const Location la = classify(a, p).location, lb = classify(b, p).location;
    if (la != lb)
      return ::testing::AssertionFailure() << "point (" << p.transpose() << "): " << int(la) << " vs " << int(lb)
                                           << " (0 out, 1 in, 2 boundary)";
  }
  return ::testing::AssertionSuccess() << points.size() << " points";
}

TEST(BatchUnion, GridBoxesWithSharedFacesEdgesAndCornersMatchVoxelsAndThePairwiseUnion) {
  // Integer boxes in [0, 8]^3: many coplanar, touching and repeated faces.
  constexpr int N = 8;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> corner(0, N - 1), size(1, 3);
    std::vector<Solid> boxes;
    std::vector<bool> voxel(N * N * N, false);
    const int count = 10 + 15 * int(seed);
    for (int k = 0; k < count; ++k) {
      int lo[3], hi[3];
      for (int i = 0; i < 3; ++i) lo[i] = corner(rng), hi[i] = std::min(N, lo[i] + size(rng));
      boxes.push_back(box({double(lo[0]), double(lo[1]), double(lo[2])}, {double(hi[0]), double(hi[1]), double(hi[2])}));
      for (int x = lo[0]; x < hi[0]; ++x)
        for (int y = lo[1]; y < hi[1]; ++y)
          for (int z = lo[2]; z < hi[2]; ++z) voxel[std::size_t((x * N + y) * N + z)] = true;
    }
    const double expected = double(std::count(voxel.begin(), voxel.end(), true));
    const Solid all = unite_all(boxes);
    EXPECT_TRUE(checks::VerticesManifold(to_mesh(all)));
    EXPECT_EQ(vol(all), expected);
    EXPECT_EQ(vol(tree_only(all)), expected);  // the tree agrees with the boundary it carries
    EXPECT_TRUE(SameSet(all, pairwise(boxes), -0.5, N + 0.5, 0.5, 500));
  }
}

TEST(BatchUnion, RandomBoxesOfTheBenchmarkMatchCoordinateCompression) {
  const std::vector<bench_cases::Box> specs = bench_cases::random_boxes(200);
  std::vector<Solid> boxes;
  for (const auto& b : specs) boxes.push_back(box({b.lo[0], b.lo[1], b.lo[2]}, {b.hi[0], b.hi[1], b.hi[2]}));
  const Solid all = unite_all(boxes);
  const double expected = bench_cases::union_volume(specs);
  const PolygonMesh m = to_mesh(all);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_NEAR(vol(all), expected, 1e-12 * expected);
  EXPECT_NEAR(vol(tree_only(all)), expected, 1e-12 * expected);
  EXPECT_TRUE(SameSet(all, pairwise(boxes), 0, 17, 1.0 / 4, 3000));
}

TEST(BatchUnion, RepeatedNestedEmptyAndFullOperands) {
  const Solid a = box({0, 0, 0}, {1, 1, 1});
  // The same box five times: one copy of each face survives.
  const Solid five = unite_all({a, a, a, a, a});
  EXPECT_EQ(vol(five), 1.0);
  EXPECT_EQ(to_mesh(five).faces.size(), 6u);
  // Nested boxes and empty operands.
  const Solid nested = unite_all({box({0.25, 0.25, 0.25}, {0.5, 0.5, 0.5}), Solid(), a, box({0, 0, 0}, {0.5, 1, 1})});
  EXPECT_EQ(vol(nested), 1.0);
  EXPECT_EQ(to_mesh(nested).faces.size(), 6u);
  // A full operand makes all of space; no operand, or only empty ones, nothing.
  EXPECT_EQ(unite_all({a, Solid::leaf(true), a}).root(), kIn);
  EXPECT_TRUE(unite_all({}).is_empty());
  EXPECT_TRUE(unite_all({Solid(), Solid(), Solid()}).is_empty());
  EXPECT_EQ(vol(unite_all({Solid(), a, Solid()})), 1.0);
}

TEST(BatchUnion, TouchingAlongFacesEdgesAndCornersOnly) {
  const Solid a = box({0, 0, 0}, {1, 1, 1});
  // Three boxes in a row sharing faces: one box of volume 3, six faces.
  const Solid row = unite_all({a, box({1, 0, 0}, {2, 1, 1}), box({2, 0, 0}, {3, 1, 1})});
  EXPECT_EQ(vol(row), 3.0);
  EXPECT_TRUE(GenusIs(to_mesh(row), 0));
  EXPECT_EQ(to_mesh(row).faces.size(), 6u);
  // Sharing only an edge or a corner: separate sheets, as the pairwise union gives.
  const std::vector<Solid> edge_corner = {a, box({1, 1, 0}, {2, 2, 1}), box({2, 2, 1}, {3, 3, 2})};
  const Solid ec = unite_all(edge_corner);
  const PolygonMesh m = to_mesh(ec);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0, 3));
  EXPECT_EQ(vol(ec), 3.0);
  EXPECT_TRUE(SameSet(ec, pairwise(edge_corner), -0.5, 3.5, 0.5));
  // Two boxes closing a ring around a hole: genus 1.
  const std::vector<Solid> ring = {box({0, 0, 0}, {3, 1, 1}), box({0, 2, 0}, {3, 3, 1}), box({0, 1, 0}, {1, 2, 1}),
                                   box({2, 1, 0}, {3, 2, 1})};
  const Solid r = unite_all(ring);
  EXPECT_TRUE(GenusIs(to_mesh(r), 1));
  EXPECT_EQ(vol(r), 8.0);
}

TEST(BatchUnion, CurvedAndTiltedSolidsMatchThePairwiseUnion) {
  const Solid s = sphere(1.0, {.segments = 24});
  const Solid c = cylinder(0.5, 2.5, {.segments = 20});
  const Solid b = box({0, 0, 0}, {1.5, 1.5, 1.5});
  const Solid t = transform(box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}),
                           Eigen::Affine3d(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized())));
  const Solid s2 = translate(s, {1.0, 0.0, 0.0});  // overlaps s: many tilted planes meet
  const std::vector<Solid> all = {s, c, b, t, s2, s};  // s twice: coplanar faces of the same orientation
  const Solid u = unite_all(all);
  const Solid p = pairwise(all);
  const PolygonMesh m = to_mesh(u);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(checks::ValidSolidMesh(m));
  EXPECT_NEAR(vol(u), vol(p), 1e-12 * vol(p));
  EXPECT_NEAR(vol(tree_only(u)), vol(p), 1e-12 * vol(p));
  EXPECT_TRUE(SameSet(u, p, -2, 3, 0.25));
}

TEST(BatchUnion, ConvexOperandsGiveShallowTrees) {
  // Four overlapping spheres of 1,200 faces each: autopartition alone chains their faces (each
  // sees all others behind it); planes through the median keep the tree shallower (height 102
  // with them, 244 without, when this test was written with flat polar caps; 152 since each pole
  // is a vertex, a fan of 48 faces: the fans still chain).
  std::vector<Solid> all;
  for (int i = 0; i < 4; ++i) all.push_back(translate(sphere(1.0, {.segments = 48}), {0.7 * i, 0.3 * (i % 2), 0.0}));
  const Solid u = unite_all(all);
  const Solid p = pairwise(all);
  EXPECT_LT(tree_stats(u).height, 170);
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(u)));
  EXPECT_NEAR(vol(u), vol(p), 1e-12 * vol(p));
  EXPECT_NEAR(vol(tree_only(u)), vol(p), 1e-12 * vol(p));
  EXPECT_TRUE(SameSet(u, p, -1.5, 3.5, 0.25));
}

TEST(BatchUnion, HundredBoxesWithTinyOffsetsMatchThePairwiseUnion) {
  // The same unit box a hundred times, moved by one or a few grid steps (2^-15): almost coplanar
  // faces everywhere, many exactly coplanar.
  const double step = 1.0 / 32768;
  std::vector<Solid> all;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d lo(i * step, (i % 7) * step, (i % 3) * step);
    all.push_back(box(lo, lo + Eigen::Vector3d::Ones()));
  }
  const Solid u = unite_all(all);
  const Solid p = pairwise(all);
  const PolygonMesh m = to_mesh(u);
  EXPECT_TRUE(checks::VerticesManifold(m));
  EXPECT_TRUE(GenusIs(m, 0));
  EXPECT_NEAR(vol(u), vol(p), 1e-14 * vol(p));
  EXPECT_NEAR(vol(tree_only(u)), vol(p), 1e-14 * vol(p));
  EXPECT_TRUE(SameSet(u, p, -0.25, 1.25, 1.0 / 8, 3000));
}

TEST(BatchUnion, UnboundedOperands) {
  // The complement of a box united with boxes that fill part of its hole.
  const Solid hole = complement(box({0, 0, 0}, {4, 4, 4}));
  const std::vector<Solid> all = {box({0, 0, 0}, {1, 4, 4}), hole, box({3, 0, 0}, {4, 4, 4}), box({1, 1, 1}, {2, 2, 2})};
  const Solid u = unite_all(all);
  const Solid p = pairwise(all);
  EXPECT_TRUE(SameSet(u, p, -1, 5, 0.5));
  const Solid window = box({-2, -2, -2}, {6, 6, 6});
  EXPECT_EQ(vol(window & u), 512.0 - 64.0 + 16.0 + 16.0 + 1.0);
  // An operand and its complement: all of space.
  const Solid a = box({0, 0, 0}, {1, 1, 1});
  EXPECT_EQ(unite_all({a, complement(a), box({5, 5, 5}, {6, 6, 6})}).root(), kIn);
}

}  // namespace
}  // namespace sculpt
