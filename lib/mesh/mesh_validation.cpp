#include "mesh/mesh_validation.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <numeric>

#include <Eigen/Geometry>

#include "base/checked_growth.hpp"
#include "base/errors.hpp"
#include "mesh/edge_incidence.hpp"
#include "mesh/predicates.hpp"
#include "mesh/self_intersection.hpp"
#include "mesh/shell_orientation.hpp"

namespace sculpt {
namespace {

std::string number(double x) {
  char buf[32];
  auto res = std::to_chars(buf, buf + sizeof buf, x);  // shortest text that reads back exactly
  return std::string(buf, res.ptr);
}

std::string point(const PolygonMesh& m, int v) {
  const Eigen::Vector3d& p = m.vertices[v];
  std::string s = "(";
  s += number(p.x());
  s += ", ";
  s += number(p.y());
  s += ", ";
  s += number(p.z());
  s += ")";
  return s;
}

std::string vertex(const PolygonMesh& m, int v) { return "vertex " + std::to_string(v) + " " + point(m, v); }

/// Corners of a face all on one line (exact: every axis projection has zero area).
bool collinear(const PolygonMesh& m, const std::vector<int>& f) {
  const Eigen::Vector3d& a = m.vertices[f[0]];
  for (size_t i = 1; i < f.size(); ++i) {
    const Eigen::Vector3d& b = m.vertices[f[i]];
    if (b == a) continue;
    for (size_t k = i + 1; k < f.size(); ++k) {  // corners before b are at a
      const Eigen::Vector3d& c = m.vertices[f[k]];
      for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        if (orient2d({a[u], a[v]}, {b[u], b[v]}, {c[u], c[v]}) != 0) return false;
      }
    }
    return true;
  }
  return true;  // all corners at one point
}

class Validator {
 public:
  Validator(const PolygonMesh& mesh, ValidationOptions options) : m_(mesh), opt_(options) {}

  ValidationReport run() {
    if (!check_indices() || !check_coordinates()) return std::move(report_);
    check_degenerate_faces();
    if (opt_.check_face_shapes) check_face_shapes();
    check_edges_and_vertices();
    if (opt_.check_self_intersections) check_self_intersections();
    if (opt_.check_shell_orientation && report_.ok()) check_shell_orientation();
    return std::move(report_);
  }

 private:
  void add(DefectKind kind, std::vector<int> faces, std::vector<int> vertices, std::string msg) {
    if (counts_[kind]++ >= opt_.max_defects_per_kind) return;
    report_.defects.push_back({kind, std::move(faces), std::move(vertices), std::move(msg)});
  }

  bool check_indices() {
    const auto n = static_cast<long long>(m_.vertices.size());
    for (size_t fi = 0; fi < m_.faces.size(); ++fi) {
      const auto& f = m_.faces[fi];
      const int id = static_cast<int>(fi);
      if (f.size() < 3)
        add(DefectKind::InvalidIndex, {id}, {},
            "face " + std::to_string(fi) + " has " + std::to_string(f.size()) + " corners");
      for (int v : f)
        if (v < 0 || v >= n)
          add(DefectKind::InvalidIndex, {id}, {v},
              "face " + std::to_string(fi) + " refers to vertex " + std::to_string(v) +
                  " but there are " + std::to_string(n) + " vertices");
    }
    return report_.ok();
  }

  bool check_coordinates() {
    for (size_t v = 0; v < m_.vertices.size(); ++v)
      if (!m_.vertices[v].allFinite())
        add(DefectKind::NonFiniteCoordinate, {}, {static_cast<int>(v)},
            vertex(m_, static_cast<int>(v)) + " has a non-finite coordinate");
    return report_.ok();
  }

  void check_degenerate_faces() {
    for (size_t fi = 0; fi < m_.faces.size(); ++fi) {
      const auto& f = m_.faces[fi];
      sorted_.assign(f.begin(), f.end());
      std::sort(sorted_.begin(), sorted_.end());
      const auto dup = std::adjacent_find(sorted_.begin(), sorted_.end());
      const int id = static_cast<int>(fi);
      if (dup != sorted_.end())
        add(DefectKind::DegenerateFace, {id}, {*dup},
            "face " + std::to_string(fi) + " visits " + vertex(m_, *dup) + " twice");
      else if (collinear(m_, f))
        add(DefectKind::DegenerateFace, {id}, f,
            "face " + std::to_string(fi) + " has zero area (corners collinear), first corner " +
                point(m_, f[0]));
    }
  }

