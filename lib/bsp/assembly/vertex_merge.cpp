#include "bsp/assembly/vertex_merge.hpp"

#include "base/parallel.hpp"
#include "bsp/assembly/vertex_equality.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace sculpt::bsp::detail {

using kernel::ApproxPoint;

namespace {

bool same_key(const IdTriple& x, const IdTriple& y) { return x[0] == y[0] && x[1] == y[1] && x[2] == y[2]; }

IdTriple sorted(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return {a, b, c};
}

// Corners are visited in order and each is resolved at once. A class is the set of corners with
// one triple (as a set of planes up to orientation): the same point without arithmetic. Classes
// are entered in the cells of a grid of one grid unit that their approximation's error box
// touches (far above the approximation errors: nearly always one cell). A corner looks for its
// class in its cells; a new class is compared exactly with the vertices of the classes in its
// cells and joins the one it equals, else it starts a new vertex. Equal points have overlapping
// error boxes, so they share the cell of the exact point: no equal pair is missed, and a new
// class equals at most one vertex (two equal vertices would have been merged).
//
// Grid points: where two points would be compared exactly, each whose approximation is within a
// quarter unit is first found to be a grid point or not (the nearest integers on its three
// planes: Int128 arithmetic, once per corner and vertex). A grid point equals another point
// exactly when that is the same grid point: most vertices of imported and transformed meshes are
// grid points (they are snapped), and they are merged by comparing integers instead of by the
// exact tests. Two points that are not grid points are tested exactly.
class CornerMerger {
 public:
  CornerMerger(const kernel::PlaneTable& planes, const PlaneIds& ids, AssemblyVertices& vertices,
               std::vector<int>& out, std::size_t corners)
      : planes_(planes), ids_(ids), v_(vertices), out_(out) {
    std::size_t slots = 64;
    while (slots < corners / 2) slots *= 2;
    slots_.assign(slots, Slot{0, kEmpty});
    shift_ = 32 - std::countr_zero(slots);
    entries_.reserve(corners / 2 + 16);
    v_.class_planes.reserve(corners / 2 + 16);
    v_.class_next.reserve(corners / 2 + 16);
    class_vertex_.reserve(corners / 2 + 16);
    v_.at.reserve(corners / 3 + 16);
    v_.triple.reserve(corners / 3 + 16);
    v_.first_class.reserve(corners / 3 + 16);
    vertex_ids_.reserve(corners / 3 + 16);
    vertex_grid_.reserve(corners / 3 + 16);
  }

  // Whether a point is a grid point: not yet looked at, no, yes, or not known (no usable
  // approximation).
  enum class GridStatus : std::uint8_t { Unchecked, No, Yes, Unknown };

  // What resolving a corner needs that depends on the corner alone: its class key, its
  // approximation and its cells (prepare(), safe to call from several threads at once).
  struct Pending {
    const kernel::Corner* corner;
    ApproxPoint at;   // the corner's approximation, tightened when it was loose (tight_approximation)
    std::size_t out;  // position in the output
    std::int32_t support;
    IdTriple key;
    int cells;  // -1: wide (no cells)
    std::uint32_t cell[8];
    GridStatus grid;  // whether the point is a grid point, found when first needed
    bool tightened;   // `at` is not the corner's own approximation (tight_approximation)
  };

  // Corner `c` of a fragment on plane `support` (canonical id s), whose vertex goes to out[position].
  void prepare(std::int32_t support, std::uint32_t s, const kernel::Corner& c, std::size_t out, Pending& p) const;

  // Resolves prepared corners in order (one thread): each joins its class, or a vertex it equals,
  // or makes a new one. The cells of a corner a few ahead are prefetched: the table is larger
  // than the caches and the probes are random.
  void resolve_all(std::vector<Pending>& corners) {
    constexpr std::size_t kAhead = 8;
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if (i + kAhead < corners.size() && corners[i + kAhead].cells > 0)
        __builtin_prefetch(&slots_[corners[i + kAhead].cell[0] >> shift_]);
      resolve(corners[i]);
    }
  }

