#include "bsp/local/kd_cells.hpp"
#include "base/cancel.hpp"
#include "base/parallel.hpp"

#include <algorithm>
#include <cmath>

#include "kernel/convex_polygon.hpp"

namespace sculpt::bsp::detail {

namespace {

constexpr std::int64_t kWorldHalf = 2 * kernel::PlaneTable::kWorld + 1;  // beyond the world box

// The closed box of a fragment, widened to everything for an invalid one.
double lo_of(const FragmentBox& b, int k) { return b.valid ? double(b.lo[k]) : -1e300; }
double hi_of(const FragmentBox& b, int k) { return b.valid ? double(b.hi[k]) : 1e300; }

// An odd value (half units) for the grid coordinate v: the wall just above floor(v).
std::int64_t odd_at(double v) { return 2 * std::int64_t(std::floor(v)) + 1; }

CellBounds root_bounds(const std::array<std::span<const FragmentBox>, 2>& boxes) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const auto& list : boxes)
    for (const FragmentBox& b : list)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], lo_of(b, k)), hi[k] = std::max(hi[k], hi_of(b, k));
  CellBounds c;
  for (int k = 0; k < 3; ++k) {
    const double w = double(kernel::PlaneTable::kWorld);
    c.lo[k] = lo[k] < -w ? -kWorldHalf : odd_at(lo[k]) - 2;  // floor(lo) - 1/2
    c.hi[k] = hi[k] > w ? kWorldHalf : odd_at(hi[k]) + 2;    // floor(hi) + 3/2 > hi
  }
  return c;
}

struct Choice {
  int axis = -1;
  std::int64_t split = 0;
};

// Where to split a cell: across its longest side, in the widest gap between its fragments' box
// ends among the middle half of them (balanced counts, and a wall far from every vertex it might
// cut near: a piece cut off within a grid step of an edge would round to a sliver), or at the
// middle when that makes no progress; none if the cell is too thin to hold an odd wall inside.
Choice choose_split(const KdNode& n, const std::array<std::span<const FragmentBox>, 2>& boxes, int attempt) {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (n.bounds.hi[k] - n.bounds.lo[k] > n.bounds.hi[axis] - n.bounds.lo[axis]) axis = k;
  const std::int64_t lo = n.bounds.lo[axis], hi = n.bounds.hi[axis];
  if (hi - lo < 4) return {};
  std::int64_t s;
  if (attempt == 0) {
    // The ends of at most about 256 boxes, evenly spaced through both lists.
    std::vector<double> ends;
    const std::size_t total = n.items[0].size() + n.items[1].size(), step = std::max<std::size_t>(1, total / 256);
    for (std::size_t k = 0; k < total; k += step) {
      const int op = k < n.items[0].size() ? 0 : 1;
      const FragmentBox& b = boxes[op][n.items[op][op == 0 ? k : k - n.items[0].size()]];
      if (b.valid) ends.push_back(double(b.lo[axis])), ends.push_back(double(b.hi[axis]));
    }
    if (ends.size() < 2) return {};
    std::sort(ends.begin(), ends.end());
    const std::size_t first = ends.size() / 4, last = std::max(first + 1, 3 * ends.size() / 4);
    std::size_t best = first;
    for (std::size_t k = first; k < last && k + 1 < ends.size(); ++k)
      if (ends[k + 1] - ends[k] > ends[best + 1] - ends[best]) best = k;
    // The sample's gap, widened to the gap between the nearest ends of all the cell's boxes.
    const double mid = 0.5 * (ends[best] + ends[std::min(best + 1, ends.size() - 1)]);
    double below = -1e300, above = 1e300;
    for (int op = 0; op < 2; ++op)
      for (const std::uint32_t i : n.items[op]) {
        const FragmentBox& b = boxes[op][i];
        if (!b.valid) continue;
        for (const double e : {double(b.lo[axis]), double(b.hi[axis])}) {
          if (e <= mid) below = std::max(below, e);
          if (e >= mid) above = std::min(above, e);
        }
      }
    s = odd_at(below > -1e300 && above < 1e300 ? 0.5 * (below + above) : mid);
  } else {
    s = lo + (hi - lo) / 2;
    if (s % 2 == 0) s += 1;  // lo, hi odd: hi - lo even, so the middle is odd or one off
  }
  s = std::clamp(s, lo + 2, hi - 2);
  return {axis, s};
}

