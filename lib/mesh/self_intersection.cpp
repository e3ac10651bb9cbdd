#include "mesh/self_intersection.hpp"
#include "base/cancel.hpp"
#include "base/parallel.hpp"

#include <algorithm>
#include <array>
#include <atomic>
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
#include "mesh/detail/moved_neighbourhood.hpp"
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

/// What the scan of the cells reads per triangle.
struct Slot {
  std::array<float, 6> box{};  // min x, y, z, max x, y, z, as_float
  int face = 0;
  bool exact = false;  // every corner of its face is marked exact (SelfIntersectionOptions)
  // Per corner: its id where the vertex's star is certified, else -1 - (its triangle): no
  // corner of another triangle has that number.
  std::array<int, 3> star{};
  int patch = 0;  // certified_patches
};

/// What the search keeps per triangle, for a run of faces: the exact tests' data and what the
/// scan reads; and how many of them belong to faces with a corner not marked exact. (What the
/// stars' certification and the grid read is made from these when needed, and freed after: on
/// a million triangles each is about 50 MB.)
struct PreparedFaces {
  std::vector<PreparedTriangle> tris;
  std::vector<Slot> slots;
  size_t moved = 0;

  void reserve(size_t n) { tris.reserve(n), slots.reserve(n); }
  void append(const PreparedFaces& o) {
    tris.insert(tris.end(), o.tris.begin(), o.tris.end());
    slots.insert(slots.end(), o.slots.begin(), o.slots.end());
    moved += o.moved;
  }
  void clear() {  // keeps the storage for the next wave
    tris.clear(), slots.clear();
    moved = 0;
  }
};

Eigen::AlignedBox3d box_of(const PreparedTriangle& t) {
  Eigen::AlignedBox3d box;
  for (int k = 0; k < 3; ++k) box.extend(t.p[size_t(k)]);
  return box;
}

/// Faces [begin, end) of `mesh` triangulated and prepared into `out` (appended, in face order),
/// those that `wanted` (one flag per face, or empty: all) marks.
/// \throw InvalidInput as triangulate_polygon.
template <typename ExactFace>
void prepare_faces(const PolygonMesh& mesh, const std::vector<int>& canon, const ExactFace& exact_face,
                   const std::vector<char>& wanted, size_t begin, size_t end, PreparedFaces& out) {
  PolygonTriangulator triangulator;
  std::vector<IndexTriangle> face_tris;
  CancelPoll poll;
  for (size_t fi = begin; fi < end; ++fi) {
    poll.tick();
    if (!wanted.empty() && wanted[fi] == 0) continue;
    const bool exact = exact_face(mesh.faces[fi]);
    face_tris.clear();
    triangulator.append(mesh.vertices, mesh.faces[fi], face_tris, EarOrder::Spread);
    for (const IndexTriangle& it : face_tris) {
      const PreparedTriangle t =
          mesh::detail::prepare_triangle({canon[it[0]], canon[it[1]], canon[it[2]]},
                                         {mesh.vertices[it[0]], mesh.vertices[it[1]], mesh.vertices[it[2]]});
      if (t.axis < 0) continue;  // collinear corners: degenerate, reported elsewhere
      const Eigen::AlignedBox3d box = box_of(t);
      Slot slot;
      for (int k = 0; k < 3; ++k) {
        slot.box[size_t(k)] = as_float(box.min()[k]);
        slot.box[size_t(k) + 3] = as_float(box.max()[k]);
      }
      slot.face = static_cast<int>(fi);
      slot.exact = exact;
      slot.star = t.ids;
      out.tris.push_back(t);
      out.slots.push_back(slot);
      out.moved += exact ? 0 : 1;
    }
  }
}

/// Cells per parallel run: about this many cell entries (a run of the scan costs about 10 us per entry).
constexpr size_t kMembersPerRun = 4096;

struct ScanInput {
  const mesh::detail::BoxGrid& grid;
  const std::vector<Slot>& slots;
  const std::vector<PreparedTriangle>& tris;
  const SelfIntersectionOptions& options;
  bool some_exact;  // some triangle is marked exact
};

/// What a run of cells found: face pairs (at most options.max_pairs), the candidate pairs examined
/// and the pairs scanned, and whether it stopped on the budget (complete = false).
struct CellScan {
  std::set<std::pair<int, int>> found;
  size_t candidates = 0, scanned = 0;
  bool complete = true;
};

