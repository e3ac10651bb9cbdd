#pragma once
/// \file sector_tree.hpp
/// Internal: the balanced tree over the faces around the z axis that ring primitives and prisms
/// share (Ihm & Naylor 1990 sec. 6: planes through the axis split the angle range in halves, short
/// ranges end in chains of face planes). One SectorTree builds the trees of several bands of one
/// path on one TreeBuilder.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "bsp/tree_builder.hpp"

namespace sculpt::bsp::detail {

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
  /// pre-order (TreeBuilder::open_node); axial planes are moved off the axis by at most `max_offset`
  /// (world units of `grid`).
  TreeRef build(const std::vector<std::int32_t>& faces, double max_offset = 0, const kernel::Grid& grid = {}) {
    if (shape_.empty()) make_shape();
    // Axial planes in the order the recursion met them: their offsets depend on that order.
    axial_id_.clear();
    axial_plane_.resize(axial_.size());  // all made first, then added (see revolve_rings' band)
    for (std::size_t i = 0; i < axial_.size(); ++i) {
      const Axial& x = axial_[i];
      ::new (&axial_plane_[i]) kernel::Plane(x.exact ? kernel::make_plane(x.exact_a, x.exact_b, 0, 0)
                                                     : kernel::plane_from_scaled_normal(x.normal, max_offset * x.fraction, grid));
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


}  // namespace sculpt::bsp::detail