// A wall with all of one operand's fragments strictly below it and all of the other's strictly
// above (by their boxes), inside the cell: there the operands' boundaries are apart, so each
// side of the wall holds one operand's pieces only and needs only the other's status (step 4 of
// the cell merge) instead of two local trees that every piece is pushed down. None if the boxes
// overlap on every axis (or one is unknown).
Choice separating_split(const KdNode& n, const std::array<std::span<const FragmentBox>, 2>& boxes) {
  for (int axis = 0; axis < 3; ++axis) {
    double top[2] = {-1e300, -1e300}, bottom[2] = {1e300, 1e300};  // per operand
    for (int op = 0; op < 2; ++op)
      for (const std::uint32_t i : n.items[op]) {
        const FragmentBox& b = boxes[op][i];
        if (!b.valid) return {};
        top[op] = std::max(top[op], double(b.hi[axis]));
        bottom[op] = std::min(bottom[op], double(b.lo[axis]));
      }
    for (int below = 0; below < 2; ++below) {
      const std::int64_t s = 2 * std::int64_t(std::floor(top[below] + 0.5)) + 1;  // the first wall above top
      if (0.5 * double(s) < bottom[1 - below] && s > n.bounds.lo[axis] && s < n.bounds.hi[axis]) return {axis, s};
    }
  }
  return {};
}

// The fragments of node n on each side of the wall c (parts[side][operand]): those whose boxes
// reach it go to both. Without branches: the items come in index order, not along the axis, so
// which side an item goes to is a coin toss for the branch predictor.
void distribute(const KdNode& n, const Choice& c, const std::array<std::span<const FragmentBox>, 2>& boxes,
                std::array<std::array<std::vector<std::uint32_t>, 2>, 2>& parts) {
  const double wall = 0.5 * double(c.split);
  const int axis = c.axis;
  for (int op = 0; op < 2; ++op) {
    const std::vector<std::uint32_t>& items = n.items[op];
    std::vector<std::uint32_t>&below = parts[0][op], &above = parts[1][op];
    below.resize(items.size());
    above.resize(items.size());
    const FragmentBox* box = boxes[op].data();
    std::size_t nb = 0, na = 0;
    for (const std::uint32_t i : items) {
      const FragmentBox& b = box[i];
      below[nb] = i;
      above[na] = i;
      nb += std::size_t(!b.valid | (double(b.lo[axis]) <= wall));  // lo_of(b, axis) <= wall
      na += std::size_t(!b.valid | (double(b.hi[axis]) >= wall));  // hi_of(b, axis) >= wall
    }
    below.resize(nb);
    above.resize(na);
    // Leaves keep their lists: not twice the memory they need.
    for (std::vector<std::uint32_t>* v : {&below, &above})
      if (v->capacity() > v->size() + v->size() / 4 + 16) v->shrink_to_fit();
  }
}

// Where node n's fragments go if it is split (parts[side][operand]), or axis -1 when it stays a
// leaf: a wall between the two operands' fragments if there is one, else the split of
// choose_split, at its middle if the gap makes no progress (neither side may keep every
// fragment).
Choice split_items(const KdNode& n, int depth, const std::array<std::span<const FragmentBox>, 2>& boxes,
                   const KdOptions& options, std::array<std::array<std::vector<std::uint32_t>, 2>, 2>& parts) {
  const std::size_t total = n.items[0].size() + n.items[1].size();
  const bool both = !n.items[0].empty() && !n.items[1].empty();
  const std::size_t limit =
      both ? options.leaf_size : (n.parent_mixed ? options.near_leaf_size : options.one_operand_leaf_size);
  const bool split_worthwhile = total > limit && depth < options.max_depth;
  // Only where the cell would stay a leaf: in a larger cell such a wall leaves two large cells of
  // one operand, whose statuses may need local trees over all of their pieces.
  if (both && !split_worthwhile && depth < options.max_depth) {
    if (const Choice c = separating_split(n, boxes); c.axis >= 0) {
      distribute(n, c, boxes, parts);
      return c;
    }
  }
  Choice c;
  for (int attempt = 0; split_worthwhile && attempt < 2; ++attempt) {
    c = choose_split(n, boxes, attempt);
    if (c.axis < 0) break;
    distribute(n, c, boxes, parts);
    const bool progress =
        parts[0][0].size() + parts[0][1].size() < total && parts[1][0].size() + parts[1][1].size() < total;
    if (progress) return c;
    c.axis = -1;
  }
  return {};
}

// Subtrees with at least this many fragments, within kSpawnLevels levels of parallel splits from
// the root, are built side by side (tbb tasks); the rest depth first on one thread.
constexpr std::size_t kParallelItems = 8192;
constexpr int kSpawnLevels = 4;

struct Grow {
  const std::array<std::span<const FragmentBox>, 2>& boxes;
  const KdOptions& options;

