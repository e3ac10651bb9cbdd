#pragma once
/// \file face_triangulation.hpp
/// Internal: ear clipping of one simple planar polygon (possibly non-convex, possibly with
/// collinear vertices) into triangles of positive area, counter-clockwise about `normal`.

#include <Eigen/Core>
#include <array>
#include <vector>

namespace sculpt::detail {

std::vector<std::array<int, 3>> triangulate_face(const std::vector<Eigen::Vector3d>& points,
                                                 const std::vector<int>& face, const Eigen::Vector3d& normal);

}  // namespace sculpt::detail