  /// Planarity (relative tolerance) and self-crossing boundaries of faces with > 3 corners.
  void check_face_shapes() {
    for (size_t fi = 0; fi < m_.faces.size(); ++fi) {
      const auto& f = m_.faces[fi];
      if (f.size() <= 3) continue;
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (int v : f) centroid += m_.vertices[v];
      centroid /= static_cast<double>(f.size());
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      double radius = 0;
      for (size_t k = 0; k < f.size(); ++k) {
        const Eigen::Vector3d a = m_.vertices[f[k]] - centroid;
        normal += a.cross(m_.vertices[f[(k + 1) % f.size()]] - centroid);
        radius = std::max(radius, a.norm());
      }
      if (normal.norm() == 0) continue;  // zero area: degenerate, reported above
      normal.normalize();
      int worst = f[0];
      double distance = 0;
      for (int v : f) {
        const double d = std::abs(normal.dot(m_.vertices[v] - centroid));
        if (d > distance) distance = d, worst = v;
      }
      if (distance > opt_.planarity_tolerance * radius)
        add(DefectKind::NonPlanarFace, {static_cast<int>(fi)}, {worst},
            "face " + std::to_string(fi) + " is not planar: " + vertex(m_, worst) + " is " +
                number(distance) + " from its plane (face radius " + number(radius) + ")");
    }
    for (int fi : find_self_crossing_faces(m_, opt_.max_defects_per_kind))
      add(DefectKind::SelfCrossingFace, {fi}, {},
          "the boundary of face " + std::to_string(fi) + " (first corner " + point(m_, m_.faces[fi][0]) +
              ") crosses itself");
  }

