#include "bsp/merge/convex_union.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "bsp/partition/autopartition.hpp"
#include "bsp/tree/solid_access.hpp"
#include "kernel/convex_hull.hpp"
#include "kernel/convex_polygon.hpp"
#include "kernel/plane.hpp"

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::CornerBox;
using kernel::GridPoint;
using kernel::Plane;
using kernel::Side;

namespace {

/// An order of grid points (for lookups of a polytope's vertices).
bool grid_less(const GridPoint& x, const GridPoint& y) { return std::tie(x.x, x.y, x.z) < std::tie(y.x, y.y, y.z); }

/// An order of planes by value (for lookups of equal planes).
bool plane_less(const Plane& x, const Plane& y) { return std::tuple(x.a, x.b, x.c, x.d) < std::tuple(y.a, y.b, y.c, y.d); }

/// A convex polytope: its face planes (arena indices, outward normals, in plane_less order), its faces as boundary
/// fragments on them, and the box of its vertices (grid units). The capsule (the points within
/// `radius` of the segment from `core[0]` to `core[1]`, grid units) lies strictly inside it when
/// `radius` > 0: a quick test that drops a piece without a test against each plane.
struct Polytope {
  std::vector<std::int32_t> planes;
  std::vector<BoundaryFragment> faces;
  std::vector<GridPoint> vertices;                  ///< the hull's vertices
  std::vector<std::int32_t> sorted_vertices;        ///< their indices, sorted by grid_less
  /// The faces around each vertex (those of the triangles at it): vertex_faces[vertex_start[v] ..
  /// vertex_start[v + 1]).
  std::vector<std::int32_t> vertex_start, vertex_faces;
  /// Per face: the vertex of each corner, corner_vertices[corner_start[f] .. + corner_count[f]).
  std::vector<std::int32_t> corner_start, corner_count, corner_vertices;
  CornerBox box;
  std::size_t hint = 0;  ///< the plane that last decided a piece: tried first for the next one
  std::array<double, 3> core[2] = {};
  double radius = 0;
  double slack = 0;  ///< bound on the rounding of a distance to the core (grid units)
};

/// The polytope's inscribed capsule about `core`: the radius is the least distance of the core's
/// ends from the face planes (the distance to a plane is linear along the segment, so its least
/// value is at an end; a ball of that radius about any point of the segment lies behind every
/// plane), less a margin that covers the rounding of these distances and of the tests' (relative
/// error below 2^-45 of the coordinates' magnitude; the margin is 2^-30 of it). No capsule (radius
/// 0) if the core is not well inside.
void set_capsule(const Arena& arena, const HullCore& core, Polytope& poly) {
  double magnitude = 1;
  for (int k = 0; k < 3; ++k) magnitude = std::max({magnitude, std::fabs(poly.box.lo[k]), std::fabs(poly.box.hi[k])});
  for (const auto& end : core.ends)
    for (const double x : end) magnitude = std::max(magnitude, std::fabs(x));
  poly.slack = 0x1p-30 * magnitude;
  double least = 1e300;
  for (const std::int32_t i : poly.planes) {
    const Plane& e = arena.planes[i];
    const double a = double(e.a), b = double(e.b), c = double(e.c);
    const double norm = std::sqrt(a * a + b * b + c * c);
    for (const auto& end : core.ends) least = std::min(least, -(a * end[0] + b * end[1] + c * end[2] + e.d_nearest) / norm);
  }
  poly.core[0] = core.ends[0];
  poly.core[1] = core.ends[1];
  poly.radius = least - 2 * poly.slack;
  if (!(poly.radius > 2 * poly.slack)) poly.radius = 0;
}

/// True if the point (with its error bound) lies strictly inside the polytope's capsule, so
/// strictly inside the polytope.
bool inside_capsule(const kernel::ApproxPoint& at, const Polytope& q) {
  if (q.radius <= 0 || !(at.err >= 0)) return false;
  const double d[3] = {q.core[1][0] - q.core[0][0], q.core[1][1] - q.core[0][1], q.core[1][2] - q.core[0][2]};
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double w[3] = {at.x - q.core[0][0], at.y - q.core[0][1], at.z - q.core[0][2]};
  // The point of the segment at parameter t (any t in [0, 1] gives an upper bound of the
  // distance to the segment; the nearest one gives the distance).
  double t = dd > 0 ? (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double r[3] = {w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]};
  const double reach = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) + 1.7320508075688774 * at.err;
  const double m = std::max({std::fabs(at.x), std::fabs(at.y), std::fabs(at.z)});
  return reach + q.slack + 0x1p-30 * m < q.radius;
}

