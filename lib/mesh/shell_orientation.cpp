#include "mesh/shell_orientation.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "mesh/edge_incidence.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/predicates.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt {
namespace {

using Triangle = std::array<Eigen::Vector3d, 3>;

/// Crossings of the segment p-q with triangle t: 0 or 1, or -1 when q lies in the triangle's
/// plane or the segment passes through an edge or corner (then another q is tried).
/// p is known to lie off the triangle (the shells do not intersect).
int crossing(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Triangle& t) {
  const int sq = orient3d(t[0], t[1], t[2], q);
  if (sq == 0) return -1;
  const int sp = orient3d(t[0], t[1], t[2], p);
  if (sp == 0 || sp == sq) return 0;  // p in the plane but off the triangle, or both on one side
  const int e0 = orient3d(p, q, t[0], t[1]);
  const int e1 = orient3d(p, q, t[1], t[2]);
  const int e2 = orient3d(p, q, t[2], t[0]);
  if (e0 == 0 || e1 == 0 || e2 == 0) return -1;
  return (e0 == e1 && e1 == e2) ? 1 : 0;
}

/// Is p inside the closed surface made of `triangles` (bounded by `box`; `boxes` the triangles'
/// boxes)? Ray parity (the same for every ray that meets no edge, corner or plane degenerately):
/// first along +x, where only triangles whose boxes hold p's y and z and reach p's x can be met
/// (exact comparisons skip the others), then along directions from a fixed sequence until one
/// meets nothing degenerately.
bool inside(const Eigen::Vector3d& p, const std::vector<Triangle>& triangles,
            const std::vector<Eigen::AlignedBox3d>& boxes, const Eigen::AlignedBox3d& box) {
  const double reach = 2 * (box.diagonal().norm() + (p - box.center()).norm()) + 1;
  {
    Eigen::Vector3d q = p;
    q.x() += reach;
    if (std::isfinite(q.x()) && q.x() > box.max().x()) {  // the segment leaves the surface's box
      int parity = 0;
      bool degenerate = false;
      for (size_t i = 0; i < triangles.size() && !degenerate; ++i) {
        const Eigen::AlignedBox3d& b = boxes[i];
        if (b.max().x() < p.x() || b.min().y() > p.y() || b.max().y() < p.y() || b.min().z() > p.z() ||
            b.max().z() < p.z())
          continue;  // no point of the triangle on the segment (constant y and z, x from p.x)
        const int c = crossing(p, q, triangles[i]);
        if (c < 0) degenerate = true;
        else parity ^= c;
      }
      if (!degenerate) return parity == 1;
    }
  }
  for (int attempt = 1; attempt <= 64; ++attempt) {
    // Golden-ratio sequence of directions: no two alike, none along an axis.
    const double a = std::fmod(0.6180339887498949 * attempt, 1.0) * 2 * M_PI;
    const double z = std::fmod(0.7548776662466927 * attempt, 1.0) * 1.8 - 0.9;
    const double r = std::sqrt(1 - z * z);
    const Eigen::Vector3d q = p + reach * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), z);
    int parity = 0;
    bool degenerate = false;
    for (const Triangle& t : triangles) {
      const int c = crossing(p, q, t);
      if (c < 0) { degenerate = true; break; }
      parity ^= c;
    }
    if (!degenerate) return parity == 1;
  }
  return false;  // 64 degenerate rays in a row cannot happen for a valid mesh; count p as outside
}

}  // namespace

std::vector<ShellOrientation> shell_orientations(const PolygonMesh& mesh) {
  check_face_indices(mesh, "shell_orientations");
  const std::vector<int> component = face_components(mesh);
  int count = 0;
  for (int c : component) count = std::max(count, c + 1);
  std::vector<ShellOrientation> shells(count);
  for (size_t f = 0; f < component.size(); ++f) shells[component[f]].faces.push_back(static_cast<int>(f));

  // Each shell as a mesh of its own (vertices renumbered), for its volume, box and triangles.
  std::vector<PolygonMesh> parts(count);
  std::vector<int> local(mesh.vertices.size(), -1), owner(mesh.vertices.size(), -1);
  for (int s = 0; s < count; ++s)
    for (int f : shells[s].faces) {
      std::vector<int> face;
      for (int v : mesh.faces[f]) {
        if (owner[v] != s) {  // shells share no vertex (they are components), but be safe
          owner[v] = s;
          local[v] = static_cast<int>(parts[s].vertices.size());
          parts[s].vertices.push_back(mesh.vertices[v]);
        }
        face.push_back(local[v]);
      }
      parts[s].faces.push_back(std::move(face));
    }
  std::vector<Eigen::AlignedBox3d> boxes(count);
  for (int s = 0; s < count; ++s) {
    shells[s].signed_volume = mesh_volume(parts[s]);
    boxes[s] = mesh_bounding_box(parts[s]);
  }
  if (count < 2) return shells;

  for (int outer = 0; outer < count; ++outer) {
    std::vector<Triangle> triangles;  // built only if some shell may lie inside this one
    std::vector<Eigen::AlignedBox3d> triangle_boxes;
    for (int inner = 0; inner < count; ++inner) {
      if (inner == outer || !boxes[outer].contains(boxes[inner])) continue;
      if (triangles.empty())
        for (const auto& face : parts[outer].faces)
          for (const IndexTriangle& t : triangulate_polygon(parts[outer].vertices, face)) {
            triangles.push_back({parts[outer].vertices[t[0]], parts[outer].vertices[t[1]], parts[outer].vertices[t[2]]});
            Eigen::AlignedBox3d b;
            for (const Eigen::Vector3d& corner : triangles.back()) b.extend(corner);
            triangle_boxes.push_back(b);
          }
      const Eigen::Vector3d& p = parts[inner].vertices.front();
      if (inside(p, triangles, triangle_boxes, boxes[outer])) ++shells[inner].enclosing_shells;
    }
  }
  return shells;
}

}  // namespace sculpt