  void check_edges_and_vertices() {
    const auto records = sorted_edge_records(m_);
    // Corner ids for the vertex fans: offset[f] + k is corner k of face f. Sized and filled with
    // Ctrl-C checks (base/checked_growth.hpp): hundreds of MB on a large mesh.
    CancelPoll poll;
    std::vector<size_t> offset;
    resize_checked(offset, m_.faces.size() + 1);
    for (size_t f = 0; f < m_.faces.size(); ++f) offset[f + 1] = offset[f] + m_.faces[f].size();
    std::vector<size_t> parent;
    resize_checked(parent, offset.back());
    std::iota(parent.begin(), parent.end(), size_t{0});
    auto find = [&](size_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    auto corner_at = [&](const HalfEdgeRecord& r, int v) {
      const auto& f = m_.faces[r.face];
      const size_t k = (f[r.corner] == v) ? r.corner : (r.corner + 1) % f.size();
      return offset[r.face] + k;
    };

    for (size_t i = 0; i < records.size();) {
      poll.tick();
      size_t j = i;
      while (j < records.size() && records[j].lo == records[i].lo && records[j].hi == records[i].hi)
        ++j;
      const HalfEdgeRecord& r = records[i];
      const bool bad = j - i != 2 || records[i].forward == records[i + 1].forward;
      if (bad) {  // messages only for defects: formatting every edge would dominate the time
        const std::string edge = "edge " + point(m_, r.lo) + " - " + point(m_, r.hi) +
                                 " (vertices " + std::to_string(r.lo) + ", " +
                                 std::to_string(r.hi) + ")";
        std::vector<int> faces;
        for (size_t k = i; k < j; ++k) faces.push_back(records[k].face);
        if (j - i == 1) {
          add(DefectKind::OpenEdge, faces, {r.lo, r.hi},
              "open " + edge + " has only face " + std::to_string(r.face));
        } else if (j - i > 2) {
          add(DefectKind::NonManifoldEdge, faces, {r.lo, r.hi},
              "non-manifold " + edge + " has " + std::to_string(j - i) + " faces");
        } else {
          add(DefectKind::InconsistentOrientation, faces, {r.lo, r.hi},
              "faces " + std::to_string(faces[0]) + " and " + std::to_string(faces[1]) +
                  " run the same way along " + edge);
        }
      }
      for (size_t k = i + 1; k < j; ++k)
        for (int v : {r.lo, r.hi}) parent[find(corner_at(records[k], v))] = find(corner_at(r, v));
      i = j;
    }

    // A manifold vertex has one fan of corners connected through its edges.
    std::vector<long long> root_of_vertex;
    resize_checked(root_of_vertex, m_.vertices.size(), -1LL);
    std::vector<char> reported(m_.vertices.size(), 0);
    for (size_t f = 0; f < m_.faces.size(); ++f) {
      poll.tick();
      for (size_t k = 0; k < m_.faces[f].size(); ++k) {
        const int v = m_.faces[f][k];
        const auto root = static_cast<long long>(find(offset[f] + k));
        if (root_of_vertex[v] < 0) {
          root_of_vertex[v] = root;
        } else if (root_of_vertex[v] != root && !reported[v]) {
          reported[v] = 1;
          add(DefectKind::NonManifoldVertex, {static_cast<int>(f)}, {v},
              "non-manifold " + vertex(m_, v) + ": its faces form more than one fan");
        }
      }
    }
  }

  void check_self_intersections() {
    for (const FacePair& p : find_self_intersections(m_, {.max_pairs = opt_.max_defects_per_kind}))
      add(DefectKind::SelfIntersection, {p.face_a, p.face_b}, {},
          "faces " + std::to_string(p.face_a) + " (first corner " +
              point(m_, m_.faces[p.face_a][0]) + ") and " + std::to_string(p.face_b) +
              " (first corner " + point(m_, m_.faces[p.face_b][0]) + ") intersect");
  }

  void check_shell_orientation() {
    const auto shells = shell_orientations(m_);
    for (size_t s = 0; s < shells.size(); ++s) {
      const ShellOrientation& shell = shells[s];
      if (shell.consistent()) continue;
      const int depth = shell.enclosing_shells;
      std::string where = "shell " + std::to_string(s) + " (" + std::to_string(shell.faces.size()) +
                          " faces, first corner " + point(m_, m_.faces[shell.faces.front()][0]) + ")";
      std::string why = depth % 2 == 0
                            ? "faces inwards (signed volume " + number(shell.signed_volume) + ") but lies inside " +
                                  std::to_string(depth) + " other shells, so it bounds material"
                            : "faces outwards (signed volume " + number(shell.signed_volume) + ") but lies inside " +
                                  std::to_string(depth) + " other shell(s), so it bounds a cavity";
      add(DefectKind::MisorientedShell, shell.faces, {}, where + " " + why + ": reverse the order of its faces' vertices");
    }
  }

  const PolygonMesh& m_;
  ValidationOptions opt_;
  ValidationReport report_;
  std::map<DefectKind, size_t> counts_;
  std::vector<int> sorted_;  ///< check_degenerate_faces: one face's corners, sorted
};

}  // namespace

const char* defect_name(DefectKind kind) {
  switch (kind) {
    case DefectKind::InvalidIndex: return "invalid index";
    case DefectKind::NonFiniteCoordinate: return "non-finite coordinate";
    case DefectKind::DegenerateFace: return "degenerate face";
    case DefectKind::NonPlanarFace: return "non-planar face";
    case DefectKind::SelfCrossingFace: return "self-crossing face";
    case DefectKind::OpenEdge: return "open edge";
    case DefectKind::NonManifoldEdge: return "non-manifold edge";
    case DefectKind::InconsistentOrientation: return "inconsistent orientation";
    case DefectKind::NonManifoldVertex: return "non-manifold vertex";
    case DefectKind::SelfIntersection: return "self-intersection";
    case DefectKind::MisorientedShell: return "misoriented shell";
  }
  return "unknown defect";
}

size_t ValidationReport::count(DefectKind kind) const {
  return static_cast<size_t>(std::count_if(defects.begin(), defects.end(),
                                           [&](const Defect& d) { return d.kind == kind; }));
}

std::string ValidationReport::summary(size_t max_lines) const {
  std::map<DefectKind, size_t> counts;
  for (const Defect& d : defects) ++counts[d.kind];
  std::string s;
  for (auto [kind, n] : counts) {
    if (!s.empty()) s += ", ";
    s += std::string(defect_name(kind)) + ": " + std::to_string(n);
  }
  for (size_t i = 0; i < defects.size() && i < max_lines; ++i) s += "\n  " + defects[i].message;
  if (defects.size() > max_lines)
    s += "\n  ... and " + std::to_string(defects.size() - max_lines) + " more";
  return s;
}

bool indices_and_coordinates_valid(const PolygonMesh& mesh) {
  const auto n = static_cast<long long>(mesh.vertices.size());
  for (const auto& f : mesh.faces) {
    if (f.size() < 3) return false;
    for (const int v : f)
      if (v < 0 || v >= n) return false;
  }
  return std::all_of(mesh.vertices.begin(), mesh.vertices.end(),
                     [](const Eigen::Vector3d& v) { return v.allFinite(); });
}

ValidationReport check_closed_manifold(const PolygonMesh& mesh, ValidationOptions options) {
  return Validator(mesh, options).run();
}

void validate_closed_manifold(const PolygonMesh& mesh, ValidationOptions options) {
  const ValidationReport report = check_closed_manifold(mesh, options);
  if (report.ok()) return;
  std::string message = options.source.empty() ? std::string() : options.source + ": ";
  message += "mesh is not a closed manifold: " + report.summary();
  throw GeometryError(message, SourceLocation{.file = options.source});
}

}  // namespace sculpt
