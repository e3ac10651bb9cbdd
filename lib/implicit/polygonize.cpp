// Implicit solids: adaptive octree, conforming tetrahedra, marching tetrahedra (polygonize.hpp).
#include "implicit/polygonize.hpp"
#include "base/cancel.hpp"

#include "implicit/detail/refine.hpp"
#include "implicit/detail/simplify.hpp"
#include "mesh/self_intersection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace sculpt::implicit {
namespace {

using Vec = Eigen::Vector3d;
using Key = std::uint64_t;

// The box is first cut into a grid of at most kTop^3 nearly cubic cells (level 0). A lattice
// coordinate then needs 21 bits (kTop 2^(kMaxLevel + 1) + 1 values), a cell index 19.
constexpr int kTop = 4;
constexpr int kMaxLevel = 16;
constexpr int kStartLevel = 1;  // cells are split at least this deep before any is kept
constexpr double kSimplifyFraction = 0.7;  // collapsed triangles stay within this times tol
constexpr double kBendFactor = 1.25;  // measured: the torus at 2e-3 stays within tol (1.5 does not)
/// With simplify, cells where the surface does not meet the box are split only while a flat
/// piece of them would be off by more than this times tol; the edge splits of detail/refine.hpp
/// then bring the marched mesh within kRefineFraction tol, and the collapses run on far fewer
/// triangles.
constexpr double kCoarseBend = 8.0;
constexpr double kRefineFraction = 0.8;

/// A leaf's content; Split: a former leaf that balancing split (its entry stays in the table).
enum class Kind : std::uint8_t { Empty, Full, Mixed, Split };

struct Cell {
  int level = 0;
  std::int64_t i = 0, j = 0, k = 0;
};

Key cell_key(int level, std::int64_t i, std::int64_t j, std::int64_t k) {
  return (Key(level) << 57) | (Key(i) << 38) | (Key(j) << 19) | Key(k);
}

Key point_key(std::int64_t x, std::int64_t y, std::int64_t z) { return Key(x) | (Key(y) << 21) | (Key(z) << 42); }
std::array<std::int64_t, 3> point_of(Key p) {
  constexpr Key m = (Key(1) << 21) - 1;
  return {std::int64_t(p & m), std::int64_t((p >> 21) & m), std::int64_t((p >> 42) & m)};
}

/// splitmix64's finalizer: lattice keys differ in few, high bits; this spreads them over all.
inline std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

struct KeyHash {
  std::uint64_t operator()(Key k) const { return mix(k); }
};
struct PairHash {
  std::uint64_t operator()(const std::pair<Key, Key>& e) const { return mix(e.first ^ mix(e.second)); }
};

/// An open-addressing hash map (linear probing, load at most 1/2) for the lattice's hot tables:
/// insert and find only, no erase. The table holds keys and indices; the values lie in one array
/// in insertion order (points made together, near in space, stay near in memory). A reference
/// is valid until the next insertion.
template <typename K, typename V, typename Hash>
class FlatMap {
 public:
  /// The value at k, default-constructed when k is new; second: whether it was inserted.
  std::pair<V*, bool> try_emplace(const K& k) {
    if (2 * (values_.size() + 1) > slots_.size()) grow();
    std::size_t i = Hash()(k) & mask_;
    while (slots_[i].index != kEmpty) {
      if (slots_[i].key == k) return {&values_[slots_[i].index], false};
      i = (i + 1) & mask_;
    }
    slots_[i] = {k, std::uint32_t(values_.size())};
    values_.emplace_back();
    keys_.push_back(k);
    return {&values_.back(), true};
  }
  [[nodiscard]] V* find(const K& k) { return const_cast<V*>(std::as_const(*this).find(k)); }
  /// f(key, value) for every entry, in insertion order.
  template <typename F>
  void for_each(F f) const {
    for (std::size_t i = 0; i < keys_.size(); ++i) f(keys_[i], values_[i]);
  }
  [[nodiscard]] const V* find(const K& k) const {
    if (slots_.empty()) return nullptr;
    std::size_t i = Hash()(k) & mask_;
    while (slots_[i].index != kEmpty) {
      if (slots_[i].key == k) return &values_[slots_[i].index];
      i = (i + 1) & mask_;
    }
    return nullptr;
  }
  [[nodiscard]] bool contains(const K& k) const { return find(k) != nullptr; }
  [[nodiscard]] std::size_t size() const { return values_.size(); }

 private:
  static constexpr std::uint32_t kEmpty = ~std::uint32_t(0);
  struct Slot {
    K key{};
    std::uint32_t index = kEmpty;
  };
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<std::size_t>(1024, 2 * old.size()), Slot{});
    mask_ = slots_.size() - 1;
    for (const Slot& s : old) {
      if (s.index == kEmpty) continue;
      std::size_t i = Hash()(s.key) & mask_;
      while (slots_[i].index != kEmpty) i = (i + 1) & mask_;
      slots_[i] = s;
    }
  }
  std::vector<Slot> slots_;
  std::vector<V> values_;
  std::vector<K> keys_;
  std::size_t mask_ = 0;
};

