#include "bsp/primitives.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <new>
#include <numbers>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "base/errors.hpp"
#include "bsp/rings/ring_boundary.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree_builder.hpp"

namespace sculpt {

using kernel::Int128;
using kernel::Plane;

namespace {

constexpr int kPathNormalBits = 26;  // integer 2D normals of the path edges (docs/kernel.md)
constexpr double kPathScale = double(std::int64_t(1) << kPathNormalBits);  // scaling by it is exact

void check_segments(int segments) {
  if (segments < 3 || segments > 1 << 16)
    throw InvalidInput("segments must be in [3, 65536], got " + std::to_string(segments));
}

void check_positive(double v, const char* what) {
  if (!(v > 0) || !std::isfinite(v))
    throw InvalidInput(std::string(what) + " must be positive and finite");
}

// Balanced tree over the faces around the z axis (Ihm & Naylor 1990 sec. 6): planes through the
// axis split the angle range in halves; small ranges end in a chain of face planes. Face f spans
// the angles [start[f], start[f + 1]] (increasing, mod 2 pi). Each range is widened by one
// face on both sides; faces that do not cut their cell are removed by TreeBuilder::build.
// The axial planes are moved off the axis by small distinct offsets (below a tenth of the
// narrowest face) so that no three of them meet in a line: otherwise every vertex on the axis
// would be an exact degenerate case for every other axial plane. Where the path has vertices on
// the coordinate axes whose ring vertices lie exactly on the planes y = 0 and x = 0, those two
// planes (through the axis, no offset) split first, at the vertices: solids and cuts aligned
// with the axes (boxes, mirror halves, other ring primitives on the same axis) then meet the
// tree in shared planes, which a merge absorbs whole, instead of crossing every wedge.
struct SectorOptions {
  bool auxiliary_axes = true;  ///< the axial planes carry no face (see revolve_rings)
  int widen = 0;               ///< chains hold at least this many extra faces on each side
  /// Path vertices on the +x, +y, -x, -y axes (face index starting there) whose ring vertices lie
  /// exactly on y = 0 (+x, -x) or x = 0 (+y, -y), or -1. Used when +x and -x are both known.
  std::array<int, 4> axis_vertex = {-1, -1, -1, -1};
};

class SectorTree {
 public:
  /// Faces start at the angles `start`; one SectorTree builds the trees of several bands of the
  /// same path: they split at the same angles, so the tree's shape is worked out once (at the
  /// first build) and each band only adds its planes and nodes.
  using Options = SectorOptions;
  SectorTree(TreeBuilder& b, const std::vector<double>& start, const Options& options = {})
      : b_(b), start_(start), n_(int(start.size())), options_(options) {}

  /// The tree over `faces` (plane indices, face i starting at start[i]), added to the builder in
  /// pre-order (TreeBuilder::open_node); axial planes are moved off the axis by at most `max_offset`.
  TreeRef build(const std::vector<std::int32_t>& faces, double max_offset = 0) {
    if (shape_.empty()) make_shape();
    // Axial planes in the order the recursion met them: their offsets depend on that order.
    axial_id_.clear();
    axial_plane_.resize(axial_.size());  // all made first, then added (see revolve_rings' band)
    for (std::size_t i = 0; i < axial_.size(); ++i) {
      const Axial& x = axial_[i];
      ::new (&axial_plane_[i]) kernel::Plane(x.exact ? kernel::make_plane(x.exact_a, x.exact_b, 0, 0)
                                                     : kernel::plane_from_scaled_normal(x.normal, max_offset * x.fraction));
    }
    for (const kernel::Plane& p : axial_plane_) axial_id_.push_back(b_.add_plane(p, options_.auxiliary_axes));
    const TreeRef base = b_.open_nodes(std::int32_t(shape_.size()));
    for (std::size_t i = 0; i < shape_.size(); ++i) {
      const ShapeNode& s = shape_[i];
      auto at = [base](TreeRef c) { return is_leaf(c) ? c : base + c; };
      b_.set_node(base + TreeRef(i), s.axial >= 0 ? axial_id_[std::size_t(s.axial)] : faces[std::size_t(s.face)],
                  at(s.negative), at(s.positive));
    }
    return base;
  }
  /// Nodes and axial planes of each band's tree.
  std::size_t nodes() {
    if (shape_.empty()) make_shape();
    return shape_.size();
  }
  std::size_t axial_planes() {
    if (shape_.empty()) make_shape();
    return axial_.size();
  }
  /// True if some chain was widened beyond the faces its wedge overlaps (after build()): its extra
  /// faces may miss their cells, so the tree needs TreeBuilder's full build.
  bool widened() const { return widened_; }

