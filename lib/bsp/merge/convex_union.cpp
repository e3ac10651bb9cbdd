#include "bsp/merge/convex_union.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "bsp/tree/autopartition.hpp"
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

/// A convex polytope: its face planes (arena indices, outward normals), its faces as boundary
/// fragments on them, and the box of its vertices (grid units).
struct Polytope {
  std::vector<std::int32_t> planes;
  std::vector<BoundaryFragment> faces;
  CornerBox box;
  std::size_t hint = 0;  ///< the plane that last decided a piece: tried first for the next one
};

/// The polytope of a 3-dimensional hull: coplanar triangles (equal normalized planes) form one
/// face, and each face is its plane's world polygon clipped by the planes of the faces across
/// its edges. For a convex polytope that is the face exactly: a face is the intersection, in its
/// plane, of the half-planes of its edges, and each edge lies on a neighbouring face's plane.
Polytope make_polytope(Arena& arena, const kernel::ConvexHull& h) {
  const std::size_t n = h.triangles.size();
  std::vector<Plane> plane(n);
  for (std::size_t t = 0; t < n; ++t)
    plane[t] = kernel::plane_through(h.vertices[std::size_t(h.triangles[t][0])], h.vertices[std::size_t(h.triangles[t][1])],
                                     h.vertices[std::size_t(h.triangles[t][2])]);
  // Faces: triangles grouped by plane.
  auto key = [](const Plane& p) { return std::tuple(p.a, p.b, p.c, p.d); };
  std::vector<std::uint32_t> order(n);
  for (std::size_t t = 0; t < n; ++t) order[t] = std::uint32_t(t);
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return key(plane[x]) < key(plane[y]); });
  std::vector<std::int32_t> face_of(n);
  Polytope poly;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 0 || !(plane[order[i]] == plane[order[i - 1]])) poly.planes.push_back(arena.planes.add(plane[order[i]]));
    face_of[order[i]] = std::int32_t(poly.planes.size() - 1);
  }
  // Neighbouring faces across every triangle edge: the directed edge (u, v) of one triangle is
  // (v, u) in the triangle across it.
  const auto nv = std::uint64_t(h.vertices.size());
  std::vector<std::pair<std::uint64_t, std::int32_t>> edges;
  edges.reserve(3 * n);
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k)
      edges.push_back({std::uint64_t(h.triangles[t][std::size_t(k)]) * nv + std::uint64_t(h.triangles[t][std::size_t((k + 1) % 3)]),
                       face_of[t]});
  std::sort(edges.begin(), edges.end());
  std::vector<std::vector<std::int32_t>> neighbours(poly.planes.size());
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t back =
          std::uint64_t(h.triangles[t][std::size_t((k + 1) % 3)]) * nv + std::uint64_t(h.triangles[t][std::size_t(k)]);
      const auto it = std::lower_bound(edges.begin(), edges.end(), std::pair{back, std::int32_t(-1)});
      if (it == edges.end() || it->first != back) throw std::logic_error("unite_convex_hulls: the hull is not closed");
      if (it->second != face_of[t]) neighbours[std::size_t(face_of[t])].push_back(it->second);
    }
  poly.faces.reserve(poly.planes.size());
  for (std::size_t f = 0; f < poly.planes.size(); ++f) {
    std::vector<std::int32_t>& around = neighbours[f];
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    ConvexPolygon buffers[2] = {kernel::world_polygon(arena.planes, poly.planes[f], {.quick_corners = true}), {}};
    int current = 0;
    CornerBox box = kernel::corner_box(buffers[0]);
    for (const std::int32_t g : around) {
      const Side s = kernel::clip_to_negative(arena.planes, buffers[current], buffers[1 - current], box, poly.planes[std::size_t(g)]);
      if (s == Side::Both) current = 1 - current;
      else if (s != Side::Negative) throw std::logic_error("unite_convex_hulls: a face lies outside its neighbour's plane");
    }
    kernel::refresh_world_corners(arena.planes, buffers[current]);
    poly.faces.push_back({std::move(buffers[current]), false});
  }
  poly.box.valid = true;
  for (int k = 0; k < 3; ++k) poly.box.lo[k] = 1e300, poly.box.hi[k] = -1e300;
  for (const GridPoint& v : h.vertices) {
    const double c[3] = {double(v.x), double(v.y), double(v.z)};  // exact: |coordinates| <= 2^25
    for (int k = 0; k < 3; ++k) poly.box.lo[k] = std::min(poly.box.lo[k], c[k]), poly.box.hi[k] = std::max(poly.box.hi[k], c[k]);
  }
  return poly;
}

