#pragma once
/// \file convex_hull.hpp
/// Exact convex hull of grid points (Barber, Dobkin & Huhdanpaa's Quickhull, 1996), every
/// orientation decided exactly in integers: grid coordinates have kCoordBits bits, so a face's
/// normal fits 64 bits and a point's signed distance to it 128 bits. Coplanar and repeated points
/// are the normal case: a point on a face's plane is not outside it, so it never becomes a vertex
/// unless it is a corner of the hull, and coplanar triangles are left for the caller to merge
/// (their planes, normalized, are equal).

#include <array>
#include <span>
#include <vector>

#include "kernel/grid.hpp"

namespace sculpt::kernel {

struct ConvexHull {
  /// 3 for a solid hull; 0, 1 or 2 when every point lies on one point, line or plane (then
  /// `vertices` and `triangles` are empty: such a hull has no volume).
  int dimension = 0;
  std::vector<GridPoint> vertices;                ///< the hull's corners (a subset of the input)
  std::vector<std::array<int, 3>> triangles;      ///< counter-clockwise seen from outside
  /// neighbours[t][k]: the triangle across the edge from triangles[t][k] to triangles[t][(k + 1) % 3]
  /// (the hull is closed: every edge has one).
  std::vector<std::array<int, 3>> neighbours;
};

/// The convex hull of `points` (grid units). Runs in O(n log n) expected time; no recursion.
ConvexHull convex_hull(std::span<const GridPoint> points);

}  // namespace sculpt::kernel