 private:
  // One node of the shape: an axial plane (index into axial_) or a face (index into faces), with
  // children as shape indices or leaves.
  struct ShapeNode {
    std::int32_t axial = -1, face = -1;
    TreeRef negative = kOut, positive = kOut;
  };
  struct Axial {
    kernel::ScaledNormal normal;  // of the plane through the axis at its angle, the same in every band
    double fraction;              // the share of max_offset its offset takes
    bool exact = false;           // y = 0 or x = 0 through the axis, no offset: (exact_a, exact_b, 0, 0)
    std::int64_t exact_a = 0, exact_b = 0;
  };

  // The recursion the tree follows, once: nodes bottom-up (children first), then laid out in
  // pre-order. Axial planes are numbered in the order they are met (positive subtrees first).
  void make_shape() {
    if (options_.axis_vertex[0] >= 0 && options_.axis_vertex[2] >= 0) {
      axis_shape();
      return;
    }
    // First split: the plane through the axis and the middle of face 0.
    const double a0 = mid(0);
    // Every later split is at a face middle; the first plane's opposite ray may pass near a
    // vertex (odd counts, irregular paths): then widen the chains by one face.
    const double opposite = a0 + std::numbers::pi;
    int f = 0;
    while (angle(f + 1) <= opposite) ++f;
    const double width = angle(f + 1) - angle(f);
    widen_ = std::min(opposite - angle(f), angle(f + 1) - opposite) < 0.25 * width ? 1 : 0;
    widen_ = std::max(widen_, options_.widen);
    widened_ = widen_ != 0;
    const std::int32_t p = axial(std::sin(a0), std::cos(a0));
    const TreeRef positive = wedge(a0, a0 + std::numbers::pi);
    const TreeRef negative = wedge(a0 + std::numbers::pi, a0 + 2 * std::numbers::pi);
    layout(node({.axial = p, .negative = negative, .positive = positive}));
  }

  // Split at the path's vertices on the axes: y = 0 (positive for angles in (0, pi)), then in each
  // half x = 0 (f = -x: positive for angles in (pi/2, 3 pi/2)) where that half has its vertex.
  // Every wedge is bounded by vertices, so its chains hold exactly its faces.
  void axis_shape() {
    widen_ = options_.widen;
    widened_ = widen_ != 0;
    const auto& v = options_.axis_vertex;
    auto after = [this](int i, int base) { return i < base ? i + n_ : i; };  // unwrapped, from base on
    const int x_pos = v[0], x_neg = after(v[2], x_pos), end = x_pos + n_;
    const std::int32_t y_plane = exact_axial(0, 1);
    std::int32_t x_plane = -1;
    auto half = [&](int first, int mid, int last) {  // faces first..last, `mid` the vertex between, or -1
      if (mid < 0) return faces(first, last);
      if (x_plane < 0) x_plane = exact_axial(1, 0);
      const TreeRef low = faces(first, mid - 1), high = faces(mid, last);  // low: x > 0 in the upper half
      const bool upper = first == x_pos;
      return node({.axial = x_plane, .negative = upper ? low : high, .positive = upper ? high : low});
    };
    const TreeRef upper = half(x_pos, v[1] < 0 ? -1 : after(v[1], x_pos), x_neg - 1);
    const TreeRef lower = half(x_neg, v[3] < 0 ? -1 : after(v[3], x_neg), end - 1);
    layout(node({.axial = y_plane, .negative = lower, .positive = upper}));
  }