/// True if the polygon lies strictly inside the polytope's capsule, so strictly inside the
/// polytope: every corner within the capsule (both are convex).
bool inside_capsule(const ConvexPolygon& piece, const Polytope& q) {
  if (q.radius <= 0) return false;
  for (const kernel::Corner& corner : piece.corners)
    if (!inside_capsule(corner.at(), q)) return false;
  return true;
}

/// The polytope of a 3-dimensional hull: coplanar triangles form one face (found by walking
/// across edges to neighbours whose third vertex is on the triangle's plane; on a convex polytope
/// the triangles of one plane are connected), and each face's polygon is read off the
/// triangulation: its boundary edges (those whose triangle across belongs to another face) form
/// one counter-clockwise cycle, each edge on the plane of the face across it; a run of collinear
/// edges with the same face across is one edge of the polygon, and a corner is the hull vertex
/// where two runs meet: the point face ∩ previous neighbour ∩ next neighbour (two different
/// neighbours along a face's boundary are never collinear on a convex polytope), a grid point, so
/// its coordinates are exact (error 0). `core` is a segment inside the hull (grid units) for the
/// inscribed capsule.
Polytope make_polytope(Arena& arena, const kernel::ConvexHull& h, const HullCore& core) {
  const std::size_t n = h.triangles.size();
  if (h.neighbours.size() != n) throw std::logic_error("unite_convex_hulls: the hull has no triangle adjacency");
  auto corner = [&](std::size_t t, int k) { return h.triangles[t][std::size_t(k % 3)]; };
  auto across = [&](std::size_t t, int k) { return std::size_t(h.neighbours[t][std::size_t(k % 3)]); };
  Polytope poly;
  // Faces: one plane each (normalized), its triangles by a walk across coplanar neighbours.
  std::vector<std::int32_t> face_of(n, -1);
  std::vector<Plane> face_planes;
  std::vector<std::size_t> stack;
  for (std::size_t t0 = 0; t0 < n; ++t0) {
    if (face_of[t0] >= 0) continue;
    const Plane plane = kernel::plane_through(h.vertices[std::size_t(corner(t0, 0))], h.vertices[std::size_t(corner(t0, 1))],
                                              h.vertices[std::size_t(corner(t0, 2))]);
    const auto f = std::int32_t(face_planes.size());
    face_planes.push_back(plane);
    face_of[t0] = f;
    stack.assign(1, t0);
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const std::size_t g = across(t, k);
        if (face_of[g] >= 0) continue;
        // The vertex of g off the shared edge (g has it as corner(t, k + 1) -> corner(t, k)).
        int third = -1;
        for (int j = 0; j < 3; ++j)
          if (corner(g, j) != corner(t, k) && corner(g, j) != corner(t, k + 1)) third = corner(g, j);
        if (third < 0) throw std::logic_error("unite_convex_hulls: a degenerate hull triangle");
        if (plane.eval(h.vertices[std::size_t(third)]) == 0) face_of[g] = f, stack.push_back(g);
      }
    }
  }
  // Faces in the order of their planes (plane_less): the union's fragments come in a
  // deterministic order that does not depend on Quickhull's triangle order (the tree built from
  // them takes its candidate planes at evenly spaced positions).
  const std::size_t faces = face_planes.size();
  {
    std::vector<std::int32_t> order(faces), rank(faces);
    for (std::size_t f = 0; f < faces; ++f) order[f] = std::int32_t(f);
    std::sort(order.begin(), order.end(),
              [&](std::int32_t x, std::int32_t y) { return plane_less(face_planes[std::size_t(x)], face_planes[std::size_t(y)]); });
    for (std::size_t r = 0; r < faces; ++r) {
      rank[std::size_t(order[r])] = std::int32_t(r);
      poly.planes.push_back(arena.planes.add(face_planes[std::size_t(order[r])]));
    }
    for (std::int32_t& f : face_of) f = rank[std::size_t(f)];
  }
  // The boundary cycle of each face: from a boundary edge (t, k) to the next one leaving its end
  // v, turning about v across the face's inner edges.
  poly.faces.resize(faces);
  poly.corner_start.assign(faces, -1);
  poly.corner_count.assign(faces, 0);
  std::vector<bool> done(3 * n, false);
  std::vector<std::int32_t> cycle_across, cycle_from;
  for (std::size_t t0 = 0; t0 < n; ++t0)
    for (int k0 = 0; k0 < 3; ++k0) {
      const std::int32_t f = face_of[t0];
      if (done[3 * t0 + std::size_t(k0)] || face_of[across(t0, k0)] == f) continue;
      if (poly.corner_start[std::size_t(f)] >= 0) throw std::logic_error("unite_convex_hulls: a face's boundary is not one cycle");
      cycle_across.clear();
      cycle_from.clear();
      std::size_t t = t0;
      int k = k0;
      do {
        done[3 * t + std::size_t(k)] = true;
        cycle_across.push_back(face_of[across(t, k)]);
        cycle_from.push_back(corner(t, k));
        const int v = corner(t, k + 1);
        k = (k + 1) % 3;  // the edge of t leaving v
        for (std::size_t turns = 0; face_of[across(t, k)] == f; ++turns) {
          // An inner edge v -> w: the triangle across has w -> v, and its edge after that leaves v.
          const std::size_t g = across(t, k);
          int j = 0;
          while (j < 3 && corner(g, j) != v) ++j;
          if (j == 3 || turns > n) throw std::logic_error("unite_convex_hulls: the hull's triangles are not consistent");
          t = g;
          k = j;
        }
        if (cycle_from.size() > 3 * n) throw std::logic_error("unite_convex_hulls: a face's boundary is not one cycle");
      } while (t != t0 || k != k0);
      const std::size_t m = cycle_across.size();
      ConvexPolygon polygon;
      polygon.support = poly.planes[std::size_t(f)];
      poly.corner_start[std::size_t(f)] = std::int32_t(poly.corner_vertices.size());
      for (std::size_t i = 0; i < m; ++i) {
        const std::int32_t prev = cycle_across[(i + m - 1) % m];
        if (prev == cycle_across[i]) continue;  // a collinear edge continues the run before it
        const GridPoint& v = h.vertices[std::size_t(cycle_from[i])];
        // The edges into and out of the corner must not be collinear (their planes and the face's
        // then meet in one point), as on any convex polytope.
        const GridPoint& u = h.vertices[std::size_t(cycle_from[(i + m - 1) % m])];
        const GridPoint& w = h.vertices[std::size_t(cycle_from[(i + 1) % m])];
        const std::int64_t in[3] = {v.x - u.x, v.y - u.y, v.z - u.z}, out[3] = {w.x - v.x, w.y - v.y, w.z - v.z};
        if (in[1] * out[2] == in[2] * out[1] && in[2] * out[0] == in[0] * out[2] && in[0] * out[1] == in[1] * out[0])
          throw std::logic_error("unite_convex_hulls: two edges of a face on different neighbours are collinear");
        poly.corner_vertices.push_back(cycle_from[i]);
        polygon.corners.push_back({poly.planes[std::size_t(cycle_across[i])], poly.planes[std::size_t(prev)],
                                   poly.planes[std::size_t(cycle_across[i])],
                                   kernel::ApproxPoint{double(v.x), double(v.y), double(v.z), 0.0}});  // exact: |coordinates| <= 2^25
      }
      if (polygon.corners.size() < 3) throw std::logic_error("unite_convex_hulls: a face has fewer than 3 corners");
      poly.corner_count[std::size_t(f)] = std::int32_t(polygon.corners.size());
      poly.faces[std::size_t(f)] = {std::move(polygon), false};
    }
  for (std::size_t f = 0; f < faces; ++f)
    if (poly.corner_start[f] < 0) throw std::logic_error("unite_convex_hulls: a face without boundary edges");
  poly.box.valid = true;
  for (int k = 0; k < 3; ++k) poly.box.lo[k] = 1e300, poly.box.hi[k] = -1e300;
  for (const GridPoint& v : h.vertices) {
    const double c[3] = {double(v.x), double(v.y), double(v.z)};  // exact: |coordinates| <= 2^25
    for (int k = 0; k < 3; ++k) poly.box.lo[k] = std::min(poly.box.lo[k], c[k]), poly.box.hi[k] = std::max(poly.box.hi[k], c[k]);
  }
  poly.vertices = h.vertices;
  poly.sorted_vertices.resize(h.vertices.size());
  for (std::size_t v = 0; v < h.vertices.size(); ++v) poly.sorted_vertices[v] = std::int32_t(v);
  std::sort(poly.sorted_vertices.begin(), poly.sorted_vertices.end(),
            [&](std::int32_t x, std::int32_t y) { return grid_less(h.vertices[std::size_t(x)], h.vertices[std::size_t(y)]); });
  // The faces around each vertex: the triangles' faces by vertex (a counting sort), each once.
  const std::size_t nv = h.vertices.size();
  poly.vertex_start.assign(nv + 1, 0);
  for (const auto& t : h.triangles)
    for (const int v : t) ++poly.vertex_start[std::size_t(v) + 1];
  for (std::size_t v = 0; v < nv; ++v) poly.vertex_start[v + 1] += poly.vertex_start[v];
  poly.vertex_faces.resize(3 * n);
  {
    std::vector<std::int32_t> at(poly.vertex_start.begin(), poly.vertex_start.end() - 1);
    for (std::size_t t = 0; t < n; ++t)
      for (const int v : h.triangles[t]) poly.vertex_faces[std::size_t(at[std::size_t(v)]++)] = face_of[t];
  }
  std::int32_t kept = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::int32_t begin = poly.vertex_start[v], end = poly.vertex_start[v + 1];
    poly.vertex_start[v] = kept;
    for (std::int32_t i = begin; i < end; ++i) {
      const std::int32_t f = poly.vertex_faces[std::size_t(i)];
      if (std::find(poly.vertex_faces.begin() + poly.vertex_start[v], poly.vertex_faces.begin() + kept, f) ==
          poly.vertex_faces.begin() + kept)
        poly.vertex_faces[std::size_t(kept++)] = f;
    }
  }
  poly.vertex_start[nv] = kept;
  poly.vertex_faces.resize(std::size_t(kept));
  set_capsule(arena, core, poly);
  return poly;
}

