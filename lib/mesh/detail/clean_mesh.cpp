#include "mesh/detail/clean_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include "base/cancel.hpp"
#include "base/dispose.hpp"

#include "mesh/predicates.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt::mesh::detail {
namespace {

using Eigen::Vector3d;

/// Cells of the triangles' index: about the mean edge length of the faces' corners.
double index_cell(const PolygonMesh& mesh) {
  double total = 0;
  size_t edges = 0;
  for (const auto& f : mesh.faces)
    for (size_t k = 0; k < f.size(); ++k, ++edges)
      total += (mesh.vertices[f[k]] - mesh.vertices[f[(k + 1) % f.size()]]).norm();
  return edges > 0 && total > 0 ? 2 * total / static_cast<double>(edges) : 1.0;
}

}  // namespace

double Rounder::resolution(const std::vector<Vector3d>& points) const {
  if (precision == OutputPrecision::Grid) return step;
  double m = std::numeric_limits<double>::min();
  for (const Vector3d& q : points) m = std::max(m, q.cwiseAbs().maxCoeff());
  const int digits = precision == OutputPrecision::Double ? 53 : 24;
  const double ulp = std::ldexp(1.0, std::ilogb(m) + 1 - digits);
  return precision == OutputPrecision::ThreeMf ? std::max(ulp, 1e-6) : ulp;
}

CleanMesh::CleanMesh(const PolygonMesh& mesh, const Rounder& rounder, CleanLimits limits_given)
    : round(rounder), resolution(rounder.resolution(mesh.vertices)), limits(limits_given), index(index_cell(mesh)) {
  p.reserve(mesh.vertices.size());
  members.resize(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    p.push_back(round(mesh.vertices[i]));
    members[i].push_back(mesh.vertices[i]);
  }
  incident.resize(p.size());
  // Room for every triangle and some edits at once: a vector of millions of prepared triangles
  // that doubles copies a gigabyte between two Ctrl-C checks (issue 35).
  std::size_t count = 0;
  for (const auto& f : mesh.faces) count += f.size() >= 2 ? f.size() - 2 : 0;
  count += count / 16 + 64;
  tris.reserve(count);
  alive.reserve(count);
  boxes.reserve(count);
  prepared.reserve(count);
  index.reserve(count);
  // Every face as n - 2 triangles: ear clipping of the rounded corners where it covers the face;
  // else of the given corners (rounding can make two corners one point, and a polygon with a
  // hole bridged to its rim then no longer simple; the given face is, and what rounding folds of
  // its triangles the sweeps repair); else a fan (a face of zero area keeps its edges; its
  // zero-area triangles are removed by the sweeps).
  CancelPoll poll;
  try {
    for (const auto& f : mesh.faces) {
      poll.tick();  // Ctrl-C (base/cancel.hpp)
      std::vector<IndexTriangle> face_tris = triangulate_polygon(p, f);
      if (face_tris.size() + 2 != f.size()) face_tris = triangulate_polygon(mesh.vertices, f);
      if (face_tris.size() + 2 != f.size()) {
        face_tris.clear();
        for (size_t k = 1; k + 1 < f.size(); ++k) face_tris.push_back({f[0], f[k], f[k + 1]});
      }
      for (const IndexTriangle& t : face_tris) add_triangle(t);
    }
  } catch (const Cancelled&) {
    // Millions of small blocks (the index's cells, the incidences) freed on another thread
    // (base/dispose.hpp), so that the stop answers at once.
    dispose_in_background(std::make_tuple(std::move(index), std::move(incident), std::move(members), std::move(tris),
                                          std::move(prepared), std::move(boxes)));
    throw;
  }
  settled = true;
}

void CleanMesh::add_triangle(const Tri& t) {
  const int id = static_cast<int>(tris.size());
  tris.push_back(t);
  alive.push_back(true);
  boxes.emplace_back();
  prepared.emplace_back();
  update_box(id);
  for (int v : t) incident[size_t(v)].push_back(id);
}

void CleanMesh::kill_triangle(int t) {
  alive[size_t(t)] = false;
  index.erase(t, boxes[size_t(t)]);
  for (int v : tris[size_t(t)]) std::erase(incident[size_t(v)], t);
}

void CleanMesh::rewrite_triangle(int t, const Tri& after) {
  for (int w : tris[size_t(t)]) std::erase(incident[size_t(w)], t);
  tris[size_t(t)] = after;
  for (int w : tris[size_t(t)]) incident[size_t(w)].push_back(t);
  update_box(t);
}

void CleanMesh::update_box(int t) {
  if (dirty.size() < tris.size()) dirty.resize(tris.size(), 0);
  dirty[size_t(t)] = settled ? 1 : 0;
  if (!boxes[size_t(t)].isEmpty()) index.erase(t, boxes[size_t(t)]);
  Eigen::AlignedBox3d box;
  for (int v : tris[size_t(t)]) box.extend(p[size_t(v)]);
  boxes[size_t(t)] = box;
  index.insert(t, box);
  const Tri& c = tris[size_t(t)];
  prepared[size_t(t)] = prepare_triangle(c, {p[size_t(c[0])], p[size_t(c[1])], p[size_t(c[2])]});
}

void CleanMesh::move_vertex(int v, const Vector3d& target) {
  p[size_t(v)] = target;
  for (int t : incident[size_t(v)]) update_box(t);
}

void CleanMesh::merge_vertex(int v, int target) {
  incident[size_t(v)].clear();
  members[size_t(target)].insert(members[size_t(target)].end(), members[size_t(v)].begin(), members[size_t(v)].end());
  members[size_t(v)].clear();
}

std::set<int> CleanMesh::neighbours(int v) const {
  std::set<int> n;
  for (int t : incident[size_t(v)])
    for (int w : tris[size_t(t)])
      if (w != v) n.insert(w);
  return n;
}

double CleanMesh::spread(int u, int v, const Vector3d& target) const {
  double m = 0;
  for (int w : {u, v})
    for (const Vector3d& q : members[size_t(w)]) m = std::max(m, (q - target).norm());
  return m;
}

bool CleanMesh::sliver(const Tri& t, double delta) const {
  double longest = 0;
  for (int k = 0; k < 3; ++k) longest = std::max(longest, (p[t[(k + 1) % 3]] - p[t[k]]).norm());
  return normal(t).norm() < delta * longest;
}

size_t CleanMesh::live_triangles() const { return static_cast<size_t>(std::count(alive.begin(), alive.end(), true)); }

PolygonMesh CleanMesh::mesh() const {
  PolygonMesh out;
  std::vector<int> at(p.size(), -1);
  for (size_t t = 0; t < tris.size(); ++t)
    if (alive[t])
      for (int v : tris[t]) at[size_t(v)] = 0;
  for (size_t v = 0; v < p.size(); ++v)
    if (at[v] == 0) {
      at[v] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(p[v]);
    }
  for (size_t t = 0; t < tris.size(); ++t)
    if (alive[t]) out.faces.push_back({at[size_t(tris[t][0])], at[size_t(tris[t][1])], at[size_t(tris[t][2])]});
  return out;
}

double CleanMesh::max_move() const {
  double m = 0;
  for (size_t v = 0; v < p.size(); ++v)
    if (vertex_alive(static_cast<int>(v)))
      for (const Vector3d& q : members[v]) m = std::max(m, (q - p[v]).norm());
  return m;
}

}  // namespace sculpt::mesh::detail