  void layout(TreeRef root) {
    // Pre-order: each node, then its negative subtree, then its positive one (explicit stack).
    std::vector<std::int32_t> at(made_.size());
    std::vector<TreeRef> stack{root};
    while (!stack.empty()) {
      const TreeRef t = stack.back();
      stack.pop_back();
      at[std::size_t(t)] = std::int32_t(shape_.size());
      shape_.push_back(made_[std::size_t(t)]);
      for (const TreeRef c : {made_[std::size_t(t)].positive, made_[std::size_t(t)].negative})
        if (!is_leaf(c)) stack.push_back(c);
    }
    for (ShapeNode& s : shape_)
      for (TreeRef* c : {&s.negative, &s.positive})
        if (!is_leaf(*c)) *c = at[std::size_t(*c)];
    made_.clear();
  }

  double angle(int i) const {  // start angle of face i (any integer i), unwrapped
    const int k = ((i % n_) + n_) % n_;
    const double turns = std::floor(double(i) / n_);
    return start_[std::size_t(k)] + 2 * std::numbers::pi * turns;
  }
  double mid(int i) const { return 0.5 * (angle(i) + angle(i + 1)); }
  // Smallest index i with angle(i) > a (angle is increasing in i): binary search.
  int first_above(double a) const {
    int lo = int(std::floor((a - start_[0]) / (2 * std::numbers::pi))) * n_ - n_, hi = lo + 3 * n_;
    while (lo < hi) {
      const int m = lo + (hi - lo) / 2;
      if (angle(m) > a)
        hi = m;
      else
        lo = m + 1;
    }
    return lo;
  }
  std::int32_t axial(double sin_a, double cos_a) {
    // f = -sin(a) x + cos(a) y + offset: positive for angles in (a, a + pi) (offset aside).
    const double fraction = 0.5 + 0.5 * std::fmod(0.6180339887498949 * double(axial_.size() + 1), 1.0);
    axial_.push_back({kernel::scale_normal({-sin_a, cos_a, 0.0}), fraction});
    return std::int32_t(axial_.size() - 1);
  }
  std::int32_t exact_axial(std::int64_t sin_a, std::int64_t cos_a) {  // f = -sin(a) x + cos(a) y
    axial_.push_back({kernel::ScaledNormal{}, 0.0, true, -sin_a, cos_a});
    return std::int32_t(axial_.size() - 1);
  }
  TreeRef node(const ShapeNode& s) {
    made_.push_back(s);
    return TreeRef(made_.size() - 1);
  }
  // Tree for the wedge of angles (lo, hi), hi - lo <= pi.
  TreeRef wedge(double lo, double hi) {
    // Faces overlapping (lo, hi): first index with angle(i+1) > lo, last with angle(i) < hi.
    const int first = first_above(lo) - 1;  // angle(first + 1) > lo >= angle(first)
    int last = first_above(hi) - 1;         // last face starting below hi (angle(i) < hi)
    while (last >= first && angle(last) >= hi) --last;  // a face starting exactly at hi (odd n)
    if (last < first) throw std::logic_error("SectorTree: empty wedge");
    return faces(first, last);
  }
  // Tree for a wedge overlapping exactly faces first..last (unwrapped indices). Inner wedges end
  // at face middles, so splitting at the middle of face k leaves faces first..k and k..last.
  TreeRef faces(int first, int last) {
    if (last - first + 1 <= 4) {
      // Widened by one face on each side only where a wedge bound may pass near a vertex
      // (first split, prisms); between face middles the chain is exactly first..last.
      TreeRef t = kIn;  // a convex chain: inside below every face, outside above any
      for (int i = last + widen_; i >= first - widen_; --i) t = node({.face = std::int32_t(wrap(i)), .negative = t});
      return t;
    }
    const int k = (first + last) / 2;
    const double a = mid(int(wrap(k)));  // the middle of face k, as an angle in [start[0], start[0] + 2 pi)
    const std::int32_t p = axial(std::sin(a), std::cos(a));
    const TreeRef positive = faces(k, last);
    const TreeRef negative = faces(first, k);
    return node({.axial = p, .negative = negative, .positive = positive});
  }
  std::size_t wrap(int i) const { return std::size_t(((i % n_) + n_) % n_); }