/// Examines the pairs owned by cells [first, last) of the grid.
CellScan scan_cells(const ScanInput& in, size_t first, size_t last) {
  CellScan out;
  const SelfIntersectionOptions& options = in.options;
  const auto& slots = in.slots;
  const auto& tris = in.tris;
  // Per cell: its members gathered field by field, then for each member the later members whose
  // boxes overlap its own collected without branching (the box tests are unpredictable; the
  // compiler runs several at a time), then those examined. mask: bits 0-2
  // BoxGrid::first_cell_masks, bit 3 an exact triangle.
  std::array<std::vector<float>, 6> lo_hi;
  std::vector<int> face, patch, keep, hits;
  std::vector<unsigned> mask;
  std::vector<std::array<int, 3>> star;
  CancelPoll poll;
  std::set<std::pair<int, int>>& found = out.found;
  for (size_t k = first; k < last && found.size() < options.max_pairs && out.complete; ++k) {
    const std::span<const int> here = in.grid.cell(k);
    if (in.some_exact && std::all_of(here.begin(), here.end(), [&](int i) { return slots[size_t(i)].exact; }))
      continue;  // only exact triangles here: nothing to examine
    const size_t m = here.size();
    for (auto& v : lo_hi) v.resize(m);
    face.resize(m);
    patch.resize(m);
    keep.resize(m);
    hits.resize(m);
    mask.resize(m);
    star.resize(m);
    const std::span<const unsigned char> first_masks = in.grid.first_cell_masks(k);
    for (size_t i = 0; i < m; ++i) {
      const Slot& slot = slots[size_t(here[i])];
      for (size_t c = 0; c < 6; ++c) lo_hi[c][i] = slot.box[c];
      face[i] = slot.face;
      patch[i] = slot.patch;
      mask[i] = first_masks[i] | (slot.exact ? 8u : 0u);
      star[i] = slot.star;
    }
    const float *x0 = lo_hi[0].data(), *y0 = lo_hi[1].data(), *z0 = lo_hi[2].data();
    const float *x1 = lo_hi[3].data(), *y1 = lo_hi[4].data(), *z1 = lo_hi[5].data();
    for (size_t i = 0; i < m && found.size() < options.max_pairs && out.complete; ++i) {
      poll.tick(std::uint32_t(std::min<size_t>(m - i, kCancelStride)));  // Ctrl-C (base/cancel.hpp)
      out.scanned += m - i - 1;
      if (out.scanned / 64 > options.max_candidates) {  // the sweep itself is cheap, not free
        out.complete = false;
        break;
      }
      // Examined: a triangle of another face and another patch whose box overlaps, in the cell
      // that owns the pair, not both exact.
      const float sx0 = x0[i], sy0 = y0[i], sz0 = z0[i], sx1 = x1[i], sy1 = y1[i], sz1 = z1[i];
      const int sf = face[i], sp = patch[i];
      const unsigned sm = mask[i];
      for (size_t j = i + 1; j < m; ++j)
        keep[j] = int(face[j] != sf) & int(patch[j] != sp) & int(x0[j] <= sx1) & int(sx0 <= x1[j]) & int(y0[j] <= sy1) &
                  int(sy0 <= y1[j]) & int(z0[j] <= sz1) & int(sz0 <= z1[j]) & int(((mask[j] | sm) & 7u) == 7u) &
                  int((mask[j] & sm & 8u) == 0u);
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
        if (++out.candidates > options.max_candidates) {
          out.complete = false;
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
  return out;
}

}  // namespace

bool triangles_meet(const std::array<int, 3>& ids_a, const std::array<Vector3d, 3>& a, const std::array<int, 3>& ids_b,
                    const std::array<Vector3d, 3>& b) {
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
  const std::vector<int> canon =
      options.distinct_vertices ? identity_ids(nv) : mesh::detail::first_copies(mesh.vertices);

  // Faces with every corner marked exact (the flags are used only when there is one per vertex):
  // pairs of their triangles are not examined (see SelfIntersectionOptions::exact_vertices).
  const bool marked = !options.exact_vertices.empty() && options.exact_vertices.size() == nv;
  auto exact_face = [&](const std::vector<int>& f) {
    return marked && std::all_of(f.begin(), f.end(), [&](int v) { return options.exact_vertices[size_t(v)] != 0; });
  };
  if (marked && std::all_of(mesh.faces.begin(), mesh.faces.end(), exact_face)) return result;
  // With marks, a face whose box meets no box of a face with an unmarked corner is in no pair
  // that is examined: only the others are prepared (mesh/detail/moved_neighbourhood.hpp).
  const std::vector<char> wanted =
      marked ? mesh::detail::faces_near_moved(mesh, options.exact_vertices) : std::vector<char>{};
  // Per triangle: what the exact tests read, its box, what the stars' certification reads, its
  // class and what the scan reads (Slot).
  PreparedFaces all;
  {
    size_t corners = 0;
    for (const auto& f : mesh.faces) corners += f.size() >= 2 ? f.size() - 2 : 0;
    all.reserve(corners);
  }
  // Faces in chunks on every core, in waves (parallel_waves): the lists are those of one pass in
  // face order (the same for any thread count) and the scratch holds one wave. A face that cannot
  // be triangulated throws as that pass would: the first such face's error, in face order.
  constexpr size_t kFaceChunk = 2048;
  parallel_waves<PreparedFaces>(
      mesh.faces.size(), kFaceChunk,
      [&](size_t begin, size_t end, PreparedFaces& part) {
        check_cancel();  // Ctrl-C (base/cancel.hpp): a second or more on millions of triangles
        prepare_faces(mesh, canon, exact_face, wanted, begin, end, part);
      },
      [&](PreparedFaces& part) {
        all.append(part);
        part.clear();
      });
  const std::vector<PreparedTriangle>& tris = all.tris;
  std::vector<Slot>& slots = all.slots;
  const size_t moved = all.moved;
  if (moved == 0) return result;
  constexpr size_t kChunk = 8192;
  // Pairs that share a vertex whose star is certified are not examined (certified_stars), nor
  // pairs of one certified patch (certified_patches).
  {
    // Per triangle what the certification reads, and its class for certified_patches: its axis
    // and the sign of its projection there, or -1 where the filter leaves that sign open.
    std::vector<mesh::detail::StarTriangle> stars(tris.size());
    std::vector<signed char> cls(tris.size());
    parallel_chunks(tris.size(), kChunk, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        stars[i] = mesh::detail::star_triangle(tris[i]);
        const int sign = stars[i].sign[size_t(tris[i].axis)];
        cls[i] = static_cast<signed char>(sign == 1 || sign == -1 ? 2 * tris[i].axis + (sign > 0 ? 1 : 0) : -1);
      }
    });
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
  const mesh::detail::BoxGrid grid = [&] {
    std::vector<Eigen::AlignedBox3d> boxes(tris.size());  // (the scan reads the slots' float boxes)
    parallel_chunks(tris.size(), kChunk, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) boxes[i] = box_of(tris[i]);
    });
    return mesh::detail::BoxGrid(boxes);
  }();
  // The cells in runs of about kMembersPerRun entries, scanned in parallel (base/parallel.hpp).
  // A run's bounds depend on the grid only, and the runs' findings are joined in run order, so the
  // pairs and the verdict are the same for every thread count.
  std::vector<size_t> run_starts{0};
  for (size_t k = 0, members = 0; k < grid.cells(); ++k) {
    members += grid.cell(k).size();
    if (members >= kMembersPerRun && k + 1 < grid.cells()) run_starts.push_back(k + 1), members = 0;
  }
  run_starts.push_back(grid.cells());
  const size_t runs = run_starts.size() - 1;
  std::vector<CellScan> scans(runs);
  // Runs after one that found max_pairs by itself cannot change the result (their pairs come
  // later in the join): they are skipped.
  std::atomic<size_t> filled(runs);
  const ScanInput input{grid, slots, tris, options, moved < tris.size()};
  parallel_chunks(runs, 1, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      if (r > filled.load(std::memory_order_relaxed)) continue;
      scans[r] = scan_cells(input, run_starts[r], run_starts[r + 1]);
      if (scans[r].found.size() >= options.max_pairs) {
        size_t seen = filled.load(std::memory_order_relaxed);
        while (r < seen && !filled.compare_exchange_weak(seen, r, std::memory_order_relaxed)) {}
      }
    }
  });
  std::set<std::pair<int, int>> found;
  size_t candidates = 0, scanned = 0;
  for (size_t r = 0; r < runs && r <= filled.load(); ++r) {
    candidates += scans[r].candidates;
    scanned += scans[r].scanned;
    result.complete = result.complete && scans[r].complete;
    for (const auto& pair : scans[r].found) {
      if (found.size() >= options.max_pairs) break;
      found.insert(pair);
    }
  }
  if (candidates > options.max_candidates || scanned / 64 > options.max_candidates) result.complete = false;
  for (auto [a, b] : found) result.pairs.push_back({a, b});
  return result;
}

}  // namespace sculpt
