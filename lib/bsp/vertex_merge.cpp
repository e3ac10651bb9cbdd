#include "bsp/vertex_merge.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>

namespace sculpt::detail {

using kernel::ApproxPoint;

namespace {

using IdTriple = std::array<std::uint32_t, 3>;  // canonical plane ids, sorted

std::uint64_t hash_triple(const IdTriple& k) {
  std::uint64_t h = (std::uint64_t(k[0]) << 32 | k[1]) * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 29) + std::uint64_t(k[2]) * 0xC2B2AE3D27D4EB4Full;
  return h ^ (h >> 32);
}

// Corners with the same triple (as a set of planes up to orientation) are one class: the same
// point, known without arithmetic. Only classes are compared exactly.
struct Classes {
  std::vector<int> of_corner;         // corner -> class
  std::vector<IdTriple> key;          // class -> sorted canonical ids
  std::vector<PlaneTriple> triple;    // class -> triple of its first corner
  std::vector<ApproxPoint> at;        // class -> approximation of its first corner
};

Classes group_corners(const Fragments& fragments, const PlaneIds& ids, std::size_t corners) {
  Classes c;
  c.of_corner.resize(corners);
  c.key.reserve(corners / 2 + 16);
  c.triple.reserve(corners / 2 + 16);
  c.at.reserve(corners / 2 + 16);
  // Keys and hashes first, so the table probes can be prefetched a few corners ahead (the
  // table is larger than the caches and the probes are random).
  struct Keyed {
    IdTriple key;
    std::uint32_t hash;
  };
  std::vector<Keyed> keyed(corners);
  std::size_t i = 0;
  for (const Fragment& fr : fragments.fragments) {
    const std::uint32_t s = ids.id[std::size_t(fr.polygon.support)];
    for (const auto& corner : fr.polygon.corners) {
      IdTriple k = {s, ids.id[std::size_t(corner.p)], ids.id[std::size_t(corner.q)]};
      if (k[0] > k[1]) std::swap(k[0], k[1]);
      if (k[1] > k[2]) std::swap(k[1], k[2]);
      if (k[0] > k[1]) std::swap(k[0], k[1]);
      keyed[i++] = {k, std::uint32_t(hash_triple(k))};
    }
  }
  std::size_t slots = 16;
  while (slots < corners + corners / 2) slots *= 2;
  struct Slot {
    IdTriple key;
    int cls;  // -1: empty
  };
  std::vector<Slot> table(slots, Slot{{0, 0, 0}, -1});
  constexpr std::size_t kAhead = 8;
  i = 0;
  for (const Fragment& fr : fragments.fragments)
    for (const auto& corner : fr.polygon.corners) {
      if (i + kAhead < corners) __builtin_prefetch(&table[keyed[i + kAhead].hash & (slots - 1)]);
      const IdTriple& k = keyed[i].key;
      std::size_t h = keyed[i].hash & (slots - 1);
      while (table[h].cls >= 0 && table[h].key != k) h = (h + 1) & (slots - 1);
      if (table[h].cls < 0) {
        table[h] = {k, int(c.key.size())};
        c.key.push_back(k);
        c.triple.push_back({fr.polygon.support, corner.p, corner.q});
        c.at.push_back(corner.at);
      }
      c.of_corner[i++] = table[h].cls;
    }
  return c;
}

class ClassMerger {
 public:
  ClassMerger(const kernel::PlaneTable& planes, const PlaneIds& ids, const Classes& c)
      : planes_(planes), ids_(ids), c_(c), uf_(c.key.size()) {}

