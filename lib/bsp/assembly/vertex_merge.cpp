#include "bsp/assembly/vertex_merge.hpp"

#include "base/parallel.hpp"
#include "bsp/assembly/vertex_equality.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>

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

// Corners are visited in order. A class is the set of corners with one triple (as a set of
// planes up to orientation): the same point without arithmetic. Classes are entered in the cells
// of a grid of one grid unit that their approximation's error box touches (far above the
// approximation errors: nearly always one cell). Equal points have overlapping error boxes, so
// they share the cell of the exact point: a class equal to an earlier one finds it among the
// classes entered before it in its cells (or among the wide classes, which have no cells).
//
// Three passes, so that the exact tests run on every core and the result does not depend on the
// thread count:
// 1. In order (one thread): each corner finds its class by key in its cells, or starts one and
//    enters it there (resolve_all).
// 2. Each class, side by side: the first class it meets in its cells' chains (newest first, then
//    the wide classes made before it) that is the same point, exactly (link_classes). Equality of
//    points is an equivalence, so the class that is found does not change the vertex.
// 3. In order: a class that found none starts a vertex (numbered in the order of their first
//    corner); the others take the vertex of the class they found (number_vertices).
//
// Grid points: where two points would be compared exactly, each whose approximation is within a
// quarter unit is first found to be a grid point or not (the nearest integers on its three
// planes: Int128 arithmetic, once per class). A grid point equals another point exactly when that
// is the same grid point: most vertices of imported and transformed meshes are grid points (they
// are snapped), and they are merged by comparing integers instead of by the exact tests. Two
// points that are not grid points are tested exactly.
//
// Grid corners: a corner found to be a grid point when it is prepared (on every core) is looked
// up by that point in pass 1, and takes the class of the first corner there: one class per grid
// vertex instead of one per triple. Round a vertex of a triangle mesh each of its six or so
// corners has its own triple, so a million imported triangles made three million classes (200 MB
// of the 10^6-triangle job's peak); now about half a million. A corner at that point that is not
// known to be a grid point (a loose approximation) still finds the class through its cells in
// pass 2, as before.
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
    class_corner_.reserve(corners / 2 + 16);
    class_support_.reserve(corners / 2 + 16);
    class_entries_.reserve(corners / 2 + 16);
    class_entries_.push_back(0);
    grid_slots_.assign(64, GridSlot{});  // grows with the grid vertices: nothing for a sphere's
  }

  // Whether a point is a grid point: not yet looked at, no, yes, or not known (no usable
  // approximation).
  enum class GridStatus : std::uint8_t { Unchecked, No, Yes, Unknown };

  // What resolving a corner needs that depends on the corner alone: its class key and its
  // cells (prepare(), safe to call from several threads at once).
  struct Pending {
    const kernel::Corner* corner;
    std::size_t out;  // position in the output
    std::int32_t support;
    IdTriple key;
    int cells;  // -1: wide (no cells)
    std::uint32_t cell[8];
    bool on_grid;         // the corner is exactly the grid point `g`
    kernel::GridPoint g;  // (only when on_grid)
  };

  // Corner `c` of a fragment on plane `support` (canonical id s), whose class goes to out[position].
  void prepare(std::int32_t support, std::uint32_t s, const kernel::Corner& c, std::size_t out, Pending& p) const;

  // Pass 1 over prepared corners in order (one thread): out[corner] is its class. The cells of a
  // corner a few ahead are prefetched: the table is larger than the caches and the probes are
  // random.
  void resolve_all(std::vector<Pending>& corners) {
    constexpr std::size_t kAhead = 8;
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if (i + kAhead < corners.size() && corners[i + kAhead].cells > 0)
        __builtin_prefetch(&slots_[corners[i + kAhead].cell[0] >> shift_]);
      resolve(corners[i]);
    }
  }

  // Passes 2 and 3, after every corner was resolved: out[corner] becomes its vertex.
  void finish() {
    std::vector<int> link = link_classes();
    number_vertices(link);
    parallel_chunks(out_.size(), std::size_t(1) << 16, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) out_[i] = link[std::size_t(out_[i])];
    });
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
    int cls, next;  // next: the entry made before it in the cell's chain
  };
  static std::int64_t floor_of(double x) {  // |x| < 2^61
    const auto t = std::int64_t(x);
    return double(t) > x ? t - 1 : t;
  }

  // The corner's class: a grid corner's is that of its grid point, if there is one yet.
  void resolve(const Pending& p) {
    GridSlot* slot = p.on_grid ? &grid_slot(p.g) : nullptr;
    if (slot != nullptr && slot->cls >= 0) {
      out_[p.out] = slot->cls;
      return;
    }
    const int k = class_of(p);
    out_[p.out] = k;
    if (slot != nullptr) {  // (class_of never touches the grid table: the slot is still valid)
      *slot = {p.g, k};
      if (2 * ++grid_used_ > grid_slots_.size()) grow_grid();
    }
  }

  // The corner's class by its key (in its cells, or among all classes for a wide corner), else a new one.
  int class_of(const Pending& p) {
    const IdTriple& key = p.key;
    if (p.cells < 0) {  // wide: its class by key among all classes, else a new one
      for (std::size_t i = 0; i < v_.class_planes.size(); ++i)
        if (same_key(v_.class_planes[i], key)) return int(i);
      const int k = new_class(p);
      wide_classes_.push_back(k);
      return k;
    }
    if (2 * (cells_used_ + 8) > slots_.size()) grow();
    const int n = p.cells;
    std::size_t cells[8];
    for (int i = 0; i < n; ++i) cells[i] = slot_of(p.cell[i]);
    for (int i = 0; i < n; ++i)
      for (int e = slots_[cells[i]].head; e >= 0; e = entries_[std::size_t(e)].next)
        if (same_key(entries_[std::size_t(e)].key, key)) return entries_[std::size_t(e)].cls;
    for (const int w : wide_classes_)
      if (same_key(v_.class_planes[std::size_t(w)], key)) return w;
    const int k = new_class(p);
    for (int i = 0; i < n; ++i) {
      entries_.push_back({key, k, slots_[cells[i]].head});
      slots_[cells[i]].head = int(entries_.size()) - 1;
    }
    class_entries_.back() = int(entries_.size());
    return k;
  }

  // The grid table: open addressing on a hash of the point (grows at half full).
  struct GridSlot {
    kernel::GridPoint g{};
    int cls = -1;  // -1: free
  };
  std::size_t grid_hash(const kernel::GridPoint& g) const {
    const std::uint64_t h = (std::uint64_t(g.x) * 0x9E3779B97F4A7C15ull) ^
                            (std::uint64_t(g.y) * 0xC2B2AE3D27D4EB4Full) ^ (std::uint64_t(g.z) * 0x165667B19E3779F9ull);
    return std::size_t(h ^ (h >> 29)) & (grid_slots_.size() - 1);
  }
  GridSlot& grid_slot(const kernel::GridPoint& g) {
    const std::size_t mask = grid_slots_.size() - 1;
    std::size_t h = grid_hash(g);
    while (grid_slots_[h].cls >= 0 && !(grid_slots_[h].g == g)) h = (h + 1) & mask;
    return grid_slots_[h];
  }
  void grow_grid() {
    std::vector<GridSlot> old = std::move(grid_slots_);
    grid_slots_.assign(2 * old.size(), GridSlot{});
    for (const GridSlot& o : old)
      if (o.cls >= 0) grid_slot(o.g) = o;
  }

  // A class: its key, first corner and where its entries end (they start where the previous
  // class's end).
  int new_class(const Pending& p) {
    const int k = int(v_.class_planes.size());
    v_.class_planes.push_back(p.key);
    class_corner_.push_back(p.corner);
    class_support_.push_back(p.support);
    class_entries_.push_back(class_entries_.back());
    wide_before_.push_back(int(wide_classes_.size()));
    class_on_grid_.push_back(p.on_grid ? 1 : 0);
    return k;
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

  // Pass 2: link[k] = an earlier class that is the same point as class k, or -1 (each class on
  // its own: the same links for any thread count). A class's candidates are the classes entered
  // before it in its cells, newest first (the same vertex's classes are usually adjacent in a
  // chain), then the wide classes made before it; a wide class's are all earlier classes.
  std::vector<int> link_classes() {
    const std::size_t count = v_.class_planes.size();
    std::vector<int> link(count, -1);
    grid_.reset(new std::atomic<GridStatus>[count]);
    for (std::size_t k = 0; k < count; ++k)
      grid_[k].store(class_on_grid_[k] != 0 ? GridStatus::Yes : GridStatus::Unchecked, std::memory_order_relaxed);
    parallel_chunks(count, 4096, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        const auto cls = int(k);
        if (wide_before_[k] < int(wide_classes_.size()) && wide_classes_[std::size_t(wide_before_[k])] == cls) {
          for (int j = cls - 1; j >= 0 && link[k] < 0; --j)
            if (same_point(cls, j)) link[k] = j;
          continue;
        }
        Probe probe(*this, cls);
        for (int e = class_entries_[k]; e < class_entries_[k + 1] && link[k] < 0; ++e)
          for (int c = entries_[std::size_t(e)].next; c >= 0 && link[k] < 0; c = entries_[std::size_t(c)].next)
            if (probe.equals(entries_[std::size_t(c)].cls)) link[k] = entries_[std::size_t(c)].cls;
        for (int w = 0; w < wide_before_[k] && link[k] < 0; ++w)
          if (probe.equals(wide_classes_[std::size_t(w)])) link[k] = wide_classes_[std::size_t(w)];
      }
    });
    return link;
  }

  // Pass 3, in class order: link[k] becomes class k's vertex. A class that found no earlier one
  // starts a vertex with its first corner's triple and approximation; the others take the vertex
  // of the earlier class they found (already numbered). Each class joins its vertex's list.
  void number_vertices(std::vector<int>& link) {
    const std::size_t count = link.size();
    v_.class_next.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      int v = link[k];
      if (v < 0) {
        const kernel::Corner& c = *class_corner_[k];
        v = v_.size();
        // A grid point's approximation is the point itself (exact: within 2^40, grid_point).
        if (class_on_grid_[k] != 0) {
          const kernel::GridPoint g = nearest_grid_point(class_at(int(k)));
          v_.at.push_back({double(g.x), double(g.y), double(g.z), 0.0});
        } else {
          v_.at.push_back(c.at());
        }
        v_.on_grid.push_back(class_on_grid_[k]);
        v_.triple.push_back({class_support_[k], c.p, c.q});
        v_.first_class.push_back(-1);
      } else {
        v = link[std::size_t(v)];
      }
      link[k] = v;
      v_.class_next[k] = v_.first_class[std::size_t(v)];
      v_.first_class[std::size_t(v)] = int(k);
    }
  }

  std::uint32_t key_of(std::int32_t plane) const { return ids_.id[std::size_t(plane)]; }

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
  ApproxPoint class_at(int k) const {
    return tight_approximation(class_support_[std::size_t(k)], *class_corner_[std::size_t(k)]);
  }

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
  // Class k's grid status, found once (by whichever thread first needs it: the same value).
  GridStatus class_grid(int k, const ApproxPoint& a) const {
    std::atomic<GridStatus>& g = grid_[std::size_t(k)];
    GridStatus s = g.load(std::memory_order_relaxed);
    if (s == GridStatus::Unchecked) {
      const kernel::Corner& c = *class_corner_[std::size_t(k)];
      s = grid_point(class_support_[std::size_t(k)], c.p, c.q, a);
      g.store(s, std::memory_order_relaxed);
    }
    return s;
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

  // Class k's point tested against other classes' points: its approximation, and its 2x2 minors
  // (shared by its tests) made when first needed.
  class Probe {
   public:
    Probe(const CornerMerger& m, int k)
        : m_(m),
          k_(k),
          corner_(*m.class_corner_[std::size_t(k)]),
          support_(m.class_support_[std::size_t(k)]),
          key_(m.v_.class_planes[std::size_t(k)]),
          at_(m.class_at(k)) {}

    // Exact: class k's point (support ∩ p ∩ q) lies on the three planes of class j's triple
    // (planes shared with k's key need no test; the others by the exact zero test of
    // vertex_equality.hpp). Disjoint error boxes are different points (a filter only).
    bool equals(int j) {
      const ApproxPoint pb = m_.class_at(j);
      const ApproxPoint& pa = at_;
      if (pa.err >= 0 && pb.err >= 0) {
        const double tol = pa.err + pb.err;
        if (std::fabs(pb.x - pa.x) > tol || std::fabs(pb.y - pa.y) > tol || std::fabs(pb.z - pa.z) > tol) return false;
      }
      const GridStatus grid = m_.class_grid(k_, pa), other = m_.class_grid(j, pb);
      const bool known = grid != GridStatus::Unknown && other != GridStatus::Unknown;
      if (known && (grid == GridStatus::Yes || other == GridStatus::Yes))
        return grid == other && nearest_grid_point(pa) == nearest_grid_point(pb);
      const kernel::Corner& cj = *m_.class_corner_[std::size_t(j)];
      const std::int32_t planes[3] = {m_.class_support_[std::size_t(j)], cj.p, cj.q};
      std::int32_t tested[3];
      int n = 0;
      for (const std::int32_t plane : planes) {
        const std::uint32_t id = m_.key_of(plane);
        if (id != key_[0] && id != key_[1] && id != key_[2]) tested[n++] = plane;
      }
      if (n == 0) return true;
      if (!minors_) minors_ = vertex_minors(m_.planes_[support_], m_.planes_[corner_.p], m_.planes_[corner_.q], at_);
      for (int i = 0; i < n; ++i)
        if (!vertex_on_plane(*minors_, m_.planes_[tested[i]])) return false;
      return true;
    }

   private:
    const CornerMerger& m_;
    int k_;
    const kernel::Corner& corner_;
    std::int32_t support_;
    IdTriple key_;
    ApproxPoint at_;
    std::optional<VertexMinors> minors_;
  };
  bool same_point(int k, int j) const { return Probe(*this, k).equals(j); }

  const kernel::PlaneTable& planes_;
  const PlaneIds& ids_;
  AssemblyVertices& v_;
  std::vector<int>& out_;  // the corners' classes, then their vertices
  std::vector<Slot> slots_;
  int shift_ = 26;
  std::size_t cells_used_ = 0;  // occupied slots
  std::vector<Entry> entries_;
  // Per class (keys in v_.class_planes): its first corner and that corner's support, where its
  // entries end (class_entries_[k] .. class_entries_[k + 1]), and how many wide classes precede it.
  std::vector<const kernel::Corner*> class_corner_;
  std::vector<std::int32_t> class_support_;
  std::vector<int> class_entries_;
  std::vector<int> wide_before_;
  std::vector<int> wide_classes_;
  std::vector<std::uint8_t> class_on_grid_;  // per class: made by a grid corner (its status is Yes)
  std::vector<GridSlot> grid_slots_;         // grid corners' classes by their point
  std::size_t grid_used_ = 0;
  std::unique_ptr<std::atomic<GridStatus>[]> grid_;  // per class, pass 2
};

void CornerMerger::prepare(std::int32_t support, std::uint32_t s, const kernel::Corner& c, std::size_t out,
                           Pending& p) const {
  p.corner = &c;
  p.out = out;
  p.support = support;
  p.key = sorted(s, ids_.id[std::size_t(c.p)], ids_.id[std::size_t(c.q)]);
  const ApproxPoint a = tight_approximation(support, c);
  p.on_grid = grid_point(support, c.p, c.q, a) == GridStatus::Yes;
  if (p.on_grid) p.g = nearest_grid_point(a);
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
  // Fragments a piece. A wave's prepared corners (72 bytes each; 110 before the exact tests left the ordered pass) are
  // scratch held beside the result: pieces of 1024 held 2.7 MB with two threads, which set small jobs' peaks (fandisk
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
  merger.finish();
  return r;
}

}  // namespace sculpt::bsp::detail
