// unite_convex_hulls (bsp/merge/convex_union.hpp) against an independent construction: each
// point set's hull as a solid with its own tree (bsp/hull.hpp), united by unite_all
// (batch_union.hpp), compared as sets ((a - b) and (b - a) empty). Small integer lattices make
// coplanar faces, shared vertices and edges, repeated points and touching hulls the normal case;
// the hulls' cores (the capsule test) are given well, badly (outside the hull, on a vertex) or
// not at all, which must not change the union.
#include "bsp/merge/convex_union.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/hull.hpp"
#include "bsp/set_operations.hpp"
#include "kernel/grid.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using bsp::detail::HullCore;
using bsp::detail::unite_convex_hulls;
using kernel::GridPoint;

const kernel::Grid kGrid;
constexpr std::int64_t kScale = 4096;  // lattice step in grid units (1/8 world unit)

Solid reference_union(const std::vector<std::vector<GridPoint>>& sets) {
  std::vector<Solid> parts;
  for (const auto& set : sets) {
    std::vector<Eigen::Vector3d> world;
    for (const GridPoint& p : set) world.push_back(kGrid.to_world(p));
    parts.push_back(hull(world, kGrid));
  }
  return unite_all(std::move(parts));
}

void expect_same_set(const Solid& a, const Solid& b, const std::string& what) {
  EXPECT_TRUE((a - b).is_empty()) << what;
  EXPECT_TRUE((b - a).is_empty()) << what;
  EXPECT_NEAR(volume(a), volume(b), 1e-9 * (1 + volume(b))) << what;
  // Hulls touching along an edge make a non-manifold edge of the set itself: checked where the
  // reference's surface has none.
  if (!a.is_empty() && checks::EdgesManifoldAndOriented(to_mesh(b))) {
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(a))) << what;
  }
}

/// Cores for the sets: 0 the centroid of the points to the first point (inside or on the hull),
/// 1 far outside every hull, 2 a segment between two of the set's points (on the boundary or
/// inside).
std::vector<HullCore> cores_for(const std::vector<std::vector<GridPoint>>& sets, int kind) {
  std::vector<HullCore> cores;
  for (const auto& set : sets) {
    HullCore c;
    std::array<double, 3> centroid{0, 0, 0};
    for (const GridPoint& p : set) centroid[0] += double(p.x), centroid[1] += double(p.y), centroid[2] += double(p.z);
    for (double& x : centroid) x /= double(set.size());
    const GridPoint& f = set.front();
    const GridPoint& l = set.back();
    if (kind == 0) c.ends[0] = centroid, c.ends[1] = {double(f.x), double(f.y), double(f.z)};
    if (kind == 1) c.ends[0] = {-1e6, 2e6, 0}, c.ends[1] = {-1e6, 2e6, 5};
    if (kind == 2) c.ends[0] = {double(f.x), double(f.y), double(f.z)}, c.ends[1] = {double(l.x), double(l.y), double(l.z)};
    cores.push_back(c);
  }
  return cores;
}

TEST(ConvexUnion, RandomLatticeHullsEqualTheUnionOfHullSolids) {
  std::mt19937 rng(17);
  int compared = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int count = 2 + trial % 5;
    const int side = 1 + trial % 3;  // coordinates in [0, side] + offset: many coplanar points
    std::uniform_int_distribution<int> coord(0, side), offset(0, 2), size(4, 12);
    std::vector<std::vector<GridPoint>> sets;
    for (int s = 0; s < count; ++s) {
      const int ox = offset(rng), oy = offset(rng), oz = offset(rng);
      std::vector<GridPoint> set;
      const int n = size(rng);
      for (int i = 0; i < n; ++i)
        set.push_back({(ox + coord(rng)) * kScale, (oy + coord(rng)) * kScale, (oz + coord(rng)) * kScale});
      sets.push_back(std::move(set));
    }
    const Solid reference = reference_union(sets);
    const std::string what = "trial " + std::to_string(trial);
    expect_same_set(unite_convex_hulls(sets, kGrid), reference, what);
    for (int kind = 0; kind < 3; ++kind) {
      const std::vector<HullCore> cores = cores_for(sets, kind);
      expect_same_set(unite_convex_hulls(sets, kGrid, {.cores = cores}), reference, what + " cores " + std::to_string(kind));
    }
    ++compared;
  }
  EXPECT_EQ(compared, 40);
}

TEST(ConvexUnion, SharedAndRepeatedHulls) {
  auto cube = [](std::int64_t x, std::int64_t y, std::int64_t z, std::int64_t e) {
    std::vector<GridPoint> c;
    for (int i = 0; i < 8; ++i) c.push_back({(x + (i & 1) * e) * kScale, (y + (i >> 1 & 1) * e) * kScale, (z + (i >> 2 & 1) * e) * kScale});
    return c;
  };
  // The same cube twice (coincident faces of equal orientation), two cubes touching face to face
  // (opposite orientation), one cube inside another sharing a corner, edge-adjacent cubes, and a
  // flat set (no volume) among them.
  const std::vector<std::vector<std::vector<GridPoint>>> cases{
      {cube(0, 0, 0, 2), cube(0, 0, 0, 2)},
      {cube(0, 0, 0, 2), cube(2, 0, 0, 2)},
      {cube(0, 0, 0, 4), cube(0, 0, 0, 2), cube(2, 2, 2, 2)},
      {cube(0, 0, 0, 2), cube(2, 2, 0, 2), cube(1, 1, 1, 2)},
      {cube(0, 0, 0, 2), {{0, 0, 8 * kScale}, {kScale, 0, 8 * kScale}, {0, kScale, 8 * kScale}}},
  };
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Solid reference = reference_union(cases[c]);
    expect_same_set(unite_convex_hulls(cases[c], kGrid), reference, "case " + std::to_string(c));
    expect_same_set(unite_convex_hulls(cases[c], kGrid, {.cores = cores_for(cases[c], 0)}), reference,
                    "case " + std::to_string(c) + " cores");
  }
  const std::vector<HullCore> one = cores_for({cases[0][0]}, 0);  // one core for two sets
  EXPECT_THROW(unite_convex_hulls(cases[0], kGrid, {.cores = one}), std::invalid_argument);
}

}  // namespace
}  // namespace sculpt
