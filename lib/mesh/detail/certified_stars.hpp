#pragma once
/// \file certified_stars.hpp
/// Stars of a triangle mesh's vertices certified to be embedded, so that the self-intersection
/// search passes over the pairs of triangles that share such a vertex (docs/mesh_io.md). A star
/// is certified when, projected along one coordinate axis, its triangles' opposite edges form one
/// cycle through distinct vertices, every triangle is oriented alike, and the cycle winds once
/// round the vertex (Sunday's crossing rule for the winding number): all decided with exact signs.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "mesh/detail/triangle_pairs.hpp"

namespace sculpt::mesh::detail {

/// What certified_stars reads of a triangle: its corner ids, its plane's minors (an area vector,
/// used only to choose an axis) and the signs of its projections along each axis where the
/// filter decides them (kUndecided elsewhere).
struct StarTriangle {
  std::array<int, 3> ids{};
  std::array<double, 3> normal{};
  std::array<signed char, 3> sign{};
};

/// t's StarTriangle (the signs by certified_minor).
StarTriangle star_triangle(const PreparedTriangle& t);

/// The link edges a -> b of the triangles v a b round each vertex v, in the vertex's frame (where
/// the sectors turn left: turned round where the vertex's orientation is negative, which
/// `turned` records), as certified_stars finds them.
struct StarLinks {
  struct Link {
    int t, a, b;  // triangle t = v a b, or v b a where turned
  };
  std::vector<int> start;  // vertex v's links are link[start[v]] to link[start[v + 1]]
  std::vector<Link> link;
  std::vector<char> turned;
};

/// certified_stars' answer: per vertex id, whether its star is certified (0 if not, else
/// 1 + 2 axis + (orientation > 0) for the projection that certifies it), and the link edges by
/// vertex (certified_patches reads them).
struct CertifiedStars {
  std::vector<signed char> certified;
  StarLinks links;
};

/// The stars of the vertex ids that no two of their triangles meet beyond the vertex and the edge
/// they share. Certified when, projected along one coordinate axis, the triangles' opposite edges
/// a -> b (in the triangles' order) form one cycle through distinct vertices, every triangle
/// v a b is oriented the same way (strictly), and the cycle winds once round v: the sectors at v
/// then tile the plane round it, two sectors meet only in v or along a common ray v b, and since
/// each triangle projects one to one, the triangles meet only in v or along the edge v b. The
/// winding number of a cycle whose every sector turns left is the number of its edges that cross
/// v's horizontal line upwards (Sunday's crossing rule). `points` are the ids' positions.
CertifiedStars certified_stars(const std::vector<StarTriangle>& tris, const std::vector<Eigen::Vector3d>& points);

}  // namespace sculpt::mesh::detail
