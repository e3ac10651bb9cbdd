#pragma once
/// \file profile_pieces.hpp
/// Closed profiles for revolve(): a simple polygon in the half-plane r >= 0 (holes, overhangs, a
/// hollow wall) split into z-monotone pieces, each of which section 6's construction (Ihm & Naylor
/// 1990) revolves into a balanced tree. In a piece a horizontal line meets the region in one
/// interval [a(z), b(z)]; the piece revolved is revolve(b) minus revolve(a), and the region
/// revolved is the union of its pieces (docs/revolution.md, "Closed profiles").
///
/// Pieces follow the region slab by slab between the polygon's vertex heights: in each slab the
/// region is a row of intervals bounded by polygon edges (a trapezoid each); an interval continues
/// the piece of the interval below it that it overlaps. An edge that crosses several slabs is one
/// line in all of them (RevolveSlab::line_*), so no new profile points are made and every plane of
/// the revolved pieces is written from grid points.

#include <vector>

#include <Eigen/Core>

#include "kernel/grid.hpp"
#include "revolution/trees/revolve_plane_tree.hpp"

namespace sculpt::revolution::detail {

/// A closed profile as revolve() takes it: the points snapped to the grid, a repeated closing
/// point and repeated consecutive points dropped, counter-clockwise in the (r, z) plane.
/// \throw InvalidInput naming the point or the two edges: fewer than 3 distinct points, a
///        non-finite coordinate, r < 0, all points on one line, or edges that cross, touch or
///        run back over each other (not a simple polygon). RangeError (grid.snap) out of range.
std::vector<Eigen::Vector2d> closed_profile(const std::vector<Eigen::Vector2d>& profile, const kernel::Grid& grid);

/// One z-monotone piece: in each of its slabs (contiguous, bottom to top) the region between the
/// inner radius a(z) and the outer radius b(z).
struct ProfilePiece {
  std::vector<RevolveSlab> outer;  ///< b(z)
  std::vector<RevolveSlab> inner;  ///< a(z) in the same slabs; empty if a = 0 throughout (on the axis)
};

/// The z-monotone pieces of a closed profile, bottom to top. \pre polygon is closed_profile's
/// output on `grid` (checked only by assertions).
std::vector<ProfilePiece> monotone_pieces(const std::vector<Eigen::Vector2d>& polygon, const kernel::Grid& grid);

}  // namespace sculpt::revolution::detail