  TreeBuilder& b_;
  const std::vector<double>& start_;
  int n_;
  Options options_;
  int widen_ = 1;
  bool widened_ = false;
  std::vector<ShapeNode> shape_, made_;    // the tree's shape in pre-order; bottom-up while made
  std::vector<Axial> axial_;               // axial planes in the order they are added
  std::vector<std::int32_t> axial_id_;     // their planes in the band being built
  std::vector<kernel::Plane> axial_plane_;
};

}  // namespace

std::vector<Eigen::Vector2d> circle_path(int segments) {
  check_segments(segments);
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * std::numbers::pi * i / segments;
    p.emplace_back(std::cos(a), std::sin(a));
  }
  return p;
}

Solid revolve_rings(const std::vector<Eigen::Vector2d>& path, const std::vector<Ring>& rings) {
  const int n = int(path.size());
  if (n < 3) throw InvalidInput("revolution path needs at least 3 vertices");
  if (rings.size() < 2) throw InvalidInput("revolution needs at least 2 rings");
  // Path edges: integer outward normals and offsets (the origin must be strictly inside).
  std::vector<Eigen::Vector2d> normal(static_cast<std::size_t>(n));
  std::vector<std::int64_t> nx(static_cast<std::size_t>(n)), ny(static_cast<std::size_t>(n));
  std::vector<double> offset(static_cast<std::size_t>(n)), start(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d& v = path[std::size_t(j)];
    const Eigen::Vector2d& w = path[std::size_t((j + 1) % n)];
    Eigen::Vector2d e = w - v;
    if (!(e.norm() > 0)) throw InvalidInput("revolution path has repeated vertices");
    Eigen::Vector2d m(e.y(), -e.x());
    m.normalize();
    normal[std::size_t(j)] = m;
    nx[std::size_t(j)] = std::llround(std::ldexp(m.x(), kPathNormalBits));
    ny[std::size_t(j)] = std::llround(std::ldexp(m.y(), kPathNormalBits));
    offset[std::size_t(j)] = m.dot(v);
    if (!(offset[std::size_t(j)] > 0))
      throw InvalidInput("revolution path must be convex, counter-clockwise and contain the axis");
    start[std::size_t(j)] = std::atan2(v.y(), v.x());
  }
  double min_edge = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) min_edge = std::min(min_edge, (path[std::size_t((j + 1) % n)] - path[std::size_t(j)]).norm());
  for (int j = 1; j < n; ++j)  // unwrap to increasing angles
    while (start[std::size_t(j)] <= start[std::size_t(j - 1)]) start[std::size_t(j)] += 2 * std::numbers::pi;
  if (start[std::size_t(n - 1)] - start[0] >= 2 * std::numbers::pi)
    throw InvalidInput("revolution path must be convex and counter-clockwise");

  // Rings on the grid: z in grid units, offsets c = scale * offset in grid units * normal scale.
  const std::size_t r = rings.size();
  std::vector<std::int64_t> z(r);
  for (std::size_t k = 0; k < r; ++k) {
    if (!(rings[k].scale >= 0) || !std::isfinite(rings[k].scale))
      throw InvalidInput("ring scale must be finite and >= 0");
    if (rings[k].scale == 0 && k != 0 && k + 1 != r)
      throw InvalidInput("only the first and the last ring may have scale 0");
    z[k] = kernel::snap(rings[k].z);
    if (k > 0 && z[k] <= z[k - 1]) {
      std::ostringstream s;
      s << "ring heights must increase by at least one grid step (" << kernel::kGridStep << ")";
      throw InvalidInput(s.str());
    }
  }
  auto c_of = [&](std::size_t k, int j) -> Int128 {
    const double c = rings[k].scale * offset[std::size_t(j)] / kernel::kGridStep;
    if (std::fabs(c) * 1.5 > double(kernel::kMaxCoord))
      throw RangeError("revolved solid exceeds the exact kernel's range " + kernel::range_text());
    return Int128(std::llround(c * kPathScale));
  };

  // Path vertices on the axes whose ring vertices lie exactly on y = 0 or x = 0 (SectorOptions):
  // at ring k, edges p = j - 1 and q = j meet where nx_p x + ny_p y = C_p and nx_q x + ny_q y = C_q
  // (C = c_of(k, .), |C| < 2^51, |n| <= 2^26: the products are exact), so the vertex has y = 0 iff
  // nx_p C_q = nx_q C_p, and x = 0 iff C_p ny_q = C_q ny_p. A ring of scale 0 is on the axis.
  std::array<int, 4> axis_vertex = {-1, -1, -1, -1};  // +x, +y, -x, -y
  for (int j = 0; j < n; ++j) {
    // Candidates: path vertices within 1e-9 rad of an axis (no trigonometry: |other| <= 1e-9 |own|).
    const double x = path[std::size_t(j)].x(), y = path[std::size_t(j)].y();
    const int d = std::fabs(y) <= 1e-9 * std::fabs(x) ? (x > 0 ? 0 : 2) : (std::fabs(x) <= 1e-9 * std::fabs(y) ? (y > 0 ? 1 : 3) : -1);
    if (d >= 0) {
      const std::size_t p = std::size_t((j + n - 1) % n), q = std::size_t(j);
      bool on = true;
      for (std::size_t k = 0; k < rings.size() && on; ++k) {
        const Int128 cp = c_of(k, int(p)), cq = c_of(k, int(q));
        on = d % 2 == 0 ? Int128(nx[p]) * cq == Int128(nx[q]) * cp : cp * ny[q] == cq * ny[p];
      }
      if (on) axis_vertex[std::size_t(d)] = j;
    }
  }

  // The direct boundary needs every path edge on every ring of positive scale. Rounding moves an
  // edge's line by at most delta grid units, which moves its ends by at most 2 delta / sin(exterior
  // angle): edges much longer than that survive.
  std::vector<double> scale(r);
  double shortest = std::numeric_limits<double>::infinity(), largest = 0, min_sin = 1, far = 0;
  for (std::size_t k = 0; k < r; ++k) {
    scale[k] = rings[k].scale;
    largest = std::max(largest, scale[k]);
    if (scale[k] > 0) shortest = std::min(shortest, scale[k] * min_edge / kernel::kGridStep);
  }
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d& a = normal[std::size_t(j)];
    const Eigen::Vector2d& c = normal[std::size_t((j + 1) % n)];
    min_sin = std::min(min_sin, std::fabs(a.x() * c.y() - a.y() * c.x()));
    far = std::max(far, path[std::size_t(j)].norm());
  }
  // Normals rounded to 2^-26 turn a line by 2^-26 (moving it by R 2^-26 at radius R); offsets are
  // rounded to 2^-27 grid units: delta below (R + 1) 2^-25, taken with a margin of 2. Two lines
  // moved by delta at exterior angle t meet at most 2 delta / sin t away, so an edge of length L
  // survives if L sin t > 4 delta; 8 delta leaves another factor of 2.
  const double delta = (largest * far / kernel::kGridStep + 1) * std::ldexp(1.0, -24);
  const bool degenerate = r == 2 && !(scale[0] > 0) && !(scale[1] > 0);
  const bool direct = !degenerate && shortest * min_sin > 8 * delta;

  TreeBuilder b;
  // Below that bound, rounding can move a face out of the wedge whose chain should hold it: the
  // solid then bends along an axial plane, which must then count as a face plane (not auxiliary)
  // for extraction to find that boundary. Chains are widened so that this stays rare.
  SectorTree sectors(b, start, {.auxiliary_axes = direct, .widen = direct ? 0 : 1, .axis_vertex = axis_vertex});
  // Exactly: the ring planes, per band n face planes, its axial planes and the opposite of its
  // lower ring plane; the two cap nodes, the inner ring nodes and each band's sector tree.
  b.reserve(std::size_t(kernel::kWorldPlanes) + r + (r - 1) * (std::size_t(n) + sectors.axial_planes() + 1),
            r + (r - 1) * sectors.nodes());
  // Ring planes z = z_k: f = z - z_k.
  std::vector<std::int32_t> ring_plane(r);
  std::vector<std::vector<std::int32_t>> face_index(r - 1);
  // Inner rings only separate bands (auxiliary); the first and last ring planes are the caps.
  for (std::size_t k = 0; k < r; ++k) {
    ring_plane[k] = b.add_plane(kernel::make_plane(0, 0, 1, -Int128(z[k])), k > 0 && k + 1 < r);
  }
  // The x, y part of a face normal is dz (nx, ny): the gcd of those two is dz gcd(nx, ny), so
  // make_plane needs only the gcd with the z part (the same planes, one gcd per face less).
  std::vector<std::uint64_t> xy_gcd(static_cast<std::size_t>(n));
  for (std::size_t j = 0; j < std::size_t(n); ++j)
    xy_gcd[j] = std::gcd(std::uint64_t(std::llabs(nx[j])), std::uint64_t(std::llabs(ny[j])));
  std::vector<Int128> c_below(static_cast<std::size_t>(n)), c_above(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) c_above[std::size_t(j)] = c_of(0, j);
  // Band k's face planes and tree (bands come in increasing order).
  std::vector<Plane> face_plane(static_cast<std::size_t>(n));
  auto band = [&](std::size_t k) -> TreeRef {
    const Int128 dz = z[k + 1] - z[k];
    std::swap(c_below, c_above);  // ring k's offsets were ring k + 1's of the band below
    for (int j = 0; j < n; ++j) c_above[std::size_t(j)] = c_of(k + 1, j);
    std::vector<std::int32_t> faces(static_cast<std::size_t>(n));
    // All planes first, then into the table: one just returned by make_plane (written in 8-byte
    // parts) and copied at once by PlaneTable::add (16-byte loads) waited for its stores to leave
    // the store queue (failed store forwarding, ~6 % of sphere(32)). Placement new: made in place.
    for (std::size_t j = 0; j < std::size_t(n); ++j) {
      const Int128 c0 = c_below[j], dc = c_above[j] - c0;
      // dz (n . (x, y)) - dc z + (dc z_k - dz c_k) = 0, positive outside. The gcd of all four is
      // gcd(dz X, dc, dc z_k - dz c_k) = gcd(dc, dz gcd(X, c_k)) with X = gcd(nx, ny): a divisor of
      // dz X and dc divides d exactly when it divides dz c_k (|c| < 2^52, dz X < 2^53).
      const std::uint64_t x = xy_gcd[j], c0m = std::uint64_t(c0 < 0 ? -c0 : c0);
      const std::uint64_t y = std::uint64_t(dz) * (x == 1 ? 1 : std::gcd(x, c0m % x));
      const std::uint64_t dcm = std::uint64_t(dc < 0 ? -dc : dc);
      ::new (&face_plane[j]) Plane(kernel::make_plane(dz * nx[j], dz * ny[j], -dc, dc * z[k] - dz * c0,
                                                      {.gcd = y == 1 ? 1 : std::gcd(y, dcm % y)}));
    }
    for (std::size_t j = 0; j < std::size_t(n); ++j) faces[j] = b.add_plane(face_plane[j]);
    const double min_scale = std::min(rings[k].scale, rings[k + 1].scale);
    const TreeRef t = sectors.build(faces, 0.05 * min_scale * min_edge);
    face_index[k] = std::move(faces);
    return t;
  };
  // The tree top-down in pre-order (TreeBuilder::open_nodes), so the builder keeps it as laid out:
  // the bottom cap's plane, the top cap's, then a balanced tree over the bands split by the inner
  // ring planes (explicit recursion depth is log2 of the ring count), lower bands first.
  const TreeRef root = b.open_nodes(2), top = root + 1;
  auto slabs = [&](auto&& self, std::size_t lo, std::size_t hi) -> TreeRef {
    if (lo == hi) return band(lo);
    const std::size_t m = (lo + hi + 1) / 2;  // ring between band m - 1 and band m
    const TreeRef node = b.open_nodes(1);
    const TreeRef negative = self(self, lo, m - 1);
    b.set_node(node, ring_plane[m], negative, self(self, m, hi));
    return node;
  };
  b.set_node(top, ring_plane[r - 1], slabs(slabs, 0, r - 2), kOut);
  b.set_node(root, ring_plane[0], kOut, top);
  if (!direct) return std::move(b).build(root);
  // Every node then cuts its cell: ring planes cut their slabs and axial planes their wedges (both
  // reach the world box), and each chain face keeps the middle part of its facet inside its wedge
  // (wedges end at face middles, facets are convex and survive rounding), so the tree is kept as
  // built. Widened chains may hold faces outside their wedges: those are left to the full build.
  std::vector<BoundaryFragment> boundary = detail::ring_boundary(b, ring_plane, face_index, scale);
  return std::move(b).build(root, std::move(boundary), {.nodes_cut_cells = !sectors.widened()});
}