struct PointData {
  double value = 0.0;
  bool has_normal = false;
  bool normal_valid = false;
  Vec normal = Vec::Zero();
};

class Polygonizer {
 public:
  Polygonizer(const Expression& f, const PolygonizeOptions& o) : f_(f), o_(o) {
    const Vec extent = o.box.hi - o.box.lo;
    const double longest = extent.maxCoeff();
    feature_ = o.feature_size > 0 ? o.feature_size : 4.0 * o.tolerance;
    // The finest cells: at most tol, and at most half the feature size (a part that thin is cut
    // by lattice points, not stepped over).
    const double finest = std::min(o.tolerance, 0.5 * feature_);
    finest_ = finest;
    const double top_side = longest / kTop;
    for (int a = 0; a < 3; ++a) top_[a] = std::clamp<std::int64_t>(std::llround(extent[a] / top_side), 1, kTop);
    lmax_ = 0;
    while (lmax_ < kMaxLevel && top_side / double(std::int64_t(1) << lmax_) > finest) ++lmax_;
    for (int a = 0; a < 3; ++a) resolution_[a] = top_[a] << (lmax_ + 1);
  }

  /// Meshes once, on the coarse octree with edge splits (coarse) or on the fine one. ok: false when
  /// the coarse way failed (an edge split, or the collapses' mesh intersected itself).
  PolygonizeResult run(bool coarse, bool& ok) {
    coarse_ = coarse;
    PolygonizeResult r = mesh_once();
    ok = !coarse || r.mesh.faces.empty() || (refined_ && !r.simplify_rejected);
    return r;
  }

 private:
  PolygonizeResult mesh_once() {
    build();
    balance();
    march();
    result_.leaves = leaf_count_;
    result_.marched_triangles = static_cast<long>(result_.mesh.faces.size());
    if (coarse_ && !result_.mesh.faces.empty()) {
      std::vector<bool> locked = locked_vertices();
      const detail::RefineResult rr = detail::refine(
          result_.mesh, locked, f_,
          {.tolerance = kRefineFraction * o_.tolerance, .limit = o_.tolerance, .min_edge = finest_,
           .max_splits = o_.max_cells, .box = o_.box});
      result_.refinements = rr.splits;
      refined_ = rr.ok;
      if (!rr.ok) return std::move(result_);
    }
    if (o_.simplify && !result_.mesh.faces.empty()) simplify();
    return std::move(result_);
  }

  std::vector<bool> locked_vertices() const {
    std::vector<bool> locked(result_.mesh.vertices.size(), false);
    for (std::size_t v = 0; v < locked.size(); ++v) {
      const Vec& p = result_.mesh.vertices[v];
      for (int a = 0; a < 3; ++a) locked[v] = locked[v] || p[a] == o_.box.lo[a] || p[a] == o_.box.hi[a];
    }
    return locked;
  }

  /// For each mesh vertex, the box sides it lies on (detail::SimplifyOptions::box_sides).
  std::vector<std::uint8_t> box_sides() const {
    std::vector<std::uint8_t> sides(result_.mesh.vertices.size(), 0);
    for (std::size_t v = 0; v < sides.size(); ++v) {
      const Vec& p = result_.mesh.vertices[v];
      for (int a = 0; a < 3; ++a) {
        if (p[a] == o_.box.lo[a]) sides[v] |= std::uint8_t(1 << (2 * a));
        if (p[a] == o_.box.hi[a]) sides[v] |= std::uint8_t(1 << (2 * a + 1));
      }
    }
    return sides;
  }

  // ---- geometry of the lattice -------------------------------------------------------------
  [[nodiscard]] std::int64_t step(int level) const { return std::int64_t(1) << (lmax_ + 1 - level); }
  [[nodiscard]] Vec world(std::int64_t x, std::int64_t y, std::int64_t z) const {
    const Vec t(double(x) / double(resolution_[0]), double(y) / double(resolution_[1]),
                double(z) / double(resolution_[2]));
    return o_.box.lo + (o_.box.hi - o_.box.lo).cwiseProduct(t);
  }
  [[nodiscard]] Vec world(Key p) const {
    const auto c = point_of(p);
    return world(c[0], c[1], c[2]);
  }
  [[nodiscard]] Box cell_box(const Cell& c) const {
    const std::int64_t s = step(c.level);
    return {.lo = world(c.i * s, c.j * s, c.k * s), .hi = world((c.i + 1) * s, (c.j + 1) * s, (c.k + 1) * s)};
  }