bool overlap(const CornerBox& a, const CornerBox& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

/// A piece of a polytope's boundary being clipped, with its corner box (kept while the piece
/// passes whole from one polytope's test to the next).
struct Piece {
  ConvexPolygon polygon;
  CornerBox box;
  std::int32_t face = -1;  ///< the polytope's face it still is whole (corners at its vertices), or -1
};

/// Where the vertices of the polytope whose pieces are clipped lie with respect to the polytope
/// q clipping them (exact), found when first needed and kept while q is the same.
class VertexSides {
 public:
  /// Statuses: >= 0 the position in q.planes of a plane the vertex lies strictly in front of;
  /// kOnBoundary in q, on one of its planes; kInside strictly inside q; <= kShared: the vertex is
  /// q's vertex kShared - status (so on q's boundary).
  static constexpr std::int32_t kOnBoundary = -1, kInside = -2, kShared = -3;

  void reset(std::size_t vertices) {
    if (stamp_.size() < vertices) stamp_.resize(vertices, 0), status_.resize(vertices, kInside);
    ++current_;
  }
  /// The status of own vertex `vertex` at `v`.
  std::int32_t side(const Arena& arena, const Polytope& q, const GridPoint& v, std::int32_t vertex) {
    if (stamp_[std::size_t(vertex)] == current_) return status_[std::size_t(vertex)];
    stamp_[std::size_t(vertex)] = current_;
    std::int32_t& result = status_[std::size_t(vertex)];
    // A vertex of q is on its boundary (hulls of neighbouring segments share the tool's vertices
    // at their joint); one in q's capsule is strictly inside. Else every plane is tested.
    const auto shared = std::lower_bound(q.sorted_vertices.begin(), q.sorted_vertices.end(), v,
                                         [&](std::int32_t x, const GridPoint& y) { return grid_less(q.vertices[std::size_t(x)], y); });
    if (shared != q.sorted_vertices.end() && q.vertices[std::size_t(*shared)] == v) return result = kShared - *shared;
    const kernel::ApproxPoint at{double(v.x), double(v.y), double(v.z), 0.0};  // exact: |coordinates| <= 2^25
    if (inside_capsule(at, q)) return result = kInside;
    const std::size_t m = q.planes.size();
    result = kInside;
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = (last_ + k) % m;
      const Plane& e = arena.planes[q.planes[i]];
      kernel::Sign g = kernel::filtered_orient(at, e);
      if (g == kernel::Sign::Zero) g = kernel::orient(v, e);
      if (g == kernel::Sign::Positive) {
        result = std::int32_t(i);
        last_ = i;
        break;
      }
      if (g == kernel::Sign::Zero) result = kOnBoundary;
    }
    return result;
  }

 private:
  std::vector<std::uint32_t> stamp_;
  std::vector<std::int32_t> status_;
  std::uint32_t current_ = 0;
  std::size_t last_ = 0;  ///< the plane the last vertex in front of one was found in front of
};

