#include "render/detail/smooth_normals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sculpt::render::detail {

std::vector<std::vector<Eigen::Vector3d>> corner_normals(const PolygonMesh& mesh, double crease_degrees) {
  const std::size_t faces = mesh.faces.size();
  // Each face's unit normal (Newell) and its angle at each corner.
  std::vector<Eigen::Vector3d> normal(faces, Eigen::Vector3d::Zero());
  std::vector<std::vector<double>> angle(faces);
  std::vector<std::vector<std::size_t>> around(mesh.vertices.size());  // faces at each vertex
  for (std::size_t f = 0; f < faces; ++f) {
    const auto& face = mesh.faces[f];
    const std::size_t k = face.size();
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < k; ++i) {
      const Eigen::Vector3d& p = mesh.vertices[static_cast<std::size_t>(face[i])];
      const Eigen::Vector3d& q = mesh.vertices[static_cast<std::size_t>(face[(i + 1) % k])];
      n += p.cross(q);
    }
    if (n.norm() > 0) normal[f] = n.normalized();
    angle[f].resize(k);
    for (std::size_t i = 0; i < k; ++i) {
      const Eigen::Vector3d& v = mesh.vertices[static_cast<std::size_t>(face[i])];
      const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(face[(i + k - 1) % k])] - v;
      const Eigen::Vector3d b = mesh.vertices[static_cast<std::size_t>(face[(i + 1) % k])] - v;
      const double na = a.norm(), nb = b.norm();
      angle[f][i] = na > 0 && nb > 0 ? std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0)) : 0.0;
      around[static_cast<std::size_t>(face[i])].push_back(f);
    }
  }
  const double cos_crease = std::cos(crease_degrees * std::numbers::pi / 180);
  std::vector<std::vector<Eigen::Vector3d>> out(faces);
  for (std::size_t f = 0; f < faces; ++f) {
    const auto& face = mesh.faces[f];
    out[f].resize(face.size(), normal[f]);
    for (std::size_t i = 0; i < face.size(); ++i) {
      const auto v = static_cast<std::size_t>(face[i]);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (std::size_t g : around[v]) {
        if (normal[g].dot(normal[f]) < cos_crease && g != f) continue;
        const auto& other = mesh.faces[g];
        const auto at = std::find(other.begin(), other.end(), face[i]) - other.begin();
        sum += angle[g][static_cast<std::size_t>(at)] * normal[g];
      }
      if (sum.norm() > 0) out[f][i] = sum.normalized();
    }
  }
  return out;
}

Eigen::Vector3d interpolated_normal(const std::vector<Eigen::Vector2d>& corners,
                                    const std::vector<Eigen::Vector3d>& normals, const Eigen::Vector2d& p) {
  // The fan triangle whose smallest barycentric coordinate at p is largest: the one holding p.
  double best = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d result = normals.front();
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    const Eigen::Vector2d &a = corners[0], &b = corners[k], &c = corners[k + 1];
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (area == 0) continue;
    const double wb = ((p - a).x() * (c - a).y() - (p - a).y() * (c - a).x()) / area;
    const double wc = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / area;
    const double wa = 1 - wb - wc;
    const double least = std::min({wa, wb, wc});
    if (least > best) {
      best = least;
      result = wa * normals[0] + wb * normals[k] + wc * normals[k + 1];
    }
  }
  const double length = result.norm();
  return length > 0 ? Eigen::Vector3d(result / length) : normals.front();
}

}  // namespace sculpt::render::detail