 private:
  static constexpr int kEmpty = -1, kNoEntry = -2;
  // Cells are identified by 32 bits of a hash of their coordinates (21 bits of each, folded):
  // cells that collide share a chain and are told apart by the approximations. The slot of a
  // hash is its top bits, so the table can grow without the coordinates.
  struct Slot {
    std::uint32_t cell;
    int head;  // last entry of the cell's chain: kNoEntry if none yet, kEmpty: free slot
  };
  struct Entry {  // a class entered in one cell
    IdTriple key;
    int vertex, next;
  };
  static std::int64_t floor_of(double x) {  // |x| < 2^61
    const auto t = std::int64_t(x);
    return double(t) > x ? t - 1 : t;
  }

  // The corner's approximation, or, when its error bound is a quarter grid unit or more (nearly
  // dependent planes: where a fine sphere's cap meets its almost flat fan, up to 3.9 grid units at
  // 512 segments), the exact vertex correctly rounded (kernel::rounded_vertex) with a bound of one
  // unit in the last place. A loose corner has no cells and takes the wide path, which compares
  // every later class with it: 1024 of them took a third of `sphere(1, 512) - moved copy`.
  ApproxPoint tight_approximation(std::int32_t support, const kernel::Corner& c) const {
    const ApproxPoint a = c.at();
    if (!(a.err >= 0.25) || !std::isfinite(a.err)) return a;
    const double largest = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)});
    if (a.err <= std::ldexp(largest, -50)) return a;  // rounded_vertex would return it as it is
    const Eigen::Vector3d r = kernel::rounded_vertex(planes_[support], planes_[c.p], planes_[c.q], a);
    const double rounded_largest = r.cwiseAbs().maxCoeff();
    return {r.x(), r.y(), r.z(), std::ldexp(rounded_largest, -52)};
  }

  void resolve(Pending& p) {
    const IdTriple& key = p.key;
    const kernel::Corner& c = *p.corner;
    if (p.cells < 0) {
      out_[p.out] = wide_vertex(key, p.support, c, p.at);
      return;
    }
    if (2 * (cells_used_ + 8) > slots_.size()) grow();
    const int n = p.cells;
    std::size_t cells[8];
    for (int i = 0; i < n; ++i) cells[i] = slot_of(p.cell[i]);
    for (int i = 0; i < n; ++i)
      for (int e = slots_[cells[i]].head; e >= 0; e = entries_[std::size_t(e)].next)
        if (same_key(entries_[std::size_t(e)].key, key)) {
          out_[p.out] = entries_[std::size_t(e)].vertex;
          return;
        }
    for (const int w : wide_classes_)
      if (same_key(v_.class_planes[std::size_t(w)], key)) {
        out_[p.out] = class_vertex_[std::size_t(w)];
        return;
      }
    int v = -1;
    int last = -1;  // a vertex's classes tend to be adjacent in a chain: test it once
    for (int i = 0; i < n && v < 0; ++i)
      for (int e = slots_[cells[i]].head; e >= 0 && v < 0; e = entries_[std::size_t(e)].next) {
        const int u = entries_[std::size_t(e)].vertex;
        if (u != last && same_point(key, p.support, c, p.at, p.grid, u)) v = u;
        last = u;
      }
    for (std::size_t i = 0; i < wide_classes_.size() && v < 0; ++i) {
      const int u = class_vertex_[std::size_t(wide_classes_[i])];
      if (same_point(key, p.support, c, p.at, p.grid, u)) v = u;
    }
    // The vertex keeps its first corner's approximation, so it inherits what was found from
    // that one only.
    if (v < 0) v = new_vertex(p.support, c, p.tightened ? GridStatus::Unchecked : p.grid);
    new_class(key, v);
    for (int i = 0; i < n; ++i) {
      entries_.push_back({key, v, slots_[cells[i]].head});
      slots_[cells[i]].head = int(entries_.size()) - 1;
    }
    out_[p.out] = v;
  }

  std::size_t slot_of(std::uint32_t cell) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t h = cell >> shift_;
    while (slots_[h].head != kEmpty && slots_[h].cell != cell) h = (h + 1) & mask;
    if (slots_[h].head == kEmpty) slots_[h] = {cell, kNoEntry}, ++cells_used_;
    return h;
  }

  void grow() {
    // Chains keep their entries; only the slots move.
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(2 * old.size(), Slot{0, kEmpty});
    shift_ = 32 - std::countr_zero(slots_.size());
    const std::size_t mask = slots_.size() - 1;
    for (const Slot& s : old) {
      if (s.head == kEmpty) continue;
      std::size_t h = s.cell >> shift_;
      while (slots_[h].head != kEmpty) h = (h + 1) & mask;
      slots_[h] = s;
    }
  }

  std::uint32_t key_of(std::int32_t plane) const { return ids_.id[std::size_t(plane)]; }

  // Whether the point s ∩ p ∩ q with approximation `a` is a grid point: the nearest integers are
  // the only candidates when the error bound is under a quarter unit, and one is when it lies on
  // the three planes exactly. Unknown for a looser bound, or beyond 2^40 units (there the Int128
  // values could overflow: |a x| <= 2^53 * 2^40, three of them, and |d| <= 2^80).
  GridStatus grid_point(std::int32_t s, std::int32_t p, std::int32_t q, const ApproxPoint& a) const {
    constexpr double kLimit = 0x1p40;
    if (!(a.err >= 0 && a.err < 0.25) ||
        !(std::fabs(a.x) < kLimit && std::fabs(a.y) < kLimit && std::fabs(a.z) < kLimit))
      return GridStatus::Unknown;
    // Most points off the grid end at the first coordinate, without a call or a plane read.
    if (!(std::fabs(a.x - nearest_integer(a.x)) <= a.err && std::fabs(a.y - nearest_integer(a.y)) <= a.err &&
          std::fabs(a.z - nearest_integer(a.z)) <= a.err))
      return GridStatus::No;
    const kernel::GridPoint g = nearest_grid_point(a);
    const bool yes = planes_[s].eval(g) == 0 && planes_[p].eval(g) == 0 && planes_[q].eval(g) == 0;
    return yes ? GridStatus::Yes : GridStatus::No;
  }
  // The integer nearest to x, |x| < 2^51 (adding and subtracting 1.5 * 2^52 rounds to an integer
  // in double arithmetic, ties to even).
  static double nearest_integer(double x) {
    constexpr double kRound = 0x1.8p52;
    return (x + kRound) - kRound;
  }
  // The grid point of an approximation found to be one (Yes: within a quarter unit of it).
  static kernel::GridPoint nearest_grid_point(const ApproxPoint& a) {
    return {std::int64_t(nearest_integer(a.x)), std::int64_t(nearest_integer(a.y)), std::int64_t(nearest_integer(a.z))};
  }

  // A class joins its vertex's list (the vertex's known planes) and the class table (the wide path).
  int new_class(const IdTriple& key, int vertex) {
    const int k = int(v_.class_planes.size());
    v_.class_planes.push_back(key);
    v_.class_next.push_back(v_.first_class[std::size_t(vertex)]);
    v_.first_class[std::size_t(vertex)] = k;
    class_vertex_.push_back(vertex);
    return k;
  }

  int new_vertex(std::int32_t support, const kernel::Corner& c, GridStatus grid) {
    vertex_grid_.push_back(grid);
    v_.at.push_back(c.at());
    v_.triple.push_back({support, c.p, c.q});
    vertex_ids_.push_back({key_of(support), key_of(c.p), key_of(c.q)});
    v_.first_class.push_back(-1);
    return v_.size() - 1;
  }

  // A corner without cells (large or no error bound: nearly dependent planes): its class by
  // key, else exact comparison with every vertex.
  int wide_vertex(const IdTriple& key, std::int32_t support, const kernel::Corner& c, const ApproxPoint& at) {
    for (std::size_t i = 0; i < v_.class_planes.size(); ++i)
      if (same_key(v_.class_planes[i], key)) return class_vertex_[i];
    int v = -1;
    GridStatus grid = GridStatus::Unchecked;
    for (int u = 0; u < v_.size() && v < 0; ++u)
      if (same_point(key, support, c, at, grid, u)) v = u;
    if (v < 0) v = new_vertex(support, c, grid);
    wide_classes_.push_back(new_class(key, v));
    return v;
  }

  // Exact: the corner's point (support ∩ p ∩ q, canonical ids `key`) lies on the three planes
  // of vertex u's triple (planes shared with the corner need no test; the others by the exact
  // zero test of vertex_equality.hpp). Disjoint error boxes are different points (a filter only).
  bool same_point(const IdTriple& key, std::int32_t support, const kernel::Corner& c, const ApproxPoint& pa,
                  GridStatus& grid, int u) {
    const ApproxPoint& pb = v_.at[std::size_t(u)];
    if (pa.err >= 0 && pb.err >= 0) {
      const double tol = pa.err + pb.err;
      if (std::fabs(pb.x - pa.x) > tol || std::fabs(pb.y - pa.y) > tol || std::fabs(pb.z - pa.z) > tol) return false;
    }
    const PlaneTriple& t = v_.triple[std::size_t(u)];
    if (grid == GridStatus::Unchecked) grid = grid_point(support, c.p, c.q, pa);
    GridStatus& vertex_grid = vertex_grid_[std::size_t(u)];
    if (vertex_grid == GridStatus::Unchecked) vertex_grid = grid_point(t.s, t.p, t.q, pb);
    const bool known = grid != GridStatus::Unknown && vertex_grid != GridStatus::Unknown;
    if (known && (grid == GridStatus::Yes || vertex_grid == GridStatus::Yes))
      return grid == vertex_grid && nearest_grid_point(pa) == nearest_grid_point(pb);
    const IdTriple& ids = vertex_ids_[std::size_t(u)];
    const std::int32_t planes[3] = {t.s, t.p, t.q};
    std::int32_t tested[3];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t id = ids[std::size_t(i)];
      if (id != key[0] && id != key[1] && id != key[2]) tested[n++] = planes[i];
    }
    if (n == 0) return true;
    // The corner's 2x2 minors, shared by its (usually two) tests (built in place: no copy).
    const VertexMinors corner = vertex_minors(planes_[support], planes_[c.p], planes_[c.q], pa);
    for (int i = 0; i < n; ++i)
      if (!vertex_on_plane(corner, planes_[tested[i]])) return false;
    return true;
  }

  const kernel::PlaneTable& planes_;
  const PlaneIds& ids_;
  AssemblyVertices& v_;
  std::vector<int>& out_;
  std::vector<Slot> slots_;
  int shift_ = 26;
  std::size_t cells_used_ = 0;  // occupied slots
  std::vector<Entry> entries_;
  std::vector<int> class_vertex_;  // class -> vertex (keys in v_.class_planes)
  std::vector<int> wide_classes_;
  std::vector<IdTriple> vertex_ids_;  // vertex -> canonical ids of its triple, in triple order
  std::vector<GridStatus> vertex_grid_;  // vertex -> whether it is a grid point
};