Solid box(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  const kernel::GridPoint lo = kernel::snap(min), hi = kernel::snap(max);
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    throw InvalidInput("box: min must be below max in every axis (after snapping to the grid)");
  TreeBuilder b;
  const Plane value[6] = {kernel::make_plane(1, 0, 0, -Int128(hi.x)), kernel::make_plane(-1, 0, 0, Int128(lo.x)),
                          kernel::make_plane(0, 1, 0, -Int128(hi.y)), kernel::make_plane(0, -1, 0, Int128(lo.y)),
                          kernel::make_plane(0, 0, 1, -Int128(hi.z)), kernel::make_plane(0, 0, -1, Int128(lo.z))};
  std::vector<std::int32_t> faces;
  for (const Plane& p : value) faces.push_back(b.add_plane(p));
  // The six faces, carried by the solid: face 2a + s (axis a, s = 0 for +, 1 for -) has the four
  // faces of the other two axes as edges, counter-clockwise about its outward normal.
  std::vector<BoundaryFragment> boundary;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) right-handed
      // Counter-clockwise about +axis: +u, +v, -u, -v; about -axis the reverse cycle.
      int cycle[4] = {2 * u, 2 * v, 2 * u + 1, 2 * v + 1};
      if (side == 1) std::swap(cycle[1], cycle[3]);
      kernel::ConvexPolygon poly;
      poly.support = faces[std::size_t(2 * axis + side)];
      for (int i = 0; i < 4; ++i) {
        const int prev = cycle[(i + 3) % 4], edge = cycle[i];
        poly.corners.push_back({faces[std::size_t(edge)], faces[std::size_t(prev)], faces[std::size_t(edge)],
                                kernel::approximate_vertex(value[2 * axis + side], value[prev], value[edge])});
      }
      boundary.push_back({std::move(poly), false});
    }
  return std::move(b).build(b.add_convex_chain(faces), std::move(boundary), {.nodes_cut_cells = true});
}