/// The exact side of a polygon with respect to a plane, for a caller that made the box test.
Side exact_side(const kernel::PlaneTable& planes, const ConvexPolygon& poly, std::int32_t plane) {
  const Plane& s = planes[poly.support];
  const Plane& cut = planes[plane];
  bool neg = false, pos = false;
  for (const kernel::Corner& c : poly.corners) {
    kernel::Sign g = kernel::filtered_orient(c.at(), cut);
    if (g == kernel::Sign::Zero) g = kernel::orient(s, planes[c.p], planes[c.q], c.at(), cut);
    neg |= g == kernel::Sign::Negative;
    pos |= g == kernel::Sign::Positive;
    if (neg && pos) return Side::Both;
  }
  return neg ? Side::Negative : (pos ? Side::Positive : Side::On);
}

/// Appends to `kept` the parts of `piece` (outward normal along its support) that are not inside
/// polytope q: the parts in front of one of q's planes, and the part on q's face when it is
/// q's face with the same orientation and `first` (the piece's polytope is listed before q).
/// For a piece that is still a whole face of `own` (its corners are own's vertices): where it lies
/// with respect to q, decided from its corners' sides (exact) where they decide it: Negative if
/// it lies in q's closed interior and not on a face of q (inside, dropped), On if it lies on a
/// face of q (`on`: that face's plane), Positive if one of q's planes has every corner on its
/// closed positive side and one strictly (outside, kept whole), Both if undecided (the corners
/// lie in front of different planes: the piece may cross q).
Side whole_face_side(const Arena& arena, const Polytope& own, const Piece& piece, Polytope& q, VertexSides& sides,
                     std::int32_t& on) {
  const std::span<const std::int32_t> corners(own.corner_vertices.data() + own.corner_start[std::size_t(piece.face)],
                                              std::size_t(own.corner_count[std::size_t(piece.face)]));
  bool strictly_inside = false;
  std::int32_t shared = -1;  // a vertex of q at one of the corners
  boost::container::small_vector<std::int32_t, 8> outside;  // planes some corner lies in front of
  for (const std::int32_t v : corners) {
    const std::int32_t s = sides.side(arena, q, own.vertices[std::size_t(v)], v);
    if (s >= 0 && std::find(outside.begin(), outside.end(), s) == outside.end()) outside.push_back(s);
    if (s <= VertexSides::kShared) shared = VertexSides::kShared - s;
    strictly_inside |= s == VertexSides::kInside;
  }
  if (outside.empty()) {
    // The face lies in q's closed interior (both are convex). It lies on a face of q only if its
    // plane is one of q's planes; otherwise its relative interior is inside q.
    if (strictly_inside) return Side::Negative;
    const Plane& support = arena.planes[piece.polygon.support];
    for (const Plane& e : {support, support.opposite()}) {
      const auto it = std::lower_bound(q.planes.begin(), q.planes.end(), e,
                                       [&](std::int32_t x, const Plane& y) { return plane_less(arena.planes[x], y); });
      if (it != q.planes.end() && arena.planes[*it] == e) {
        on = *it;
        return Side::On;
      }
    }
    return Side::Negative;
  }
  // A corner in front of q and one strictly inside: the face crosses q's boundary.
  if (strictly_inside) return Side::Both;
  // A plane of q with no corner behind it and one in front separates the face from q. Where a corner is a vertex
  // of q, such a plane passes through it (q lies behind each of its planes): one of the faces at
  // that vertex. Else try the planes the corners were found in front of.
  auto separates = [&](std::int32_t candidate) {
    const Plane& e = arena.planes[q.planes[std::size_t(candidate)]];
    bool front = false;  // a face on the plane is not in front of it
    for (const std::int32_t v : corners) {
      const GridPoint& p = own.vertices[std::size_t(v)];
      kernel::Sign g = kernel::filtered_orient(kernel::ApproxPoint{double(p.x), double(p.y), double(p.z), 0.0}, e);
      if (g == kernel::Sign::Zero) g = kernel::orient(p, e);
      if (g == kernel::Sign::Negative) return false;
      front |= g == kernel::Sign::Positive;
    }
    if (front) q.hint = std::size_t(candidate);
    return front;
  };
  if (shared >= 0) {
    for (std::int32_t k = q.vertex_start[std::size_t(shared)]; k < q.vertex_start[std::size_t(shared) + 1]; ++k)
      if (separates(q.vertex_faces[std::size_t(k)])) return Side::Positive;
    return Side::Both;
  }
  for (const std::int32_t candidate : outside)
    if (separates(candidate)) return Side::Positive;
  return Side::Both;
}

