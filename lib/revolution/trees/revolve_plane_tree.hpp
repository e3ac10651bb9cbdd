#pragma once
/// \file revolve_plane_tree.hpp
/// The balanced BSP tree of a solid of revolution (Ihm & Naylor 1990, section 6), as plain planes:
/// a balanced tree of horizontal planes through the profile's vertices, and in each slab between
/// two consecutive planes the path's tree (path_tree.hpp) lifted to 3D. A line u.q = c of the path's
/// plane becomes, in a slab whose profile radius runs linearly from r0 at z0 to r1 at z1, the plane
/// u.(x, y) = c r(z): a face line gives the plane of a trapezoidal face, a chord line a plane
/// through a non-horizontal edge of a face and the sub-curve's first or last point.
/// revolve.hpp turns this into a Solid; this layer is separate so it can be checked on its own.

#include <vector>

#include <Eigen/Core>

#include "bsp/convex_path.hpp"
#include "revolution/revolve.hpp"
#include "revolution/trees/path_tree.hpp"

namespace sculpt::revolution::detail {

/// A BSP tree of planes. Node plane (a, b, c, d), (a, b, c) a unit vector: a x + b y + c z + d > 0 is
/// the positive side (child `above`; outside the solid for a face plane, higher z for a horizontal
/// one). Children are node indices or kIn / kOut (path_tree.hpp).
struct PlaneTree {
  struct Node {
    Eigen::Vector4d plane;
    int below, above;
    int slab;      ///< -1: the horizontal plane through level `from` (revolve_levels)
    int from, to;  ///< else the path line from vertex `from` to `to`, lifted into slab `slab`
  };
  std::vector<Node> nodes;
  int root = kOut;

  /// kIn or kOut (a point on a plane goes below). Walks without recursion.
  [[nodiscard]] int classify(const Eigen::Vector3d& p) const;
  [[nodiscard]] int height() const;  ///< partitioning nodes on the longest root-to-leaf path
  [[nodiscard]] int leaves() const { return static_cast<int>(nodes.size()) + 1; }
};

/// \throw InvalidInput naming point i of a profile if it is not finite or has r < 0.
void check_profile_point(std::size_t i, const Eigen::Vector2d& p);

/// A profile as revolve() takes it: points (r, z), r >= 0, z monotone (non-decreasing, or
/// non-increasing: then it is reversed). Horizontal runs are allowed (steps, flat caps inside).
/// \throw InvalidInput with the vertex index if it has < 2 points, a non-finite coordinate,
///        r < 0, all z equal, or z that goes up and then down (close it: docs/revolution.md)
std::vector<Eigen::Vector2d> monotone_profile(const std::vector<Eigen::Vector2d>& profile);

/// One slab of the revolved solid: between z0 < z1, profile radius r0 at z0 and r1 at z1.
/// The radius runs along the line of a profile segment, from (r, z) = (line_r0, line_z0) to
/// (line_r1, line_z1), whose ends are the points the exact planes are written with (revolve.cpp):
/// the slab's own ends for a segment of an open profile; for an edge of a closed profile that
/// spans several slabs (profile_pieces.hpp) the whole edge, so each slab of it gets the same planes.
struct RevolveSlab {
  double z0, z1, r0, r1;
  double line_z0 = 0, line_z1 = 0, line_r0 = 0, line_r1 = 0;
};
/// The slab of one profile segment from (r0, z0) to (r1, z1), z0 < z1: its own line.
inline RevolveSlab segment_slab(double z0, double z1, double r0, double r1) { return {z0, z1, r0, r1, z0, z1, r0, r1}; }
/// The slabs of a (valid) profile, bottom to top.
std::vector<RevolveSlab> revolve_slabs(const std::vector<Eigen::Vector2d>& profile);
/// The distinct z levels of a (valid) profile's vertices, increasing: slab k lies between levels k and k + 1.
std::vector<double> revolve_levels(const std::vector<Eigen::Vector2d>& profile);
/// The levels of contiguous slabs (each slab's z1 is the next one's z0): their z0 and the last z1.
std::vector<double> slab_levels(const std::vector<RevolveSlab>& slabs);

/// The plane of the path line from vertex `from` to vertex `to`, lifted into a slab (positive side:
/// the line's right, i.e. outside for a counter-clockwise edge), normalized.
Eigen::Vector4d lifted_plane(const ConvexPath& path, int from, int to, const RevolveSlab& slab);

/// The section 6 tree of profile revolved along path. \throw InvalidInput (see monotone_profile)
PlaneTree revolve_plane_tree(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path,
                             const RevolveOptions& options = {});
/// The same tree for contiguous slabs, bottom to top (a chain of a closed profile's piece): the
/// radius r(z) of the slabs revolved along path. A slab with r0 = r1 = 0 is empty.
/// \pre slabs not empty, contiguous
PlaneTree revolve_slab_tree(const std::vector<RevolveSlab>& slabs, const ConvexPath& path,
                            const RevolveOptions& options = {});

}  // namespace sculpt::revolution::detail
