#pragma once
/// \file cell_reach.hpp
/// Internal: whether a convex polygon has a part of positive area in a kd cell, decided from its
/// corner approximations alone where they suffice (local/cell_merge.cpp's step 2 asks this of
/// every fragment in every leaf its box meets; the exact clip to the cell's six walls was a
/// seventh of a real-mesh job).

#include "bsp/local/kd_cells.hpp"
#include "kernel/convex_polygon.hpp"

namespace sculpt::bsp::detail {

/// True only if `poly` certainly has a part of positive area inside the cell `bounds`: a point
/// of the polygon lies strictly inside the cell. The polygon's corner approximations are clipped
/// to the cell in floating point and the centre of what is left is tested, with a margin that
/// covers the approximations' error bounds and the rounding of the clip; a point of the polygon
/// lies within that margin of the centre (the centre is a convex combination of the corners),
/// and a neighbourhood of it in the polygon has positive area. False means undecided (nothing of
/// the polygon in the cell, a sliver near a wall, or a corner without an approximation): the
/// caller clips exactly.
bool certainly_reaches(kernel::PolygonView poly, const CellBounds& bounds);

}  // namespace sculpt::bsp::detail