  PointData& point(Key p) {
    auto [d, inserted] = points_.try_emplace(p);
    if (inserted) d->value = f_.value(world(p));
    return *d;
  }
  bool inside(Key p) { return point(p).value <= 0.0; }

  /// Unit normal at a lattice point, or false where the gradient vanishes or is not finite.
  bool normal(Key p, Vec& n) {
    PointData& d = point(p);
    if (!d.has_normal) {
      d.has_normal = true;
      try {
        const Vec g = f_.value_gradient(world(p)).gradient;
        const double len = g.norm();
        if (len > 0 && std::isfinite(len)) {
          d.normal = g / len;
          d.normal_valid = true;
        }
      } catch (const NonFiniteValue&) {
        // a kink such as sqrt at 0: no normal here; the cell counts as bent
      }
    }
    n = d.normal;
    return d.normal_valid;
  }

  void charge(long& counter) {
    ++counter;
    poll_.tick();  // Ctrl-C (base/cancel.hpp)
    if (result_.cells + result_.search_cells + leaf_count_ > o_.max_cells) {
      throw GeometryError("polygonize: the work budget of " + std::to_string(o_.max_cells) +
                          " cells ran out (the surface is too large for the box and tol, or f's interval bounds "
                          "cannot tell the cells apart); raise the budget, raise tol or shrink the box");
    }
  }

  std::array<Key, 8> corners(const Cell& c) const {
    const std::int64_t s = step(c.level);
    std::array<Key, 8> out{};
    for (int b = 0; b < 8; ++b) out[b] = point_key((c.i + (b & 1)) * s, (c.j + ((b >> 1) & 1)) * s, (c.k + (b >> 2)) * s);
    return out;
  }

  // ---- octree ------------------------------------------------------------------------------
  /// True when the normals at the corners say a flat piece of this cell's size would be off the
  /// surface by more than tol / 2 (sagitta of a chord d turning by theta: d theta / 8).
  bool bent(const Cell& c, const std::array<Key, 8>& corner, const std::array<bool, 8>& in) {
    std::array<Vec, 8> n;
    for (int b = 0; b < 8; ++b) {
      if (!normal(corner[b], n[b])) return true;
    }
    double min_dot = 1.0;
    for (int a = 0; a < 8; ++a)
      for (int b = a + 1; b < 8; ++b) min_dot = std::min(min_dot, n[a].dot(n[b]));
    const double theta = std::acos(std::clamp(min_dot, -1.0, 1.0));
    const Box box = cell_box(c);
    const double factor = coarse_ && !surface_at_box(c, in) ? kCoarseBend : kBendFactor;
    return (box.hi - box.lo).norm() * theta / 8.0 > factor * o_.tolerance;
  }