Solid convex_polytope(const std::vector<HalfSpace>& half_spaces) {
  if (half_spaces.empty()) throw InvalidInput("convex_polytope needs at least one half-space");
  TreeBuilder b;
  std::vector<std::int32_t> faces;
  for (const HalfSpace& h : half_spaces) faces.push_back(b.add_plane(kernel::plane_from_normal(h.normal, h.offset)));
  return std::move(b).build(b.add_convex_chain(faces));
}

Solid prism(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1) {
  if (polygon.size() < 3) throw InvalidInput("prism: polygon needs at least 3 vertices");
  if (!(z0 < z1)) throw InvalidInput("prism: z0 must be below z1");
  // Exact side planes through grid points; a balanced tree needs the axis inside: build around
  // the snapped centroid, then translate (exact).
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : polygon) centroid += p;
  centroid /= double(polygon.size());
  const Eigen::Vector3d shift(kernel::snap(centroid.x()) * kernel::kGridStep,
                              kernel::snap(centroid.y()) * kernel::kGridStep, 0.0);
  const std::int64_t gz0 = kernel::snap(z0), gz1 = kernel::snap(z1);
  if (gz0 >= gz1) throw InvalidInput("prism: height below the grid step");
  std::vector<kernel::GridPoint> g;
  for (const auto& p : polygon) g.push_back(kernel::snap(Eigen::Vector3d(p.x() - shift.x(), p.y() - shift.y(), 0.0)));
  TreeBuilder b;
  const int n = int(g.size());
  std::vector<std::int32_t> faces;
  std::vector<double> start;
  for (int j = 0; j < n; ++j) {
    const kernel::GridPoint& v = g[std::size_t(j)];
    const kernel::GridPoint& w = g[std::size_t((j + 1) % n)];
    const kernel::GridPoint up{v.x, v.y, v.z + 1};
    const Plane p = kernel::plane_through(v, w, up);
    if (!(p.d < 0)) throw InvalidInput("prism: polygon must be convex and counter-clockwise");
    faces.push_back(b.add_plane(p));
    start.push_back(std::atan2(double(v.y), double(v.x)));
  }
  for (int j = 1; j < n; ++j)
    while (start[std::size_t(j)] <= start[std::size_t(j - 1)]) start[std::size_t(j)] += 2 * std::numbers::pi;
  if (start[std::size_t(n - 1)] - start[0] >= 2 * std::numbers::pi)
    throw InvalidInput("prism: polygon must be convex and counter-clockwise");
  const TreeRef sides = SectorTree(b, start).build(faces);
  const std::int32_t bottom = b.add_plane(kernel::make_plane(0, 0, -1, Int128(gz0)));
  const std::int32_t top = b.add_plane(kernel::make_plane(0, 0, 1, -Int128(gz1)));
  const TreeRef root = b.add_node(bottom, b.add_node(top, sides, kOut), kOut);
  return translate(std::move(b).build(root), shift);
}

Solid cylinder(double radius, double height, const CircularOptions& options) {
  return cone(radius, height, options, radius);
}

Solid cone(double radius, double height, const CircularOptions& options, double top_radius) {
  check_positive(radius, "cone radius");
  check_positive(height, "cone height");
  if (!(top_radius >= 0)) throw InvalidInput("cone top radius must be >= 0");
  const double z0 = options.center ? -height / 2 : 0.0;
  return revolve_rings(circle_path(options.segments), {{z0, radius}, {z0 + height, top_radius}});
}

Solid sphere(double radius, const CircularOptions& options) {
  check_positive(radius, "sphere radius");
  check_segments(options.segments);
  const int rings = (options.segments + 1) / 2;
  std::vector<Ring> r;
  for (int k = rings - 1; k >= 0; --k) {  // bottom to top
    const double phi = (k + 0.5) * std::numbers::pi / rings;
    r.push_back({radius * std::cos(phi), radius * std::sin(phi)});
  }
  return revolve_rings(circle_path(options.segments), r);
}

}  // namespace sculpt
