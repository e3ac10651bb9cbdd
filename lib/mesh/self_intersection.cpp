#include "mesh/self_intersection.hpp"
#include "base/cancel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <set>
#include <utility>

#include <Eigen/Geometry>

#include "mesh/detail/box_grid.hpp"
#include "mesh/detail/certified_patches.hpp"
#include "mesh/detail/certified_stars.hpp"
#include "mesh/detail/point_copies.hpp"
#include "mesh/detail/triangle_pairs.hpp"
#include "mesh/predicates.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using mesh::detail::drop;
using mesh::detail::PreparedTriangle;

/// Coordinate axis along which the polygon's projection has the largest area (Newell normal, or
/// the widest corner triangle when the net area is zero); -1 when all corners are collinear.
int projection_axis(const PolygonMesh& mesh, const std::vector<int>& face) {
  const Vector3d origin = mesh.vertices[face[0]];
  Vector3d normal = Vector3d::Zero();
  for (size_t i = 0; i < face.size(); ++i)
    normal += (mesh.vertices[face[i]] - origin).cross(mesh.vertices[face[(i + 1) % face.size()]] - origin);
  if (normal.cwiseAbs().maxCoeff() == 0) {
    // Zero net area (a symmetric bow tie, say): take the plane of the widest corner triangle.
    for (size_t i = 1; i < face.size(); ++i)
      for (size_t k = i + 1; k < face.size(); ++k) {
        const Vector3d n = (mesh.vertices[face[i]] - origin).cross(mesh.vertices[face[k]] - origin);
        if (n.squaredNorm() > normal.squaredNorm()) normal = n;
      }
  }
  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  return normal[axis] == 0 ? -1 : axis;
}

/// Vertex ids when every vertex is distinct (SelfIntersectionOptions::distinct_vertices); else
/// mesh::detail::first_copies gives copies of a point one id.
std::vector<int> identity_ids(size_t n) {
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  return ids;
}

/// x as a float, clamped to float's range: monotone (x <= y gives as_float(x) <= as_float(y)), so
/// boxes that overlap still do after this rounding.
float as_float(double x) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return static_cast<float>(x < -kMax ? -kMax : x > kMax ? kMax : x);
}

/// Asks for t's cache lines ahead of its use (a hint; nothing where the compiler has none).
void prefetch(const PreparedTriangle& t) {
#if defined(__GNUC__)
  const char* p = reinterpret_cast<const char*>(&t);
  for (size_t at = 0; at < sizeof(PreparedTriangle); at += 64) __builtin_prefetch(p + at);
#else
  (void)t;
#endif
}

}  // namespace

bool triangles_meet(const std::array<int, 3>& ids_a, const std::array<Vector3d, 3>& a,
                    const std::array<int, 3>& ids_b, const std::array<Vector3d, 3>& b) {
  PreparedTriangle s = mesh::detail::prepare_triangle(ids_a, a), t = mesh::detail::prepare_triangle(ids_b, b);
  s.axis = std::max(s.axis, 0);  // degenerate (excluded by the precondition): axis 0, as before
  t.axis = std::max(t.axis, 0);
  return mesh::detail::triangles_meet(s, t);
}

std::vector<int> find_self_crossing_faces(const PolygonMesh& mesh, size_t max_faces) {
  std::vector<int> out;
  for (size_t fi = 0; fi < mesh.faces.size() && out.size() < max_faces; ++fi) {
    const auto& f = mesh.faces[fi];
    const size_t n = f.size();
    if (n <= 3) continue;
    const int axis = projection_axis(mesh, f);
    if (axis < 0) continue;
    std::vector<Vector2d> p;
    for (int v : f) p.push_back(drop(mesh.vertices[v], axis));
    bool crossing = false;
    for (size_t i = 0; i < n && !crossing; ++i)
      for (size_t j = i + 2; j < n && !crossing; ++j) {
        if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
        crossing = mesh::detail::segments_meet_2d(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]);
      }
    if (crossing) out.push_back(static_cast<int>(fi));
  }
  return out;
}

std::vector<FacePair> find_self_intersections(const PolygonMesh& mesh, SelfIntersectionOptions options) {
  return search_self_intersections(mesh, options).pairs;
}

