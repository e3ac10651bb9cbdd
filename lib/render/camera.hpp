#pragma once
/// \file camera.hpp
/// The orthographic camera shared by pictures (picture.hpp) and 3D plots (plot.hpp): a viewing
/// direction, given as a vector or a name, and the screen frame derived from it (z is up).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace sculpt::render {

/// The direction from the scene towards the viewer for a name: "iso" (1, -1, 1), "front"
/// (0, -1, 0), "back", "left" (-1, 0, 0), "right", "top" (0, 0, 1), "bottom". The default
/// picture is "iso": the front, right and top sides are visible.
/// \throw InvalidInput for another name (the message lists the names).
Eigen::Vector3d view_direction(const std::string& name);

/// An orthographic camera: screen x = scale * (p - center) . right + width / 2, screen y =
/// height / 2 - scale * (p - center) . up (pixel rows go down; pixel (i, j) covers
/// [i, i + 1) x [j, j + 1) and is sampled at its centre), depth = (p - center) . toward
/// (larger is nearer the viewer).
struct Camera {
  Eigen::Vector3d toward{0, 0, 1};  ///< unit vector from the scene towards the viewer
  Eigen::Vector3d right{1, 0, 0};   ///< unit screen x
  Eigen::Vector3d up{0, 1, 0};      ///< unit screen y (up on screen)
  Eigen::Vector3d center{0, 0, 0};  ///< world point at the image centre
  double scale = 1;                 ///< pixels per world unit
  int width = 800;
  int height = 600;

  /// Screen position (x, y) and depth of a world point.
  [[nodiscard]] Eigen::Vector3d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = p - center;
    return {0.5 * width + scale * q.dot(right), 0.5 * height - scale * q.dot(up), q.dot(toward)};
  }
};

/// The screen frame for a viewing direction `toward` (normalized here): `up` is the part of +z
/// perpendicular to it and `right` = up x toward; looking along the z axis (toward parallel to
/// z), `up` is +y. Image size, center and scale are left at their defaults.
/// \throw InvalidInput if `toward` is zero or not finite.
Camera orient_camera(const Eigen::Vector3d& toward);

/// Sets center and scale so that the points' projection fills the image up to `margin` (a
/// fraction of each image side, on each side), centred. No points, or a single point, keep a
/// finite scale (1 pixel per unit, resp. the previous one).
void frame_points(Camera& camera, const std::vector<Eigen::Vector3d>& points, double margin = 0.05);

}  // namespace sculpt::render