  // Candidates share a cell of a grid of one grid unit (far above the approximation errors; a
  // class within its error of a cell boundary is entered in every cell it may belong to). Cells
  // are numbered row-major within the bounding box of all cells; a box too large for 64 bits
  // folds coordinates (cells that collide are rejected by the approximations).
  UnionFind run() {
    const std::size_t n = c_.key.size();
    constexpr double kShift = 0.3711;  // grid points never sit on a cell boundary
    struct Range {
      std::int64_t lo[3], hi[3];
    };
    std::vector<Range> ranges(n);
    std::vector<int> wide;
    std::int64_t min[3] = {INT64_MAX, INT64_MAX, INT64_MAX}, max[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
    for (std::size_t i = 0; i < n; ++i) {
      const ApproxPoint& a = c_.at[i];
      const double v[3] = {a.x, a.y, a.z};
      Range& r = ranges[i];
      bool too_wide = !(a.err >= 0 && a.err < 0.25);
      for (int k = 0; k < 3 && !too_wide; ++k) {
        r.lo[k] = std::int64_t(std::floor(v[k] - a.err + kShift));
        r.hi[k] = std::int64_t(std::floor(v[k] + a.err + kShift));
        min[k] = std::min(min[k], r.lo[k]);
        max[k] = std::max(max[k], r.hi[k]);
      }
      if (too_wide) {
        wide.push_back(int(i));  // a large error bound (nearly dependent planes): brute force
        r.lo[0] = 1, r.hi[0] = 0;  // no cells
      }
    }
    // Row-major numbering when the box has fewer than 2^62 cells, else folded coordinates.
    std::uint64_t size[3] = {1, 1, 1};
    double cells = 1;
    for (int k = 0; k < 3; ++k)
      if (max[k] >= min[k]) cells *= double(max[k] - min[k]) + 1;
    const bool exact = cells < 0x1p62;
    for (int k = 0; k < 3; ++k)
      if (exact && max[k] >= min[k]) size[k] = std::uint64_t(max[k] - min[k] + 1);
    auto cell = [&](std::int64_t x, std::int64_t y, std::int64_t z) -> std::uint64_t {
      if (exact)
        return (std::uint64_t(x - min[0]) * size[1] + std::uint64_t(y - min[1])) * size[2] + std::uint64_t(z - min[2]);
      constexpr std::uint64_t kMask = (std::uint64_t(1) << 21) - 1;
      return (std::uint64_t(x) & kMask) << 42 | (std::uint64_t(y) & kMask) << 21 | (std::uint64_t(z) & kMask);
    };
    // Cells in a hash table, each with the chain of classes entered so far: a class is compared
    // with the classes already in its cells, so classes are visited in their own (spatially
    // coherent) order and nothing is sorted.
    std::size_t entries = 0;
    for (const Range& r : ranges)
      if (r.lo[0] <= r.hi[0]) entries += std::size_t((r.hi[0] - r.lo[0] + 1) * (r.hi[1] - r.lo[1] + 1) * (r.hi[2] - r.lo[2] + 1));
    std::size_t slots = 16;
    while (slots < 2 * entries) slots *= 2;
    const int shift = 64 - std::countr_zero(slots);
    struct Slot {
      std::uint64_t cell;
      int head;  // last entry of the cell's chain, -1: empty slot
    };
    std::vector<Slot> table(slots, Slot{0, -1});
    std::vector<int> entry_class, entry_next;
    entry_class.reserve(entries);
    entry_next.reserve(entries);
    for (const int a : wide)
      for (std::size_t b = 0; b < n; ++b)
        if (std::size_t(a) != b) consider(a, int(b));
    for (std::size_t i = 0; i < n; ++i) {
      const Range& r = ranges[i];
      for (std::int64_t x = r.lo[0]; x <= r.hi[0]; ++x)
        for (std::int64_t y = r.lo[1]; y <= r.hi[1]; ++y)
          for (std::int64_t z = r.lo[2]; z <= r.hi[2]; ++z) {
            const std::uint64_t k = cell(x, y, z);
            std::size_t h = std::size_t((k * 0x9E3779B97F4A7C15ull) >> shift);
            while (table[h].head >= 0 && table[h].cell != k) h = (h + 1) & (slots - 1);
            for (int e = table[h].head; e >= 0; e = entry_next[std::size_t(e)]) consider(entry_class[std::size_t(e)], int(i));
            entry_class.push_back(int(i));
            entry_next.push_back(table[h].head);
            table[h] = {k, int(entry_class.size()) - 1};
          }
    }
    return std::move(uf_);
  }

 private:
  void consider(int a, int b) {
    if (uf_.find(a) == uf_.find(b)) return;
    const ApproxPoint& pa = c_.at[std::size_t(a)];
    const ApproxPoint& pb = c_.at[std::size_t(b)];
    if (pa.err >= 0 && pb.err >= 0) {  // a filter only: disjoint error boxes are different points
      const double tol = pa.err + pb.err;
      if (std::fabs(pb.x - pa.x) > tol || std::fabs(pb.y - pa.y) > tol || std::fabs(pb.z - pa.z) > tol) return;
    }
    if (same_point(a, b)) uf_.unite(a, b);
  }

  // Exact: class a's point lies on the three planes of class b (planes shared by both triples
  // need no test).
  bool same_point(int a, int b) const {
    const PlaneTriple& ta = c_.triple[std::size_t(a)];
    const PlaneTriple& tb = c_.triple[std::size_t(b)];
    const IdTriple& ka = c_.key[std::size_t(a)];
    for (const std::int32_t plane : {tb.s, tb.p, tb.q}) {
      const std::uint32_t id = ids_.id[std::size_t(plane)];
      if (id == ka[0] || id == ka[1] || id == ka[2]) continue;
      if (kernel::orient(planes_[ta.s], planes_[ta.p], planes_[ta.q], c_.at[std::size_t(a)], planes_[plane]) !=
          kernel::Sign::Zero)
        return false;
    }
    return true;
  }

  const kernel::PlaneTable& planes_;
  const PlaneIds& ids_;
  const Classes& c_;
  UnionFind uf_;
};

}  // namespace

MergedVertices merge_vertices(const Fragments& fragments, const PlaneIds& ids) {
  std::size_t corners = 0;
  for (const Fragment& fr : fragments.fragments) corners += fr.polygon.corners.size();
  const Classes classes = group_corners(fragments, ids, corners);
  UnionFind uf = ClassMerger(fragments.planes, ids, classes).run();

  // Vertices numbered by first corner; each keeps its first corner's triple and approximation.
  MergedVertices r;
  AssemblyVertices& v = r.vertices;
  r.vertex_of.resize(corners);
  std::vector<int> vertex_of_root(classes.key.size(), -1);
  std::size_t i = 0;
  for (const Fragment& fr : fragments.fragments)
    for (const auto& corner : fr.polygon.corners) {
      const int root = uf.find(classes.of_corner[i]);
      int& vertex = vertex_of_root[std::size_t(root)];
      if (vertex < 0) {
        vertex = v.size();
        v.at.push_back(corner.at);
        v.triple.push_back({fr.polygon.support, corner.p, corner.q});
      }
      r.vertex_of[i++] = vertex;
    }

  // Known planes of each vertex: the canonical ids of all its classes' triples, without repeats.
  const std::size_t nv = v.at.size();
  std::vector<int> count(nv + 1, 0);
  for (std::size_t c = 0; c < classes.key.size(); ++c) count[std::size_t(vertex_of_root[std::size_t(uf.find(int(c)))]) + 1] += 3;
  for (std::size_t k = 0; k < nv; ++k) count[k + 1] += count[k];
  std::vector<std::uint32_t> all(static_cast<std::size_t>(count[nv]));
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (std::size_t c = 0; c < classes.key.size(); ++c) {
    int& at = fill[std::size_t(vertex_of_root[std::size_t(uf.find(int(c)))])];
    for (const std::uint32_t id : classes.key[c]) all[std::size_t(at++)] = id;
  }
  v.known_start.assign(nv + 1, 0);
  v.known.reserve(all.size());
  for (std::size_t k = 0; k < nv; ++k) {
    const auto b = all.begin() + count[k], e = all.begin() + count[k + 1];
    if (e - b > 3) std::sort(b, e);
    const auto last = e - b > 3 ? std::unique(b, e) : e;
    v.known.insert(v.known.end(), b, last);
    v.known_start[k + 1] = int(v.known.size());
  }
  return r;
}

}  // namespace sculpt::detail