  /// Whether the cell has a face on the box whose corners differ in sign: the surface meets the
  /// box there, and the triangles at the box, whose vertices on the box are kept, are not split
  /// by the edge splits (detail/refine.hpp), so such a cell gets the fine criterion. A cell whose
  /// faces on the box have corners of one sign has no mesh vertex on the box from its own edges
  /// (a finer neighbour along the box could still put one on an edge midpoint: the edge splits
  /// then fail where that leaves a triangle beyond tol, and the fine octree is meshed instead).
  bool surface_at_box(const Cell& c, const std::array<bool, 8>& in) const {
    const std::int64_t last = std::int64_t(1) << c.level;
    const std::array<std::int64_t, 3> index = {c.i, c.j, c.k};
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        if (index[a] != (side == 0 ? 0 : top_[a] * last - 1)) continue;
        int count = 0;
        for (int b = 0; b < 8; ++b)
          if (((b >> a) & 1) == side) count += in[b] ? 1 : 0;
        if (count != 0 && count != 4) return true;
      }
    return false;
  }

  /// True when an edge of a Kuhn tetrahedron of the cell (the 12 cube edges, the 6 face
  /// diagonals from lowest to highest corner, the main diagonal) has ends of one sign and its
  /// midpoint of the other: the surface crosses it twice (a thin part, or two sheets), which
  /// marching tetrahedra on this cell would miss.
  bool crossed_twice(const Cell& c, const std::array<bool, 8>& in) {
    const std::int64_t s = step(c.level);
    // corner b is (i + (b & 1), j + (b >> 1 & 1), k + (b >> 2)); an edge (a, a | mask) has its
    // lower end a without the bits of mask: masks of one bit are the cube edges, of two bits
    // the face diagonals, 7 the main diagonal
    for (int mask = 1; mask < 8; ++mask)
      for (int lo = 0; lo < 8; ++lo) {
        if ((lo & mask) != 0 || in[lo] != in[lo | mask]) continue;
        const std::int64_t x = 2 * c.i * s + (2 * (lo & 1) + (mask & 1)) * s;
        const std::int64_t y = 2 * c.j * s + (2 * ((lo >> 1) & 1) + ((mask >> 1) & 1)) * s;
        const std::int64_t z = 2 * c.k * s + (2 * (lo >> 2) + (mask >> 2)) * s;
        if (inside(point_key(x / 2, y / 2, z / 2)) != in[lo]) return true;
      }
    return false;
  }

  /// Searches a cell whose corners are all inside (or all outside) for a point of the other
  /// sign, culling sub-cells by interval bounds, down to sub-cells of feature_size / 2 (a ball
  /// of diameter feature_size holds the centre of some sub-cell at every level below its size).
  /// Returns +1 found, 0 proven free, -1 unresolved.
  int search(const Box& cell, bool corners_inside) {
    std::vector<Box> stack{cell};
    bool unresolved = false;
    const double floor = 0.5 * feature_;
    while (!stack.empty()) {
      const Box b = stack.back();
      stack.pop_back();
      charge(result_.search_cells);
      const Vec mid = 0.5 * (b.lo + b.hi);
      if ((f_.value(mid) <= 0.0) != corners_inside) return 1;
      const IntervalBounds r = f_.bounds(b);
      if (!r.domain_error) {
        if (corners_inside && r.range.hi <= 0.0) continue;
        if (!corners_inside && r.range.lo > 0.0) continue;
      }
      if ((b.hi - b.lo).maxCoeff() <= floor) {
        unresolved = true;
        continue;
      }
      for (int o = 0; o < 8; ++o) {
        Box child;
        for (int a = 0; a < 3; ++a) {
          const bool upper = (o >> a) & 1;
          child.lo[a] = upper ? mid[a] : b.lo[a];
          child.hi[a] = upper ? b.hi[a] : mid[a];
        }
        stack.push_back(child);
      }
    }
    return unresolved ? -1 : 0;
  }

  void build() {
    std::vector<Cell> stack;
    for (std::int64_t i = 0; i < top_[0]; ++i)
      for (std::int64_t j = 0; j < top_[1]; ++j)
        for (std::int64_t k = 0; k < top_[2]; ++k) stack.push_back({0, i, j, k});
    while (!stack.empty()) {
      const Cell c = stack.back();
      stack.pop_back();
      charge(result_.cells);
      const Box box = cell_box(c);
      const IntervalBounds r = f_.bounds(box);
      Kind kind = Kind::Mixed;
      if (!r.domain_error && r.range.lo > 0.0) kind = Kind::Empty;
      if (!r.domain_error && r.range.hi <= 0.0) kind = Kind::Full;
      bool split = false;
      if (kind == Kind::Mixed && c.level < lmax_) {
        if (c.level < kStartLevel) {
          split = true;
        } else {
          const std::array<Key, 8> corner = corners(c);
          std::array<bool, 8> in{};
          for (int b = 0; b < 8; ++b) in[b] = inside(corner[b]);
          const bool first = in[0];
          bool mixed = false;
          for (int b = 1; b < 8; ++b) mixed = mixed || in[b] != first;
          if (mixed) {
            split = crossed_twice(c, in) || bent(c, corner, in);
          } else {
            const int s = search(box, first);
            split = s > 0;
            if (s < 0) ++result_.unresolved_cells;
          }
        }
      }
      if (!split) {
        *leaves_.try_emplace(cell_key(c.level, c.i, c.j, c.k)).first = kind;
        ++leaf_count_;
        result_.max_level = std::max(result_.max_level, c.level);
        continue;
      }
      for (int o = 0; o < 8; ++o) {
        stack.push_back({c.level + 1, 2 * c.i + (o & 1), 2 * c.j + ((o >> 1) & 1), 2 * c.k + (o >> 2)});
      }
    }
  }

  /// The leaf containing cell (level, i, j, k) or one of its ancestors; false when the cell is
  /// split further (its region holds finer leaves).
  bool leaf_over(int level, std::int64_t i, std::int64_t j, std::int64_t k, Cell& out) const {
    for (int l = level; l >= 0; --l) {
      const int d = level - l;
      const Key key = cell_key(l, i >> d, j >> d, k >> d);
      if (is_leaf(key)) {
        out = {l, i >> d, j >> d, k >> d};
        return true;
      }
    }
    return false;
  }

  [[nodiscard]] bool is_leaf(Key key) const {
    const Kind* kind = leaves_.find(key);
    return kind && *kind != Kind::Split;
  }

  static Cell cell_of(Key key) {
    constexpr Key m = (Key(1) << 19) - 1;
    return {int(key >> 57), std::int64_t((key >> 38) & m), std::int64_t((key >> 19) & m), std::int64_t(key & m)};
  }

  /// 2:1 balance over faces, edges and corners: a leaf next to one more than a level finer is split.
  void balance() {
    std::vector<Cell> queue;
    leaves_.for_each([&](Key key, Kind kind) {
      if (kind != Kind::Split) queue.push_back(cell_of(key));
    });
    while (!queue.empty()) {
      poll_.tick();  // Ctrl-C (base/cancel.hpp)
      const Cell c = queue.back();
      queue.pop_back();
      if (c.level < 1 || !is_leaf(cell_key(c.level, c.i, c.j, c.k))) continue;
      const std::array<std::int64_t, 3> n = {top_[0] << c.level, top_[1] << c.level, top_[2] << c.level};
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const std::int64_t x = c.i + dx, y = c.j + dy, z = c.k + dz;
            if ((dx | dy | dz) == 0 || x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2]) continue;
            Cell big;
            if (!leaf_over(c.level, x, y, z, big) || big.level >= c.level - 1) continue;
            // split `big` into its 8 children, which are balanced in turn
            const Key key = cell_key(big.level, big.i, big.j, big.k);
            Kind* entry = leaves_.find(key);
            const Kind kind = *entry;
            *entry = Kind::Split;  // before the children's insertions move the table
            --leaf_count_;
            for (int o = 0; o < 8; ++o) {
              const Cell child{big.level + 1, 2 * big.i + (o & 1), 2 * big.j + ((o >> 1) & 1), 2 * big.k + (o >> 2)};
              *leaves_.try_emplace(cell_key(child.level, child.i, child.j, child.k)).first = kind;
              ++leaf_count_;
              charge(result_.cells);
              queue.push_back(child);
            }
            queue.push_back(c);  // look again: the neighbour's children may still be too coarse
            dx = dy = 2;         // leave the loops (the cell is re-queued)
            break;
          }
    }
  }

  /// Edge collapses where the surface is flat (detail/simplify.hpp), checked afterwards for
  /// self-intersections by the exact test of the mesh layer (or by the caller's
  /// accept_simplified); a mesh that fails it is not used.
  void simplify() {
    const std::vector<bool> locked = locked_vertices();
    detail::SimplifyResult s = detail::simplify(
        result_.mesh, locked, f_,
        {.tolerance = kSimplifyFraction * o_.tolerance, .min_height = o_.min_height, .box_sides = box_sides()});
    const bool accept = o_.accept_simplified ? o_.accept_simplified(s.mesh)
                                             : find_self_intersections(s.mesh, {.max_pairs = 1}).empty();
    if (accept) {
      result_.accepted = bool(o_.accept_simplified);
      result_.mesh = std::move(s.mesh);
      result_.collapses = s.collapses;
      result_.thin_triangles = s.thin_triangles;
    } else {
      result_.simplify_rejected = true;
    }
  }

  // ---- tetrahedra and marching -------------------------------------------------------------
  using Triangle = std::array<Key, 3>;

  /// The triangles of face (axis, side) of a leaf. Both leaves sharing a face compute the same
  /// triangles from the same global facts (which lattice points are leaf corners), so the
  /// tetrahedra conform:
  /// - no edge midpoint is a leaf corner: two triangles, cut by the diagonal from the face's
  ///   lowest to its highest corner (as the Kuhn tetrahedra cut it);
  /// - the face centre is a leaf corner (finer leaves on the other side; then every edge
  ///   midpoint is one too): the four quarters, each cut the same way (as the finer leaves cut them);
  /// - else (a finer leaf touches only an edge): a fan from the face centre over the corners and
  ///   the edge midpoints that are leaf corners.
  void face_triangles(const Cell& c, int axis, int side, std::vector<Triangle>& out) const {
    const std::int64_t s = step(c.level), h = s / 2;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    std::array<std::int64_t, 3> base = {c.i * s, c.j * s, c.k * s};
    base[axis] += side * s;
    auto at = [&](std::int64_t du, std::int64_t dv) {
      std::array<std::int64_t, 3> p = base;
      p[u] += du;
      p[v] += dv;
      return point_key(p[0], p[1], p[2]);
    };
    // the boundary counter-clockwise in (u, v): corner, edge midpoint, corner, ...
    const std::array<Key, 8> ring = {at(0, 0), at(h, 0), at(s, 0), at(s, h), at(s, s), at(h, s), at(0, s), at(0, h)};
    bool any_midpoint = false;
    for (int m = 1; m < 8; m += 2) any_midpoint = any_midpoint || present_.contains(ring[m]);
    if (!any_midpoint || present_.contains(at(h, h))) {
      const std::int64_t q = any_midpoint ? h : s;
      for (std::int64_t a = 0; a < s; a += q)
        for (std::int64_t b = 0; b < s; b += q) {
          out.push_back({at(a, b), at(a + q, b), at(a + q, b + q)});
          out.push_back({at(a, b), at(a + q, b + q), at(a, b + q)});
        }
      return;
    }
    const Key centre = at(h, h);
    Key previous = ring[0];
    for (int m = 1; m <= 8; ++m) {
      const Key p = ring[m % 8];
      if (m % 2 == 1 && !present_.contains(p)) continue;
      out.push_back({centre, previous, p});
      previous = p;
    }
  }

  /// A mesh vertex on the edge between an inside and an outside lattice point.
  int root(Key in, Key out) {
    const std::pair<Key, Key> edge = in < out ? std::pair{in, out} : std::pair{out, in};
    if (const int* known = roots_.find(edge)) return *known;
    const Vec a = world(in), b = world(out);
    double fa = point(in).value, fb = point(out).value;  // fa <= 0 < fb
    double ta = 0.0, tb = 1.0;
    int side = 0;
    // Illinois regula falsi, safeguarded by bisection when it stalls.
    for (int iter = 0; iter < 60 && tb - ta > 1e-13; ++iter) {
      double t = ta + (tb - ta) * (fa / (fa - fb));
      if (!(t > ta && t < tb) || iter % 4 == 3) t = 0.5 * (ta + tb);
      const double ft = f_.value(a + t * (b - a));
      if (ft <= 0.0) {
        ta = t;
        fa = ft;
        if (side == -1) fb *= 0.5;
        side = -1;
      } else {
        tb = t;
        fb = ft;
        if (side == 1) fa *= 0.5;
        side = 1;
      }
      if (ft == 0.0) break;
    }
    // Keep the vertex off the lattice point (a vertex there would be shared by several edges),
    // and at least min_root_gap from it where the edge allows (at most a quarter of the edge).
    const double gap = std::min(std::max(1e-7, o_.min_root_gap / (b - a).norm()), 0.25);
    const double t = std::clamp(0.5 * (ta + tb), gap, 1.0 - gap);
    const int id = static_cast<int>(result_.mesh.vertices.size());
    result_.mesh.vertices.push_back(a + t * (b - a));
    *roots_.try_emplace(edge).first = id;
    return id;
  }

  int lattice_vertex(Key p) {
    const auto [id, inserted] = box_vertices_.try_emplace(p);
    if (inserted) {
      *id = static_cast<int>(result_.mesh.vertices.size());
      result_.mesh.vertices.push_back(world(p));
    }
    return *id;
  }

  /// Orientation sign of (b - a, c - a, d - a) on small integer coordinates.
  static std::int64_t orient(const std::array<std::int64_t, 3>& a, const std::array<std::int64_t, 3>& b,
                             const std::array<std::int64_t, 3>& c, const std::array<std::int64_t, 3>& d) {
    const std::int64_t b0 = b[0] - a[0], b1 = b[1] - a[1], b2 = b[2] - a[2];
    const std::int64_t c0 = c[0] - a[0], c1 = c[1] - a[1], c2 = c[2] - a[2];
    const std::int64_t d0 = d[0] - a[0], d1 = d[1] - a[1], d2 = d[2] - a[2];
    return b0 * (c1 * d2 - c2 * d1) - b1 * (c0 * d2 - c2 * d0) + b2 * (c0 * d1 - c1 * d0);
  }

  void emit(int a, int b, int c) { result_.mesh.faces.push_back({a, b, c}); }

  /// The 6 Kuhn tetrahedra of leaf c (paths from the lowest to the highest corner along the
  /// axes), marched; corner b is (i + (b & 1), j + (b >> 1 & 1), k + (b >> 2)), in[b] its sign.
  void kuhn(const Cell& c, const std::array<Key, 8>& corner, const std::array<bool, 8>& in) {
    static constexpr std::array<std::array<int, 3>, 6> kOrders = {
        {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    for (const auto& order : kOrders) {
      std::array<Key, 4> t{};
      std::array<bool, 4> tin{};
      int b = 0;
      t[0] = corner[0];
      tin[0] = in[0];
      for (int m = 0; m < 3; ++m) {
        b |= 1 << order[m];
        t[m + 1] = corner[b];
        tin[m + 1] = in[b];
      }
      march_tet(t, step(c.level), &tin);
    }
  }

  /// Marching tetrahedra on one tetrahedron. Triangles are oriented on the combinatorial
  /// structure (edge midpoints in lattice coordinates, exact integers), so every triangle has
  /// the inside on its back whatever the roots' positions.
  void march_tet(const std::array<Key, 4>& t, std::int64_t scale, const std::array<bool, 4>* known = nullptr) {
    std::array<bool, 4> in{};
    int count = 0;
    for (int a = 0; a < 4; ++a) count += (in[a] = known ? (*known)[a] : inside(t[a])) ? 1 : 0;
    if (count == 0 || count == 4) return;
    ++result_.tetrahedra;
    std::array<std::array<std::int64_t, 3>, 4> p{};
    const auto origin = point_of(t[0]);
    for (int a = 0; a < 4; ++a) {
      const auto q = point_of(t[a]);
      for (int x = 0; x < 3; ++x) p[a][x] = (q[x] - origin[x]) / scale;
    }
    auto mid = [&](int a, int b) {
      return std::array<std::int64_t, 3>{p[a][0] + p[b][0], p[a][1] + p[b][1], p[a][2] + p[b][2]};
    };
    auto twice = [&](int a) { return std::array<std::int64_t, 3>{2 * p[a][0], 2 * p[a][1], 2 * p[a][2]}; };
    auto edge = [&](int a, int b) { return in[a] ? root(t[a], t[b]) : root(t[b], t[a]); };
    // emit triangle on edges (a0 b0), (a1 b1), (a2 b2) with the inside vertex `ref_in` behind it
    auto triangle = [&](std::array<std::array<int, 2>, 3> e, int ref, bool ref_inside) {
      const auto m0 = mid(e[0][0], e[0][1]), m1 = mid(e[1][0], e[1][1]), m2 = mid(e[2][0], e[2][1]);
      const std::int64_t o = orient(m0, m1, m2, twice(ref));
      // the normal must point away from the inside: an inside reference on the negative side
      if ((o > 0) == ref_inside) std::swap(e[1], e[2]);
      emit(edge(e[0][0], e[0][1]), edge(e[1][0], e[1][1]), edge(e[2][0], e[2][1]));
    };
    if (count == 1 || count == 3) {
      int lone = 0;
      for (int a = 0; a < 4; ++a)
        if (in[a] == (count == 1)) lone = a;
      std::array<std::array<int, 2>, 3> e{};
      int n = 0;
      for (int a = 0; a < 4; ++a)
        if (a != lone) e[n++] = {lone, a};
      triangle(e, lone, in[lone]);
      return;
    }
    int i0 = -1, i1 = -1, o0 = -1, o1 = -1;
    for (int a = 0; a < 4; ++a) {
      if (in[a]) (i0 < 0 ? i0 : i1) = a;
      else (o0 < 0 ? o0 : o1) = a;
    }
    // quad (i0 o0) (i0 o1) (i1 o1) (i1 o0), cut by its diagonal (i0 o0)-(i1 o1)
    triangle({{{i0, o0}, {i0, o1}, {i1, o1}}}, i0, true);
    triangle({{{i0, o0}, {i1, o1}, {i1, o0}}}, i0, true);
  }

  /// The part of a box-face triangle inside the solid, oriented outwards (normal = sign * e_axis).
  void close_box(Triangle tri, int axis, int sign) {
    const auto a = point_of(tri[0]), b = point_of(tri[1]), c = point_of(tri[2]);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const std::int64_t normal = (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
    if ((normal > 0) != (sign > 0)) std::swap(tri[1], tri[2]);
    std::array<int, 4> poly{};
    int n = 0;
    for (int e = 0; e < 3; ++e) {
      const Key p = tri[e], q = tri[(e + 1) % 3];
      const bool pin = inside(p), qin = inside(q);
      if (pin) poly[n++] = lattice_vertex(p);
      if (pin != qin) poly[n++] = pin ? root(p, q) : root(q, p);
    }
    for (int k = 1; k + 1 < n; ++k) emit(poly[0], poly[k], poly[k + 1]);
  }

  void march() {
    std::vector<std::pair<Cell, Kind>> cells;
    cells.reserve(std::size_t(leaf_count_));
    leaves_.for_each([&](Key key, Kind kind) {
      if (kind == Kind::Split) return;
      const Cell c = cell_of(key);
      for (const Key p : corners(c)) present_.try_emplace(p);
      if (kind != Kind::Empty) cells.emplace_back(c, kind);
    });
    // A fixed order, so the output does not depend on the tables' order.
    std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) {
      return std::tie(a.first.level, a.first.i, a.first.j, a.first.k) < std::tie(b.first.level, b.first.i, b.first.j, b.first.k);
    });
    std::vector<Triangle> faces;
    for (const auto& entry : cells) {
      poll_.tick();                 // Ctrl-C (base/cancel.hpp)
      const Cell& c = entry.first;  // not a structured binding: lambdas below capture it (clang 14)
      const Kind kind = entry.second;
      const std::int64_t s = step(c.level);
      // the faces' triangles: all six for the tetrahedra of a mixed leaf, else only those on the box
      auto on_box = [&](int f) {
        const int axis = f / 2, side = f % 2;
        const std::int64_t index = axis == 0 ? c.i : axis == 1 ? c.j : c.k;
        return side == 0 ? index == 0 : index == (top_[axis] << c.level) - 1;
      };
      bool box_cell = false;
      for (int f = 0; f < 6; ++f) box_cell = box_cell || on_box(f);
      if (kind == Kind::Mixed && !box_cell) {
        // A leaf without finer neighbours (no edge midpoint is a leaf corner; a face centre that
        // is one makes its edge midpoints leaf corners too) is cut into the 6 Kuhn tetrahedra,
        // whose vertices are its corners: nothing to march when they all have one sign.
        bool transition = false;
        for (int axis = 0; axis < 3 && !transition; ++axis)
          for (int e = 0; e < 4 && !transition; ++e) {
            std::array<std::int64_t, 3> m = {c.i * s, c.j * s, c.k * s};
            m[axis] += s / 2;
            m[(axis + 1) % 3] += (e & 1) * s;
            m[(axis + 2) % 3] += (e >> 1) * s;
            transition = present_.contains(point_key(m[0], m[1], m[2]));
          }
        if (!transition) {
          const std::array<Key, 8> corner = corners(c);
          std::array<bool, 8> in{};
          int count = 0;
          for (int b = 0; b < 8; ++b) count += (in[b] = inside(corner[b])) ? 1 : 0;
          if (count == 0 || count == 8) continue;
          kuhn(c, corner, in);
          continue;
        }
      }
      faces.clear();
      std::array<std::size_t, 7> first{};
      for (int f = 0; f < 6; ++f) {
        first[f] = faces.size();
        if (kind == Kind::Mixed || on_box(f)) face_triangles(c, f / 2, f % 2, faces);
      }
      first[6] = faces.size();
      if (kind == Kind::Mixed) {
        if (faces.size() == 12) {
          const std::array<Key, 8> corner = corners(c);
          std::array<bool, 8> in{};
          for (int b = 0; b < 8; ++b) in[b] = inside(corner[b]);
          kuhn(c, corner, in);
        } else {
          const Key centre = point_key(c.i * s + s / 2, c.j * s + s / 2, c.k * s + s / 2);
          for (const Triangle& tri : faces) march_tet({centre, tri[0], tri[1], tri[2]}, s / 2);
        }
      }
      for (int f = 0; f < 6; ++f) {
        if (!on_box(f)) continue;
        for (std::size_t t = first[f]; t < first[f + 1]; ++t) close_box(faces[t], f / 2, f % 2 == 0 ? -1 : 1);
      }
    }
  }

  const Expression& f_;
  const PolygonizeOptions& o_;
  int lmax_ = 0;
  std::array<std::int64_t, 3> top_ = {1, 1, 1};         // level-0 cells per axis
  std::array<std::int64_t, 3> resolution_ = {2, 2, 2};  // lattice steps per axis
  double feature_ = 0.0;
  double finest_ = 0.0;
  bool coarse_ = false;   // the coarse octree and edge splits (with simplify)
  bool refined_ = false;  // the edge splits succeeded
  PolygonizeResult result_;
  CancelPoll poll_;
  FlatMap<Key, Kind, KeyHash> leaves_;                  // leaves (and split former leaves) by cell key
  long leaf_count_ = 0;
  FlatMap<Key, PointData, KeyHash> points_;
  FlatMap<Key, char, KeyHash> present_;                  // lattice points that are leaf corners
  FlatMap<std::pair<Key, Key>, int, PairHash> roots_;    // mesh vertex on a tetrahedron edge
  FlatMap<Key, int, KeyHash> box_vertices_;
};

}  // namespace

PolygonizeResult polygonize(const Expression& f, const PolygonizeOptions& options) {
  const Box& box = options.box;
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a]) || !(box.lo[a] < box.hi[a])) {
      throw InvalidInput("polygonize: the box must be finite with lo < hi in x, y and z");
    }
  }
  const double longest = (box.hi - box.lo).maxCoeff();
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance)) {
    throw InvalidInput("polygonize: the tolerance must be a finite number > 0");
  }
  if (options.tolerance < 4e-6 * longest) {
    throw InvalidInput("polygonize: the tolerance is below 4e-6 of the box's longest side (" +
                       std::to_string(4e-6 * longest) + "), the octree's finest level");
  }
  if (!(options.feature_size >= 0) || !std::isfinite(options.feature_size)) {
    throw InvalidInput("polygonize: feature_size must be a finite number >= 0");
  }
  if (options.max_cells <= 0) throw InvalidInput("polygonize: max_cells must be > 0");
  bool ok = false;
  if (options.simplify) {
    PolygonizeResult r = Polygonizer(f, options).run(true, ok);
    if (ok) {
      r.coarse = true;
      return r;
    }
  }
  return Polygonizer(f, options).run(false, ok);  // the fine octree, as without simplify
}

}  // namespace sculpt::implicit
