#pragma once
/// \file polygon_offset.hpp
/// Offsets of simple polygons (the 2D `offset` of OpenSCAD and Clipper) with round or miter
/// joins, decided exactly by the solids' set operations instead of by cleaning a raw offset
/// curve. The offset of polygon P by r > 0 is the set of points within r of P, P + D_r
/// (Minkowski sum with the disk); it is the union of P, of the rectangle of width r on the outer
/// side of every edge, and of the wedge of the disk between the two edge normals at every convex
/// vertex (a point outside P within r of it has its nearest point of P inside an edge, then it
/// lies in that edge's rectangle, or at a convex vertex, then in that vertex's wedge). The inward
/// offset by -r is the complement's outward offset: P minus the inner rectangles and the wedges
/// at reflex vertices. With round joins a wedge is the circle's sector as a polygon of arcs of
/// `segments` per full turn whose ends lie on the edge normals; with miter joins it is the corner
/// where the two offset edges meet, cut off square where it lies farther than miter_limit * r
/// from the vertex.
///
/// Each piece is a convex slab (bsp/hull.hpp) over its snapped corners, the polygon a prism
/// (bsp/extrude.hpp); the union (and difference) are the exact set operations, and the result's
/// outline is read off the top face of the solid's boundary (its exact vertices, rounded). So
/// concave corners, offsets larger than a notch, an inward offset that splits the polygon or
/// lets it vanish are all decided exactly, with no self-intersecting intermediate curve.

#include <Eigen/Core>
#include <vector>

#include "kernel/grid.hpp"

namespace sculpt {

/// How offset edges meet at a corner that opens up.
enum class OffsetJoin {
  Round,  ///< an arc (polygon) around the vertex
  Miter,  ///< the offset edges extended until they meet, cut off beyond miter_limit
};

struct PolygonOffsetOptions {
  OffsetJoin join = OffsetJoin::Round;
  /// Round joins: edges per full turn, as for circles (a corner turning by angle a gets
  /// ceil(segments * a / 360 degrees) edges, at least 1).
  int segments = 32;
  /// Miter joins: the largest distance of the corner from its vertex, in multiples of |r| (>= 1);
  /// beyond it the corner is cut by the line across the bisector at that distance. 2 (Clipper's
  /// default) keeps the full corner for turns up to 120 degrees (a square's corners).
  double miter_limit = 2.0;
  /// The grid the polygon and the pieces are snapped to (docs/kernel.md, "World range").
  kernel::Grid grid{};
};

/// The boundary loops of the offset of `polygon` (x, y; simple, either orientation, a repeated
/// closing point dropped) by `distance`: outwards for distance > 0, inwards for < 0. Outer loops
/// are counter-clockwise, holes clockwise, outer loops first; collinear vertices are left out.
/// An inward offset that lets the polygon vanish gives no loops; an offset that splits it gives
/// several. Distance 0 gives the snapped polygon.
/// \throw InvalidInput for fewer than 3 distinct points, zero area, a non-finite distance,
/// segments < 3 or miter_limit < 1; GeometryError if the polygon crosses or touches itself.
std::vector<std::vector<Eigen::Vector2d>> offset_polygon(const std::vector<Eigen::Vector2d>& polygon, double distance,
                                                         const PolygonOffsetOptions& options = {});

}  // namespace sculpt
