#include "mesh/triangulate.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "base/errors.hpp"
#include "mesh/predicates.hpp"

namespace sculpt {
namespace {


/// Ear clipping on a doubly linked ring of polygon corners projected to 2D, counter-clockwise.
/// The ring lives in the caller's buffers (PolygonTriangulator), so many faces allocate nothing.
class EarClipper {
 public:
  EarClipper(const std::vector<Eigen::Vector2d>& points, std::span<const int> ids, std::vector<int>& next,
             std::vector<int>& prev, EarOrder order)
      : p_(points), ids_(ids), next_(next), prev_(prev), spread_(order == EarOrder::Spread) {
    const int n = static_cast<int>(p_.size());
    next_.resize(p_.size());
    prev_.resize(p_.size());
    for (int i = 0; i < n; ++i) {
      next_[i] = (i + 1) % n;
      prev_[i] = (i + n - 1) % n;
    }
    remaining_ = n;
    convex_ = n > 8 && strictly_convex();  // a few corners: the containment scans cost less than the test
  }

  void run(std::vector<IndexTriangle>& out) {
    int cur = 0;
    while (remaining_ > 3) {
      int tried = 0;
      while (tried < remaining_ && !is_ear(cur)) {
        cur = next_[cur];
        ++tried;
      }
      if (tried < remaining_) {
        cur = clip(cur, out);
        if (spread_) cur = next_[next_[cur]];  // past the corner that just became the ear's neighbour
        continue;
      }
      // No ear: the rest is degenerate (zero area, spikes) or not simple.
      if (!drop_spike() && !clip_any_convex(out)) return;  // zero-area remainder: dropped
      cur = start_;
    }
    const int a = prev_[cur], b = cur, c = next_[cur];
    if (orient2d(p_[a], p_[b], p_[c]) != 0) out.push_back({ids_[a], ids_[b], ids_[c]});
  }

 private:
  bool same_point(int i, int j) const { return p_[i] == p_[j]; }

  /// Strictly convex corner whose closed triangle holds no other remaining corner
  /// (corners at the same position as one of its three corners excepted).
  bool is_ear(int b) const {
    const int a = prev_[b], c = next_[b];
    if (orient2d(p_[a], p_[b], p_[c]) <= 0) return false;
    if (convex_) return true;  // no corner of a strictly convex polygon lies in another's ear
    for (int q = next_[c]; q != a; q = next_[q]) {
      if (same_point(q, a) || same_point(q, b) || same_point(q, c)) continue;
      if (orient2d(p_[a], p_[b], p_[q]) >= 0 && orient2d(p_[b], p_[c], p_[q]) >= 0 &&
          orient2d(p_[c], p_[a], p_[q]) >= 0)
        return false;
    }
    return true;
  }

  int clip(int b, std::vector<IndexTriangle>& out) {
    const int a = prev_[b], c = next_[b];
    out.push_back({ids_[a], ids_[b], ids_[c]});
    return unlink(b);
  }

  int unlink(int b) {
    const int a = prev_[b], c = next_[b];
    next_[a] = c;
    prev_[c] = a;
    --remaining_;
    start_ = a;
    return a;
  }

  /// Removes one corner where the boundary turns back on itself (zero area, not on a straight run).
  bool drop_spike() {
    int b = start_;
    for (int k = 0; k < remaining_; ++k, b = next_[b]) {
      const int a = prev_[b], c = next_[b];
      if (orient2d(p_[a], p_[b], p_[c]) != 0) continue;
      const Eigen::Vector2d u = p_[b] - p_[a], v = p_[c] - p_[b];
      if (u.dot(v) <= 0) {  // reversal (sign of the dot product suffices for collinear vectors)
        unlink(b);
        return true;
      }
    }
    return false;
  }

  /// Last resort for non-simple polygons: clip the first strictly convex corner.
  bool clip_any_convex(std::vector<IndexTriangle>& out) {
    int b = start_;
    for (int k = 0; k < remaining_; ++k, b = next_[b]) {
      if (orient2d(p_[prev_[b]], p_[b], p_[next_[b]]) > 0) {
        clip(b, out);
        return true;
      }
    }
    return false;
  }

