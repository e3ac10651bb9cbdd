#pragma once
/// \file smooth_normals.hpp
/// Smooth shading of pictures (picture.hpp, PictureOptions::smooth): the normal at each corner of
/// each face is the mean of the normals of the faces around that corner's vertex that meet the
/// face at no more than the crease angle, weighted by their angles at the vertex (Thürmer &
/// Wüthrich's angle-weighted vertex normals), so a curved surface made of flat faces shades as
/// curved while its creases stay sharp. Inside a face the normal is interpolated from its corners
/// (screen-space barycentric coordinates in the face's fan of triangles).

#include <vector>

#include <Eigen/Core>

#include "mesh/polygon_mesh.hpp"

namespace sculpt::render::detail {

/// For each face of `mesh`, the unit normal at each of its corners (in the face's order): faces
/// whose normals differ from the face's by at most `crease_degrees` are averaged, weighted by
/// their angle at the vertex. A degenerate face gets its neighbours' mean, or nothing.
std::vector<std::vector<Eigen::Vector3d>> corner_normals(const PolygonMesh& mesh, double crease_degrees);

/// The normal at screen point `p` inside the face with screen corners `corners` and corner
/// normals `normals`, interpolated in the fan triangle (0, k, k + 1) that holds p (the nearest one
/// where p lies in none, as at a non-convex face's notch), normalized.
Eigen::Vector3d interpolated_normal(const std::vector<Eigen::Vector2d>& corners,
                                    const std::vector<Eigen::Vector3d>& normals, const Eigen::Vector2d& p);

}  // namespace sculpt::render::detail
