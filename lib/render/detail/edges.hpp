#pragma once
/// \file edges.hpp
/// The lines of pictures (picture.hpp), found in image space from the z-buffer's face ids: where
/// two neighbouring pixels show different faces, a line is drawn on the nearer of the two if the
/// faces belong to different solids or to nothing (silhouettes), do not touch (occlusion
/// boundaries), or touch (share a vertex) and meet at more than the threshold angle (feature
/// edges).

#include <Eigen/Core>
#include <vector>

#include "render/detail/rasterizer.hpp"

namespace sculpt::render::detail {

struct FaceInfo {
  int solid = 0;              ///< the mesh (solid) it belongs to
  int face = 0;               ///< its index in that mesh's faces
  Eigen::Vector3d normal;     ///< unit outward normal
  std::vector<int> vertices;  ///< the face's vertex indices in its mesh, sorted
};

/// Per pixel: true where a line goes. `cos_threshold`: the cosine of the threshold angle.
std::vector<bool> edge_pixels(const DepthBuffer& buffer, const std::vector<FaceInfo>& faces, double cos_threshold);

/// The lines widened to `width` pixels (each line pixel becomes a width x width square around
/// it), kept to covered pixels.
std::vector<bool> widen_lines(const DepthBuffer& buffer, const std::vector<bool>& lines, int width);

}  // namespace sculpt::render::detail