void clip_outside(Arena& arena, const Polytope& own, Piece piece, Polytope& q, bool first, VertexSides& sides,
                  std::vector<Piece>& kept) {
  if (!overlap(piece.box, q.box)) {  // box_side would find a separating plane, but this is cheaper
    kept.push_back(std::move(piece));
    return;
  }
  const std::size_t m = q.planes.size();
  // A piece wholly in front of one of q's planes is outside q and stays whole: look for such a
  // plane by the box tests first (from the one that decided the last piece), then exactly, and
  // split only a piece that no plane separates from q (one that crosses q's boundary).
  thread_local std::vector<std::uint32_t> crossing;
  crossing.clear();
  // The plane that decided the last piece first; then, before the other planes, a whole face by
  // its corners' sides (those in q's capsule are inside without a plane test), another piece by
  // the capsule: pieces deep inside q (most near a joint of a sweep) would pass the box test of
  // every plane.
  if (kernel::box_side(piece.box, arena.planes[q.planes[q.hint % m]]) == Side::Positive) {
    kept.push_back(std::move(piece));
    return;
  }
  if (piece.face < 0 && inside_capsule(piece.polygon, q)) return;
  if (piece.face >= 0) {
    std::int32_t on = -1;
    const Side s = whole_face_side(arena, own, piece, q, sides, on);
    if (s == Side::Positive) kept.push_back(std::move(piece));
    if (s == Side::On && first && arena.planes[on] == arena.planes[piece.polygon.support]) kept.push_back(std::move(piece));
    if (s != Side::Both) return;
  }
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = (q.hint + k) % m;
    const Side quick = kernel::box_side(piece.box, arena.planes[q.planes[i]]);
    if (quick == Side::Positive) {
      q.hint = i;
      kept.push_back(std::move(piece));
      return;
    }
    if (quick == Side::Both) crossing.push_back(std::uint32_t(i));
  }
  std::int32_t on = -1;
  std::size_t live = 0;  // planes of `crossing` the piece crosses exactly
  for (const std::uint32_t i : crossing) {
    const Side s = exact_side(arena.planes, piece.polygon, q.planes[i]);
    if (s == Side::Positive) {
      q.hint = i;
      kept.push_back(std::move(piece));
      return;
    }
    if (s == Side::On) on = q.planes[i];
    if (s == Side::Both) crossing[live++] = i;
  }
  ConvexPolygon neg, pos;
  bool whole = true;  // piece.box is still the box of piece.polygon
  for (std::size_t k = 0; k < live; ++k) {
    const std::int32_t p = q.planes[crossing[k]];
    const Side s = kernel::split(arena.planes, piece.polygon, p, arena.opposite(p), neg, pos);
    if (s == Side::Positive) {  // the part left after earlier splits is in front of this plane
      if (!whole) piece.box = kernel::corner_box(piece.polygon);
      kept.push_back(std::move(piece));
      return;
    }
    if (s == Side::Both) {
      const CornerBox box = kernel::corner_box(pos);
      kept.push_back({std::move(pos), box, -1});
      std::swap(piece.polygon, neg);
      whole = false;
      piece.face = -1;
    }
  }
  // What is left lies in q's closed interior: inside q unless it lies on one of q's faces.
  if (on >= 0 && first && arena.planes[on] == arena.planes[piece.polygon.support]) {
    if (!whole) piece.box = kernel::corner_box(piece.polygon);
    kept.push_back(std::move(piece));
  }
}

}  // namespace