void CornerMerger::prepare(std::int32_t support, std::uint32_t s, const kernel::Corner& c, std::size_t out,
                           Pending& p) const {
  p.corner = &c;
  p.out = out;
  p.support = support;
  p.key = sorted(s, ids_.id[std::size_t(c.p)], ids_.id[std::size_t(c.q)]);
  const ApproxPoint a = tight_approximation(support, c);
  p.at = a;
  p.tightened = a.err != c.at().err;
  constexpr double kShift = 0.3711;  // grid points never sit on a cell boundary
  constexpr double kFar = 0x1p60;    // beyond: no cells (the brute-force path)
  std::int64_t lo[3], hi[3];
  bool wide = !(a.err >= 0 && a.err < 0.25);
  const double coord[3] = {a.x, a.y, a.z};
  for (int k = 0; k < 3 && !wide; ++k) {
    wide = !(std::fabs(coord[k]) < kFar);
    lo[k] = floor_of(coord[k] - a.err + kShift);
    hi[k] = floor_of(coord[k] + a.err + kShift);
  }
  p.cells = -1;
  p.grid = GridStatus::Unchecked;
  if (wide) return;
  // The cells of the error box (at most two per axis).
  constexpr std::uint64_t kMask = (std::uint64_t(1) << 21) - 1;
  int n = 0;
  for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
        const std::uint64_t k =
            (std::uint64_t(x) & kMask) << 42 | (std::uint64_t(y) & kMask) << 21 | (std::uint64_t(z) & kMask);
        p.cell[n++] = std::uint32_t((k * 0x9E3779B97F4A7C15ull) >> 32);
      }
  p.cells = n;
}

}  // namespace

