#pragma once
/// \file edges.hpp
/// The lines of pictures (picture.hpp), found in image space from the z-buffer's face ids: where
/// two neighbouring pixels show different faces, a line is drawn on the nearer of the two if the
/// faces belong to different solids or to nothing (silhouettes), if the surface is not
/// continuous between the two pixel centres (occlusion boundaries), or if it is and the faces meet
/// at more than the threshold angle (feature edges).
///
/// Continuity is decided from the faces' depth planes, not from the mesh's topology: faces that
/// meet along an edge between the two centres differ in depth at the midpoint by at most half the
/// difference of their slopes (the depth difference is linear along the segment and zero where
/// the edge crosses it). So coplanar pieces of one face that meet at T-junctions (a carved block's
/// top, made of hundreds of pieces) draw no line, and neither do neighbouring pixels of a fine
/// curved mesh that show faces two triangles apart (the specks of the old topological test).

#include <Eigen/Core>
#include <vector>

#include "render/detail/rasterizer.hpp"

namespace sculpt::render::detail {

struct FaceInfo {
  int solid = 0;           ///< the mesh (solid) it belongs to
  int face = 0;            ///< its index in that mesh's faces
  Eigen::Vector3d normal;  ///< unit outward normal
  /// Its depth plane on screen, depth(x, y) = dx x + dy y + d0 (as ScreenPolygon's).
  double dx = 0, dy = 0, d0 = 0;
  /// Smooth shading only (smooth_normals.hpp): its corners on screen and their normals.
  std::vector<Eigen::Vector2d> corners{};
  std::vector<Eigen::Vector3d> corner_normals{};
};

/// Per pixel: true where a line goes. `cos_threshold`: the cosine of the threshold angle;
/// `depth_slack`: depth gaps up to this (world units: about a pixel's length) count as continuous;
/// a group of crease pixels smaller than `least_crease` that touches no outline is a speck (a
/// sliver of a fine mesh whose normal turns away) and is dropped.
std::vector<bool> edge_pixels(const DepthBuffer& buffer, const std::vector<FaceInfo>& faces, double cos_threshold,
                              double depth_slack, int least_crease);

/// The lines widened to `width` pixels (each line pixel becomes a width x width square around
/// it), kept to covered pixels.
std::vector<bool> widen_lines(const DepthBuffer& buffer, const std::vector<bool>& lines, int width);

}  // namespace sculpt::render::detail