SelfIntersectionSearch search_self_intersections(const PolygonMesh& mesh, SelfIntersectionOptions options) {
  SelfIntersectionSearch result;
  const size_t nv = mesh.vertices.size();
  const std::vector<int> canon = options.distinct_vertices ? identity_ids(nv) : mesh::detail::first_copies(mesh.vertices);

  // Faces with every corner marked exact (the flags are used only when there is one per vertex):
  // pairs of their triangles are not examined (see SelfIntersectionOptions::exact_vertices).
  const bool marked = !options.exact_vertices.empty() && options.exact_vertices.size() == nv;
  auto exact_face = [&](const std::vector<int>& f) {
    return marked && std::all_of(f.begin(), f.end(), [&](int v) { return options.exact_vertices[size_t(v)] != 0; });
  };
  if (marked && std::all_of(mesh.faces.begin(), mesh.faces.end(), exact_face)) return result;
  // Per triangle: what the exact tests read, its box, what the stars' certification reads, and
  // what the scan reads (Slot).
  struct Slot {
    std::array<float, 6> box{};  // min x, y, z, max x, y, z, as_float
    int face = 0;
    bool exact = false;  // every corner of its face is marked exact (SelfIntersectionOptions)
    // Per corner: its id where the vertex's star is certified, else -1 - (its triangle): no
    // corner of another triangle has that number.
    std::array<int, 3> star{};
    int patch = 0;  // certified_patches
  };
  std::vector<PreparedTriangle> tris;
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<mesh::detail::StarTriangle> stars;
  std::vector<signed char> cls;
  std::vector<Slot> slots;
  {
    size_t corners = 0;
    for (const auto& f : mesh.faces) corners += f.size() >= 2 ? f.size() - 2 : 0;
    tris.reserve(corners);
    boxes.reserve(corners);
    stars.reserve(corners);
    cls.reserve(corners);
    slots.reserve(corners);
  }
  size_t moved = 0;  // triangles of faces with a corner not marked exact
  PolygonTriangulator triangulator;
  std::vector<IndexTriangle> face_tris;
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const bool exact = exact_face(mesh.faces[fi]);
    face_tris.clear();
    triangulator.append(mesh.vertices, mesh.faces[fi], face_tris, EarOrder::Spread);
    for (const IndexTriangle& it : face_tris) {
      const PreparedTriangle t =
          mesh::detail::prepare_triangle({canon[it[0]], canon[it[1]], canon[it[2]]},
                                         {mesh.vertices[it[0]], mesh.vertices[it[1]], mesh.vertices[it[2]]});
      if (t.axis < 0) continue;  // collinear corners: degenerate, reported elsewhere
      Eigen::AlignedBox3d box;
      for (int k = 0; k < 3; ++k) box.extend(t.p[k]);
      Slot slot;
      for (int k = 0; k < 3; ++k) {
        slot.box[size_t(k)] = as_float(box.min()[k]);
        slot.box[size_t(k) + 3] = as_float(box.max()[k]);
      }
      slot.face = static_cast<int>(fi);
      slot.exact = exact;
      slot.star = t.ids;
      tris.push_back(t);
      boxes.push_back(box);
      stars.push_back(mesh::detail::star_triangle(t));
      // Its class for certified_patches: its axis and the sign of its projection there, or -1
      // where the filter leaves that sign open.
      const int sign = stars.back().sign[size_t(t.axis)];
      cls.push_back(static_cast<signed char>(sign == 1 || sign == -1 ? 2 * t.axis + (sign > 0 ? 1 : 0) : -1));
      slots.push_back(slot);
      moved += exact ? 0 : 1;
    }
  }
  if (moved == 0) return result;
  // Pairs that share a vertex whose star is certified are not examined (certified_stars), nor
  // pairs of one certified patch (certified_patches).
  {
    const mesh::detail::CertifiedStars star_verdicts = mesh::detail::certified_stars(stars, mesh.vertices);
    const std::vector<signed char>& certified = star_verdicts.certified;
    const std::vector<int> patch = mesh::detail::certified_patches(cls, star_verdicts, mesh.vertices);
    for (size_t i = 0; i < slots.size(); ++i) slots[i].patch = patch[i];
    for (size_t i = 0; i < slots.size(); ++i)
      for (int& id : slots[i].star) id = certified[size_t(id)] != 0 ? id : -1 - int(i);
  }
  // Broad phase (mesh/detail/box_grid.hpp): a uniform grid over the triangles' boxes; a pair
  // whose boxes overlap is examined in the one cell that owns it, so once. The scan compares the
  // boxes rounded to floats: they overlap where the boxes do, and a pair that overlaps only after
  // rounding has triangles that do not meet, so the cell that examines it does not matter.
  std::set<std::pair<int, int>> found;
  const mesh::detail::BoxGrid grid(boxes);
  size_t candidates = 0, scanned = 0;
  // Per cell: its members gathered field by field, then for each member the later members whose
  // boxes overlap its own collected without branching (the box tests are unpredictable; the
  // compiler runs several at a time), then those examined. mask: bits 0-2
  // BoxGrid::first_cell_masks, bit 3 an exact triangle.
  std::array<std::vector<float>, 6> lo_hi;
  std::vector<int> face, patch, keep, hits;
  std::vector<unsigned> mask;
  std::vector<std::array<int, 3>> star;
  CancelPoll poll;
  for (size_t k = 0; k < grid.cells() && found.size() < options.max_pairs && result.complete; ++k) {
    const std::span<const int> here = grid.cell(k);
    if (moved < tris.size() && std::all_of(here.begin(), here.end(), [&](int i) { return slots[size_t(i)].exact; }))
      continue;  // only exact triangles here: nothing to examine
    const size_t m = here.size();
    for (auto& v : lo_hi) v.resize(m);
    face.resize(m);
    patch.resize(m);
    keep.resize(m);
    hits.resize(m);
    mask.resize(m);
    star.resize(m);
    const std::span<const unsigned char> first = grid.first_cell_masks(k);
    for (size_t i = 0; i < m; ++i) {
      const Slot& slot = slots[size_t(here[i])];
      for (size_t c = 0; c < 6; ++c) lo_hi[c][i] = slot.box[c];
      face[i] = slot.face;
      patch[i] = slot.patch;
      mask[i] = first[i] | (slot.exact ? 8u : 0u);
      star[i] = slot.star;
    }
    const float *x0 = lo_hi[0].data(), *y0 = lo_hi[1].data(), *z0 = lo_hi[2].data();
    const float *x1 = lo_hi[3].data(), *y1 = lo_hi[4].data(), *z1 = lo_hi[5].data();
    for (size_t i = 0; i < m && found.size() < options.max_pairs && result.complete; ++i) {
      poll.tick(std::uint32_t(std::min<size_t>(m - i, kCancelStride)));  // Ctrl-C (base/cancel.hpp)
      scanned += m - i - 1;
      if (scanned / 64 > options.max_candidates) {  // the sweep itself is cheap, not free
        result.complete = false;
        break;
      }
      // Examined: a triangle of another face and another patch whose box overlaps, in the cell
      // that owns the pair, not both exact.
      const float sx0 = x0[i], sy0 = y0[i], sz0 = z0[i], sx1 = x1[i], sy1 = y1[i], sz1 = z1[i];
      const int sf = face[i], sp = patch[i];
      const unsigned sm = mask[i];
      for (size_t j = i + 1; j < m; ++j)
        keep[j] = int(face[j] != sf) & int(patch[j] != sp) & int(x0[j] <= sx1) & int(sx0 <= x1[j]) & int(y0[j] <= sy1) & int(sy0 <= y1[j]) &
                  int(z0[j] <= sz1) & int(sz0 <= z1[j]) & int(((mask[j] | sm) & 7u) == 7u) & int((mask[j] & sm & 8u) == 0u);
      size_t count = 0;
      for (size_t j = i + 1; j < m; ++j) {
        hits[count] = int(j);
        count += size_t(keep[j]);
      }
      // Pairs that share a vertex whose star is certified meet only in what they share; the rest
      // are decided exactly, their triangles fetched ahead.
      const std::array<int, 3>& x = star[i];
      size_t left = 0;
      for (size_t h = 0; h < count; ++h) {
        const std::array<int, 3>& y = star[size_t(hits[h])];
        const bool shared = (x[0] == y[0]) | (x[0] == y[1]) | (x[0] == y[2]) | (x[1] == y[0]) | (x[1] == y[1]) |
                            (x[1] == y[2]) | (x[2] == y[0]) | (x[2] == y[1]) | (x[2] == y[2]);
        hits[left] = hits[h];
        left += shared ? 0 : 1;
      }
      for (size_t h = 0; h < left; ++h) prefetch(tris[size_t(here[size_t(hits[h])])]);
      for (size_t h = 0; h < left; ++h) {
        const size_t j = size_t(hits[h]);
        if (++candidates > options.max_candidates) {
          result.complete = false;
          break;
        }
        const auto face_pair = std::minmax(sf, face[j]);
        if (!found.empty() && found.count(face_pair)) continue;
        if (mesh::detail::triangles_meet(tris[size_t(here[i])], tris[size_t(here[j])])) {
          found.insert(face_pair);
          if (found.size() >= options.max_pairs) break;
        }
      }
    }
  }
  for (auto [a, b] : found) result.pairs.push_back({a, b});
  return result;
}

}  // namespace sculpt