  // Splits node `top` of `cells` (at `top_depth`) and all below it, depth first: the node ids are
  // given as one pass with an explicit stack gives them (a node's children when it is split, then
  // the lower child's subtree, then the upper's), and leaves come below before above. Where both
  // children are large, their subtrees are grown apart in parallel and appended in that order.
  void operator()(KdCells& cells, std::int32_t top, int top_depth, int level) const {
    std::vector<std::pair<std::int32_t, int>> stack{{top, top_depth}};  // node, depth
    std::array<std::array<std::vector<std::uint32_t>, 2>, 2> parts;     // [side][operand]
    while (!stack.empty()) {
      check_cancel();  // Ctrl-C (base/cancel.hpp): a node near the root sorts millions of boxes
      const auto [id, depth] = stack.back();
      stack.pop_back();
      const Choice c = split_items(cells.nodes[std::size_t(id)], depth, boxes, options, parts);
      if (c.axis < 0) {
        cells.leaves.push_back(id);
        continue;
      }
      KdNode& n = cells.nodes[std::size_t(id)];
      n.axis = c.axis;
      n.split = c.split;
      n.items[0] = {};
      n.items[1] = {};
      const CellBounds bounds = n.bounds;
      const bool mixed =
          (!parts[0][0].empty() || !parts[1][0].empty()) && (!parts[0][1].empty() || !parts[1][1].empty());
      std::size_t sizes[2];
      for (int side = 0; side < 2; ++side) {
        KdNode child;
        child.bounds = bounds;
        (side == 0 ? child.bounds.hi : child.bounds.lo)[c.axis] = c.split;
        child.parent = id;
        child.parent_mixed = mixed;
        child.items[0] = std::move(parts[side][0]);
        child.items[1] = std::move(parts[side][1]);
        sizes[side] = child.items[0].size() + child.items[1].size();
        cells.nodes[std::size_t(id)].child[side] = std::int32_t(cells.nodes.size());
        cells.nodes.push_back(std::move(child));  // invalidates n
      }
      const std::int32_t child[2] = {cells.nodes[std::size_t(id)].child[0], cells.nodes[std::size_t(id)].child[1]};
      if (level < kSpawnLevels && sizes[0] >= kParallelItems && sizes[1] >= kParallelItems) {
        KdCells sub[2];
        for (int side = 0; side < 2; ++side)
          sub[side].nodes.push_back(std::move(cells.nodes[std::size_t(child[side])]));
        parallel_invoke([&] { (*this)(sub[0], 0, depth + 1, level + 1); },
                        [&] { (*this)(sub[1], 0, depth + 1, level + 1); });
        append(cells, child, sub);
        continue;
      }
      // The lower child is visited first: leaves come in depth-first order, below before above.
      stack.push_back({child[1], depth + 1});
      stack.push_back({child[0], depth + 1});
    }
  }

  // The two subtrees grown apart (each with its root at 0) put back: each root where its child
  // was, then the lower one's other nodes, then the upper one's, with their references renumbered.
  static void append(KdCells& cells, const std::int32_t child[2], KdCells sub[2]) {
    const auto base0 = std::int32_t(cells.nodes.size());
    const std::int32_t first[2] = {base0, base0 + std::int32_t(sub[0].nodes.size()) - 1};
    for (int side = 0; side < 2; ++side) {
      auto global = [&](std::int32_t local) { return local == 0 ? child[side] : first[side] + local - 1; };
      for (std::size_t k = 0; k < sub[side].nodes.size(); ++k) {
        KdNode& node = sub[side].nodes[k];
        for (std::int32_t& c : node.child)
          if (c >= 0) c = global(c);
        if (k > 0) node.parent = global(node.parent);
      }
      cells.nodes[std::size_t(child[side])] = std::move(sub[side].nodes[0]);
      for (std::size_t k = 1; k < sub[side].nodes.size(); ++k) cells.nodes.push_back(std::move(sub[side].nodes[k]));
      for (const std::int32_t l : sub[side].leaves) cells.leaves.push_back(global(l));
    }
  }
};

}  // namespace

KdCells subdivide(const std::array<std::span<const FragmentBox>, 2>& boxes, const KdOptions& options) {
  KdCells cells;
  KdNode root;
  root.bounds = root_bounds(boxes);
  for (int op = 0; op < 2; ++op) {
    root.items[op].resize(boxes[op].size());
    for (std::uint32_t i = 0; i < boxes[op].size(); ++i) root.items[op][i] = i;
  }
  cells.nodes.push_back(std::move(root));
  Grow{boxes, options}(cells, 0, 0, 0);
  return cells;
}

}  // namespace sculpt::bsp::detail