MergedFragments merge_vertices(FragmentsView fragments) {
  const FragmentList& list = fragments.fragments;
  const std::size_t nf = list.size();
  // Fragments a piece. A wave's prepared corners (about 110 bytes each) are scratch held beside
  // the result: pieces of 1024 held 2.7 MB with two threads, which set small jobs' peaks (fandisk
  // 33.3 -> 29.7 MB with 256; larger jobs and times unchanged, docs/benchmarks.md "Session 40").
  constexpr std::size_t kGrain = 256;
  MergedFragments r;
  r.ids = canonical_plane_ids(fragments.planes);
  FaceList& faces = r.faces;
  faces.start.resize(nf + 1);
  faces.support.resize(nf);
  faces.flip.resize(nf);
  parallel_chunks(nf, kGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      faces.start[f + 1] = int(list[f].polygon.corners.size());
      faces.support[f] = list[f].polygon.support;
      faces.flip[f] = list[f].flip ? 1 : 0;
    }
  });
  faces.start[0] = 0;
  for (std::size_t f = 0; f < nf; ++f) faces.start[f + 1] += faces.start[f];
  const std::size_t corners = std::size_t(faces.start[nf]);
  faces.vertex.resize(corners);
  faces.line.resize(corners);
  CornerMerger merger(fragments.planes, r.ids, r.vertices, faces.vertex, corners);
  // Corners are prepared in parallel, a wave of pieces at a time, and resolved in order.
  using Pending = CornerMerger::Pending;
  parallel_waves<std::vector<Pending>>(
      nf, kGrain,
      [&](std::size_t begin, std::size_t end, std::vector<Pending>& out) {
        out.resize(std::size_t(faces.start[end] - faces.start[begin]));
        std::size_t k = 0;
        for (std::size_t f = begin; f < end; ++f) {
          const FragmentRef fr = list[f];
          const auto& cs = fr.polygon.corners;
          const std::size_t m = cs.size(), base = std::size_t(faces.start[f]);
          const std::uint32_t s = r.ids.id[std::size_t(fr.polygon.support)];
          // A flipped fragment's corners reversed: corner j goes to position m-1-j, and its edge
          // (to corner j+1) becomes the edge leaving position m-1-(j+1).
          for (std::size_t j = 0; j < m; ++j) {
            merger.prepare(fr.polygon.support, s, cs[j], base + (fr.flip ? m - 1 - j : j), out[k++]);
            faces.line[base + (fr.flip ? m - 1 - (j + 1 == m ? 0 : j + 1) : j)] = cs[j].edge;
          }
        }
      },
      [&](std::vector<Pending>& out) { merger.resolve_all(out); });
  return r;
}

}  // namespace sculpt::bsp::detail
