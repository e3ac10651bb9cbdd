#include "render/camera.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "base/errors.hpp"

namespace sculpt::render {

Eigen::Vector3d view_direction(const std::string& name) {
  static const std::array<std::pair<const char*, Eigen::Vector3d>, 7> kViews = {{
      {"iso", {1, -1, 1}},
      {"front", {0, -1, 0}},
      {"back", {0, 1, 0}},
      {"left", {-1, 0, 0}},
      {"right", {1, 0, 0}},
      {"top", {0, 0, 1}},
      {"bottom", {0, 0, -1}},
  }};
  for (const auto& [n, v] : kViews)
    if (name == n) return v;
  throw InvalidInput("unknown view '" + name + "' (views: iso, front, back, left, right, top, bottom, or a direction [x, y, z])");
}

Camera orient_camera(const Eigen::Vector3d& toward) {
  const double length = toward.norm();
  if (!toward.allFinite() || !(length > 0)) throw InvalidInput("the view direction must be a nonzero finite vector");
  Camera camera;
  camera.toward = toward / length;
  const Eigen::Vector3d z(0, 0, 1);
  Eigen::Vector3d up = z - z.dot(camera.toward) * camera.toward;
  // Within about 0.06 degrees of the z axis, +z gives no usable "up": use +y.
  if (up.norm() < 1e-3) up = Eigen::Vector3d(0, 1, 0) - camera.toward.y() * camera.toward;
  camera.up = up.normalized();
  camera.right = camera.up.cross(camera.toward).normalized();
  return camera;
}

void frame_points(Camera& camera, const std::vector<Eigen::Vector3d>& points, double margin) {
  if (points.empty()) {
    camera.center = Eigen::Vector3d::Zero();
    camera.scale = 1;
    return;
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  double x0 = inf, x1 = -inf, y0 = inf, y1 = -inf, d0 = inf, d1 = -inf;
  for (const Eigen::Vector3d& p : points) {
    const double x = p.dot(camera.right), y = p.dot(camera.up), d = p.dot(camera.toward);
    x0 = std::min(x0, x), x1 = std::max(x1, x);
    y0 = std::min(y0, y), y1 = std::max(y1, y);
    d0 = std::min(d0, d), d1 = std::max(d1, d);
  }
  camera.center = 0.5 * (x0 + x1) * camera.right + 0.5 * (y0 + y1) * camera.up + 0.5 * (d0 + d1) * camera.toward;
  const double usable = std::max(0.0, 1 - 2 * margin);
  const double sx = x1 > x0 ? usable * camera.width / (x1 - x0) : inf;
  const double sy = y1 > y0 ? usable * camera.height / (y1 - y0) : inf;
  const double s = std::min(sx, sy);
  if (std::isfinite(s) && s > 0) camera.scale = s;
}

}  // namespace sculpt::render