Solid unite_convex_hulls(const std::vector<std::vector<GridPoint>>& point_sets, const kernel::Grid& grid,
                         const ConvexUnionOptions& options) {
  if (!options.cores.empty() && options.cores.size() != point_sets.size())
    throw std::invalid_argument("unite_convex_hulls: one core per point set");
  Arena arena;
  std::vector<Polytope> polys;
  for (std::size_t s = 0; s < point_sets.size(); ++s) {
    const kernel::ConvexHull h = kernel::convex_hull(point_sets[s]);
    if (h.dimension != 3) continue;
    HullCore core;
    if (!options.cores.empty()) {
      core = options.cores[s];
    } else {  // the centroid of the vertices: strictly inside a hull with volume
      for (const GridPoint& v : h.vertices) {
        core.ends[0][0] += double(v.x), core.ends[0][1] += double(v.y), core.ends[0][2] += double(v.z);
      }
      for (double& x : core.ends[0]) x /= double(h.vertices.size());
      core.ends[1] = core.ends[0];
    }
    polys.push_back(make_polytope(arena, h, core));
  }
  // Pairs of polytopes whose boxes meet (sorted by their lower x, a sweep over x), each list
  // ordered nearest in the list first (in a sweep, the hulls of the neighbouring segments): they
  // cover most of what gets dropped, so fewer pieces reach the others.
  const std::size_t n = polys.size();
  std::vector<std::vector<std::size_t>> near(n);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return polys[a].box.lo[0] < polys[b].box.lo[0]; });
  for (std::size_t x = 0; x < n; ++x)
    for (std::size_t y = x + 1; y < n && polys[order[y]].box.lo[0] <= polys[order[x]].box.hi[0]; ++y)
      if (overlap(polys[order[x]].box, polys[order[y]].box)) near[order[x]].push_back(order[y]), near[order[y]].push_back(order[x]);
  FragmentList result;
  std::vector<Piece> pieces, kept;
  VertexSides sides;
  for (std::size_t i = 0; i < n; ++i) {
    pieces.clear();
    for (std::size_t f = 0; f < polys[i].faces.size(); ++f) {
      const CornerBox box = kernel::corner_box(polys[i].faces[f].polygon);
      pieces.push_back({std::move(polys[i].faces[f].polygon), box, std::int32_t(f)});
    }
    auto distance = [i](std::size_t j) { return j > i ? j - i : i - j; };
    std::sort(near[i].begin(), near[i].end(),
              [&](std::size_t a, std::size_t b) { return std::pair(distance(a), a) < std::pair(distance(b), b); });
    for (const std::size_t j : near[i]) {
      if (pieces.empty()) break;
      kept.clear();
      sides.reset(polys[i].vertices.size());
      for (Piece& piece : pieces) clip_outside(arena, polys[i], std::move(piece), polys[j], i < j, sides, kept);
      std::swap(pieces, kept);
    }
    for (Piece& piece : pieces) result.push_back({std::move(piece.polygon), false});
  }
  if (result.empty()) return SolidAccess::at_grid(Solid(), grid);
  return SolidAccess::at_grid(autopartition(arena, std::move(result)), grid);
}

}  // namespace sculpt::bsp::detail