bool overlap(const CornerBox& a, const CornerBox& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

/// Appends to `kept` the parts of `piece` (outward normal along its support) that are not inside
/// polytope q: the parts in front of one of q's planes, and the part on q's face when it is
/// q's face with the same orientation and `first` (the piece's polytope is listed before q).
void clip_outside(Arena& arena, ConvexPolygon piece, Polytope& q, bool first, std::vector<ConvexPolygon>& kept) {
  CornerBox box = kernel::corner_box(piece);
  if (!overlap(box, q.box)) {  // box_side would find a separating plane, but this is cheaper
    kept.push_back(std::move(piece));
    return;
  }
  const std::size_t m = q.planes.size();
  // A piece wholly in front of one of q's planes is outside q and stays whole: look for such a
  // plane by the box tests first (from the one that decided the last piece), then exactly, and
  // split only a piece that no plane separates from q (one that crosses q's boundary).
  thread_local std::vector<std::uint32_t> crossing;
  crossing.clear();
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = (q.hint + k) % m;
    const Side quick = kernel::box_side(box, arena.planes[q.planes[i]]);
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
    const Side s = kernel::classify(arena.planes, piece, q.planes[i]);
    if (s == Side::Positive) {
      q.hint = i;
      kept.push_back(std::move(piece));
      return;
    }
    if (s == Side::On) on = q.planes[i];
    if (s == Side::Both) crossing[live++] = i;
  }
  ConvexPolygon neg, pos;
  for (std::size_t k = 0; k < live; ++k) {
    const std::int32_t p = q.planes[crossing[k]];
    const Side s = kernel::split(arena.planes, piece, p, arena.opposite(p), neg, pos);
    if (s == Side::Positive) {  // the part left after earlier splits is in front of this plane
      kept.push_back(std::move(piece));
      return;
    }
    if (s == Side::Both) {
      kept.push_back(std::move(pos));
      std::swap(piece, neg);
    }
  }
  // What is left lies in q's closed interior: inside q unless it lies on one of q's faces.
  if (on >= 0 && first && arena.planes[on] == arena.planes[piece.support]) kept.push_back(std::move(piece));
}

}  // namespace

Solid unite_convex_hulls(const std::vector<std::vector<GridPoint>>& point_sets, const kernel::Grid& grid) {
  Arena arena;
  std::vector<Polytope> polys;
  for (const auto& points : point_sets) {
    const kernel::ConvexHull h = kernel::convex_hull(points);
    if (h.dimension == 3) polys.push_back(make_polytope(arena, h));
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
  std::vector<BoundaryFragment> result;
  std::vector<ConvexPolygon> pieces, kept;
  for (std::size_t i = 0; i < n; ++i) {
    pieces.clear();
    for (BoundaryFragment& f : polys[i].faces) pieces.push_back(std::move(f.polygon));
    auto distance = [i](std::size_t j) { return j > i ? j - i : i - j; };
    std::sort(near[i].begin(), near[i].end(),
              [&](std::size_t a, std::size_t b) { return std::pair(distance(a), a) < std::pair(distance(b), b); });
    for (const std::size_t j : near[i]) {
      if (pieces.empty()) break;
      kept.clear();
      for (ConvexPolygon& piece : pieces) clip_outside(arena, std::move(piece), polys[j], i < j, kept);
      std::swap(pieces, kept);
    }
    for (ConvexPolygon& piece : pieces) result.push_back({std::move(piece), false});
  }
  if (result.empty()) return SolidAccess::at_grid(Solid(), grid);
  return SolidAccess::at_grid(autopartition(arena, std::move(result)), grid);
}

}  // namespace sculpt::bsp::detail