  /// Every corner turns strictly left and the edges' x components change sign exactly twice
  /// around the ring (the edge direction turns once, not several times): a strictly convex
  /// polygon, whose every convex corner is an ear and stays one as ears are clipped (exact).
  bool strictly_convex() const {
    const size_t n = p_.size();
    for (size_t i = 0; i < n; ++i)
      if (orient2d(p_[(i + n - 1) % n], p_[i], p_[(i + 1) % n]) <= 0) return false;
    int changes = 0, last = 0;
    for (size_t k = 0; k < 2 * n; ++k) {  // twice around: the first nonzero sign sets `last`
      const double dx = p_[(k + 1) % n].x() - p_[k % n].x();  // its sign is exact
      const int sign = dx > 0 ? 1 : (dx < 0 ? -1 : 0);
      if (sign == 0) continue;
      if (last != 0 && sign != last && k >= n) ++changes;
      last = sign;
    }
    return changes == 2;
  }

  const std::vector<Eigen::Vector2d>& p_;
  std::span<const int> ids_;
  std::vector<int>& next_;
  std::vector<int>& prev_;
  bool spread_ = false;
  bool convex_ = false;
  int remaining_ = 0;
  int start_ = 0;
};

/// Every corner of the projected quadrilateral turns strictly left (exact orientation tests): then
/// no corner lies in the triangle of the other three, and any corner is an ear.
bool quad_is_strictly_convex(const std::vector<Eigen::Vector2d>& p) {
  return orient2d(p[3], p[0], p[1]) > 0 && orient2d(p[0], p[1], p[2]) > 0 && orient2d(p[1], p[2], p[3]) > 0 &&
         orient2d(p[2], p[3], p[0]) > 0;
}

}  // namespace

void PolygonTriangulator::append(const std::vector<Eigen::Vector3d>& vertices, std::span<const int> face,
                                 std::vector<IndexTriangle>& out, EarOrder order) {
  if (face.size() < 3)
    throw InvalidInput("triangulate_polygon: a face needs at least 3 vertices, got " +
                       std::to_string(face.size()));
  for (int id : face)
    if (id < 0 || static_cast<size_t>(id) >= vertices.size())
      throw InvalidInput("triangulate_polygon: vertex index " + std::to_string(id) +
                         " out of range (mesh has " + std::to_string(vertices.size()) +
                         " vertices)");
  if (face.size() == 3) {
    out.push_back({face[0], face[1], face[2]});
    return;
  }
  // Newell normal, relative to the first corner and scaled to unit size (no overflow or
  // underflow for huge or tiny coordinates).
  const Eigen::Vector3d origin = vertices[face[0]];
  double scale = 0;
  for (int id : face) scale = std::max(scale, (vertices[id] - origin).cwiseAbs().maxCoeff());
  if (!(scale > 0) || !std::isfinite(scale)) scale = 1;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < face.size(); ++i) {
    const Eigen::Vector3d a = (vertices[face[i]] - origin) / scale;
    const Eigen::Vector3d b = (vertices[face[(i + 1) % face.size()]] - origin) / scale;
    normal += a.cross(b);
  }
  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  if (normal[axis] == 0) return;  // zero area: nothing to cover
  // Project on the two other axes in cyclic order (keeps handedness); mirror if the
  // polygon runs clockwise there, so that the ring is counter-clockwise.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const double mirror = normal[axis] > 0 ? 1.0 : -1.0;
  points_.clear();
  for (int id : face) points_.emplace_back(mirror * vertices[id][u], vertices[id][v]);
  if (face.size() == 4 && quad_is_strictly_convex(points_)) {
    // What the ear clipper gives a strictly convex quadrilateral (its first corner is an ear,
    // then the rest, begun where the order says), without its rings: a faceted sphere's faces
    // are nearly all such.
    out.push_back({face[3], face[0], face[1]});
    if (order == EarOrder::Spread)
      out.push_back({face[1], face[2], face[3]});
    else
      out.push_back({face[2], face[3], face[1]});
    return;
  }
  EarClipper(points_, face, next_, prev_, order).run(out);
}

std::vector<IndexTriangle> triangulate_polygon(const std::vector<Eigen::Vector3d>& vertices,
                                          std::span<const int> face) {
  std::vector<IndexTriangle> out;
  PolygonTriangulator().append(vertices, face, out);
  return out;
}

PolygonMesh triangulate(const PolygonMesh& mesh) {
  PolygonMesh out;
  out.vertices = mesh.vertices;
  out.faces.reserve(mesh.faces.size());
  PolygonTriangulator triangulator;
  std::vector<IndexTriangle> tris;
  for (const auto& face : mesh.faces) {
    tris.clear();
    triangulator.append(mesh.vertices, face, tris);
    for (const IndexTriangle& t : tris) out.faces.push_back({t[0], t[1], t[2]});
  }
  return out;
}

}  // namespace sculpt
