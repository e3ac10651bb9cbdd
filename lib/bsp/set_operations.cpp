#include "bsp/set_operations.hpp"
#include "base/cancel.hpp"
#include "base/parallel.hpp"
#include "bsp/tree/solid_access.hpp"

#include <memory>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "bsp/local/cell_merge.hpp"
#include "bsp/merge/batch_union.hpp"
#include "bsp/merge/boundary_merge.hpp"
#include "bsp/merge/extent_pruning.hpp"
#include "bsp/tree/boundary_fragments.hpp"
#include "bsp/tree/deferred_tree.hpp"
#include "bsp/tree/node_polygons.hpp"
#include "bsp/tree/tree_arena.hpp"

namespace sculpt {

using bsp::detail::Arena;
using bsp::detail::SolidAccess;
using bsp::detail::WrittenStorage;
using kernel::ConvexPolygon;
using kernel::Side;

namespace {

// Where a partition result goes: a child field of an arena node, or one of two outputs.
struct Slot {
  std::int32_t node;  // -1: out[side]
  int side;
};

class Merger {
 public:
  /// With `written` (in-place operations), the nodes of a the merge reuses and the subtrees it
  /// drops are recorded there, for reclaim_added.
  explicit Merger(Arena& arena, WrittenStorage* written = nullptr) : a_(arena), written_(written) {}

  void set(Slot s, TreeRef v) {
    if (s.node < 0)
      out_[s.side] = v;
    else if (s.side == 0)
      a_.nodes[std::size_t(s.node)].negative = v;
    else
      a_.nodes[std::size_t(s.node)].positive = v;
  }

  // Naylor et al. 1990, "partition_bspt": splits `subtree` (living in region R) by plane
  // `cut`, whose part inside R is the polygon `pp`. Uses the invariant that every node's plane
  // cuts its cell into two parts of positive volume, so when the node's sub-hyperplane S lies on
  // one side of `cut`, `pp` lies on one side of the node's plane and the other child's region
  // lies entirely on S's side of `cut`. Subtrees are moved, never shared.
  // `pp` is copied before the arena grows (it may be one of the arena's polygons). A side that
  // is not `wanted` (the caller drops it) is not built: a node cut in two stays whole on the
  // wanted side (no copy), and nodes placed wholly on the other side are left unused.
  std::pair<TreeRef, TreeRef> partition(TreeRef subtree, const ConvexPolygon& pp, std::int32_t cut,
                                        const bool wanted[2] = kBothSides) {
    std::vector<PartitionFrame>& stack = partition_stack_;
    std::vector<std::pair<TreeRef, Slot>>& touched = touched_;  // nodes placed in a result, pre-order
    stack.clear();
    touched.clear();
    stack.emplace_back();
    stack.back() = {subtree, {}, {-1, 0}, {-1, 1}};
    stack.back().pp = pp;
    const std::int32_t cut_opp = a_.opposite(cut);
    // The top frame is updated in place where one child follows (no copy of its polygon).
    // `part` is copied, never moved, out: a small_vector moved from while on the heap is left
    // with no storage at all (not even its inline buffer), so every later split into it
    // allocated (about 3 allocations per split node).
    ConvexPolygon& part = scratch_;
    while (!stack.empty()) {
      poll_.tick();
      PartitionFrame& f = stack.back();
      if (is_leaf(f.t)) {
        set(f.neg, f.t);
        set(f.pos, f.t);
        stack.pop_back();
        continue;
      }
      const TreeRef t = f.t;
      const BspNode n = a_.nodes[std::size_t(t)];
      // The node polygon's positive part goes straight into a new slot (taken back if unused).
      a_.polygons.emplace_back();
      const Side side = kernel::split(a_.planes, a_.polygons[std::size_t(t)], cut, cut_opp, part, a_.polygons.back());
      if (side != Side::Both) a_.polygons.pop_back();
      switch (side) {
        case Side::On: {  // the node is absorbed by `cut`, which takes over its faces
          const bool same = a_.planes[n.plane] == a_.planes[cut];
          if (!a_.planes.auxiliary(n.plane)) {
            a_.planes.set_auxiliary(cut, false);
            a_.planes.set_auxiliary(cut_opp, false);
          }
          set(f.neg, same ? n.negative : n.positive);
          set(f.pos, same ? n.positive : n.negative);
          stack.pop_back();
          break;
        }
        case Side::Both: {
          // Node t keeps the negative part and a copy m the positive one; with one side wanted,
          // t alone goes to that side. Slots of the other side write the dropped output.
          TreeRef tn = -1, tp = -1;
          if (wanted[0] && wanted[1]) {
            tn = t, tp = std::int32_t(a_.nodes.size());
            a_.nodes.push_back(n);
            a_.polygons[std::size_t(t)] = part;
          } else {
            (wanted[0] ? tn : tp) = t;
            if (wanted[0])
              a_.polygons[std::size_t(t)] = part;
            else
              a_.polygons[std::size_t(t)] = std::move(a_.polygons.back());
            a_.polygons.pop_back();
          }
          if (tn >= 0) {
            set(f.neg, tn);
            touched.push_back({tn, f.neg});
          }
          if (tp >= 0) {
            set(f.pos, tp);
            touched.push_back({tp, f.pos});
          }
          auto slot = [](TreeRef node, int child, int side_of_output) {
            return node >= 0 ? Slot{node, child} : Slot{-1, side_of_output};
          };
          // The negative child replaces the frame, the positive one goes on top of it; pp's
          // positive part is written into the new frame directly.
          const std::size_t top = stack.size() - 1;
          stack.emplace_back();  // invalidates f
          PartitionFrame& cur = stack[top];
          PartitionFrame& next = stack.back();
          const Side pside = kernel::split(a_.planes, cur.pp, n.plane, a_.opposite(n.plane), part, next.pp);
          if (pside == Side::Both)
            cur.pp = part;
          else  // cannot happen with exact predicates and the invariant; keep the tree valid anyway
            next.pp = cur.pp;
          next.t = n.positive, next.neg = slot(tn, 1, 0), next.pos = slot(tp, 1, 1);
          cur.t = n.negative, cur.neg = slot(tn, 0, 0), cur.pos = slot(tp, 0, 1);
          break;
        }
        case Side::Negative:
        case Side::Positive: {
          const bool node_neg = side == Side::Negative;  // node's region part stays on this side
          const Side pside = kernel::classify(a_.planes, f.pp, n.plane);
          const bool recurse_neg = pside != Side::Positive;  // pp in the node's negative half
          const Slot child_slot{t, recurse_neg ? 0 : 1};
          touched.push_back({t, node_neg ? f.neg : f.pos});
          f.t = recurse_neg ? n.negative : n.positive;  // the child follows with the same polygon
          if (node_neg) {
            set(f.neg, t);
            f.neg = child_slot;
          } else {
            set(f.pos, t);
            f.pos = child_slot;
          }
          break;
        }
      }
    }
    // A node whose two children became the same leaf is replaced by that leaf.
    for (auto it = touched.rbegin(); it != touched.rend(); ++it) {
      const BspNode& n = a_.nodes[std::size_t(it->first)];
      if (is_leaf(n.negative) && n.negative == n.positive) set(it->second, n.negative);
    }
    return {out_[0], out_[1]};
  }

  // Naylor et al. 1990, "merge_bspts": the result follows the structure of tree `a`; tree `b`
  // is partitioned by a's planes, and leaves are combined by the truth table op[in_a][in_b].
  // Tree b's sub-hyperplanes must be known (fill_node_polygons); a's pending ones are computed
  // from their paths as the merge reaches them (`a` is the root of a whole tree).
  TreeRef merge(TreeRef a, TreeRef b, const bool op[2][2]) {
    struct Frame {
      TreeRef a, b;
      Slot slot;
      std::size_t depth;  // length of a's path to this frame's parent
      std::int32_t add;   // plane this frame adds to the path, -1 at the root
    };
    std::vector<std::int32_t> path;  // a's half-spaces down to the current node
    std::vector<Frame> stack{{a, b, {-1, 0}, 0, -1}};
    std::vector<std::pair<TreeRef, Slot>> visited;  // result nodes taken from a, pre-order
    TreeRef result = kOut;
    auto put = [&](Slot s, TreeRef v) {
      if (s.node < 0)
        result = v;
      else
        set(s, v);
    };
    while (!stack.empty()) {
      poll_.tick();
      Frame f = stack.back();
      stack.pop_back();
      if (is_leaf(f.a) || is_leaf(f.b)) {
        const TreeRef v = combine(f.a, f.b, op);
        if (written_ && !is_leaf(f.a) && is_leaf(v)) written_->dropped.push_back(f.a);  // a's nodes freed
        put(f.slot, v);
        continue;
      }
      path.resize(f.depth);
      if (f.add >= 0) path.push_back(f.add);
      const BspNode n = a_.nodes[std::size_t(f.a)];
      if (bsp::detail::pending(a_.polygons[std::size_t(f.a)]))
        a_.polygons[std::size_t(f.a)] = bsp::detail::node_polygon(a_, n.plane, path);
      // A side whose child in a is a leaf that decides the result alone does not need b's part.
      const bool wanted[2] = {!decided(n.negative, op), !decided(n.positive, op)};
      TreeRef bneg = kOut, bpos = kOut;
      if (wanted[0] || wanted[1]) std::tie(bneg, bpos) = partition(f.b, a_.polygons[std::size_t(f.a)], n.plane, wanted);
      put(f.slot, f.a);  // a's node is reused: its region and sub-hyperplane are unchanged
      visited.push_back({f.a, f.slot});
      if (written_) written_->merged.push_back(f.a);
      stack.push_back({n.negative, bneg, {f.a, 0}, path.size(), n.plane});
      stack.push_back({n.positive, bpos, {f.a, 1}, path.size(), a_.opposite(n.plane)});
    }
    // Collapse nodes whose children became the same leaf, children before parents.
    for (auto it = visited.rbegin(); it != visited.rend(); ++it) {
      const BspNode& n = a_.nodes[std::size_t(it->first)];
      if (is_leaf(n.negative) && n.negative == n.positive) put(it->second, n.negative);
    }
    return result;
  }

 private:
  static constexpr bool kBothSides[2] = {true, true};

  // True if `a` is a leaf whose value alone decides op (then combine() ignores b).
  static bool decided(TreeRef a, const bool op[2][2]) {
    if (!is_leaf(a)) return false;
    const int x = a == kIn;
    return op[x][0] == op[x][1];
  }

  TreeRef combine(TreeRef a, TreeRef b, const bool op[2][2]) {
    if (is_leaf(a)) {
      const int x = a == kIn;
      if (op[x][0] == op[x][1]) return op[x][0] ? kIn : kOut;
      if (op[x][1]) return b;
      bsp::detail::complement_in_place(a_, b);
      return b;
    }
    const int y = b == kIn;
    if (op[0][y] == op[1][y]) return op[0][y] ? kIn : kOut;
    if (op[1][y]) return a;
    bsp::detail::complement_in_place(a_, a);
    return a;
  }

  struct PartitionFrame {
    TreeRef t;
    ConvexPolygon pp;
    Slot neg, pos;
  };

  Arena& a_;
  WrittenStorage* written_;
  CancelPoll poll_;  // Ctrl-C (base/cancel.hpp)
  TreeRef out_[2] = {kOut, kOut};
  // Working storage of partition(), kept between calls (one partition per node of the merge).
  std::vector<PartitionFrame> partition_stack_;
  std::vector<std::pair<TreeRef, Slot>> touched_;
  ConvexPolygon scratch_;
};

// A set operation in two steps: the boundary of op(a, b) (to arena.boundary), then the merged
// tree. Where the result out of a does not depend on b (op[0][*] constant), b only matters
// inside a: b's planes with a on one closed side are dropped (extent_pruning.hpp), from b's
// fragments before the boundary merge and from b's tree before the merge of the trees.
class MergeSteps {
 public:
  MergeSteps(TreeRef ra, TreeRef rb, std::size_t b_nodes, const bool op[2][2]) : ra_(ra), rb_(rb), b_nodes_(b_nodes) {
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) op_[i][j] = op[i][j];
  }
  // The result's boundary, from a's fragments `fa` (boxes `boxes`) and b's `fb`; the extent
  // sides first, for both steps. In place, what it rewrites goes to `written`.
  void boundary(Arena& arena, FragmentList fa, bsp::detail::FragmentBoxes boxes, const FragmentList& fb,
                WrittenStorage* written) {
    if (prunes()) {
      bsp::detail::complete_boxes(fa, boxes);
      sides_ = bsp::detail::extent_sides(arena, ra_, fa, boxes, rb_, fb);
    }
    bsp::detail::merge_boundaries(arena, ra_, std::move(fa), std::move(boxes), rb_, fb, op_,
                                  sides_ ? &*sides_ : nullptr, written);
  }
  // The same boundary without the extent sides, which wait for tree() (a deferred tree may never
  // be built): b's fragments that they would drop are pushed down a's tree and dropped there,
  // which costs less than the sides (sphere minus sphere: 2.6 against 3.4 ms at 64 segments).
  // Keeps a copy of a's fragments and b's for them.
  void boundary_sides_later(Arena& arena, FragmentList fa, bsp::detail::FragmentBoxes boxes, FragmentList fb) {
    if (prunes()) {
      bsp::detail::complete_boxes(fa, boxes);
      later_ = std::make_shared<const Later>(Later{fa, boxes, std::move(fb)});
      bsp::detail::merge_boundaries(arena, ra_, std::move(fa), std::move(boxes), rb_, later_->b_faces, op_, nullptr);
    } else {
      bsp::detail::merge_boundaries(arena, ra_, std::move(fa), std::move(boxes), rb_, fb, op_, nullptr);
    }
  }
  // The merged tree (after boundary()); returns its root. In place, what the merge rewrites
  // goes to `written`.
  TreeRef tree(Arena& arena, WrittenStorage* written = nullptr) {
    TreeRef rb = rb_;
    if (later_) {  // the trees are as they were: merge_boundaries does not change them
      sides_ = bsp::detail::extent_sides(arena, ra_, later_->a_faces, later_->a_boxes, rb_, later_->b_faces);
      later_.reset();
    }
    if (sides_) rb = bsp::detail::prune_to_extent(arena, rb, *sides_);
    bsp::detail::fill_node_polygons(arena, rb);  // b is partitioned: all its sub-hyperplanes are needed
    // Room for the nodes partition() adds (2.5-3.5 per node of b on the curved cases): one
    // allocation instead of regrowth copies (the polygons never move: PolygonStore).
    const std::size_t need = arena.nodes.size() + 4 * b_nodes_;
    if (need > arena.nodes.capacity()) arena.nodes.reserve(std::max(need, 2 * arena.nodes.capacity()));
    Merger m(arena, written);
    return m.merge(ra_, rb, op_);
  }

 private:
  bool prunes() const { return op_[0][0] == op_[0][1] && !is_leaf(rb_); }
  struct Later {  // what the extent sides are computed from
    FragmentList a_faces;
    bsp::detail::FragmentBoxes a_boxes;
    FragmentList b_faces;
  };
  TreeRef ra_, rb_;
  std::size_t b_nodes_;
  bool op_[2][2];
  std::optional<bsp::detail::ExtentSides> sides_;
  std::shared_ptr<const Later> later_;  // shared: DeferredMerge::build copies the steps
};

// A copying set operation whose tree merge waits until the result's tree is first used
// (deferred_tree.hpp): the arena keeps both operands' trees and the result's boundary.
class DeferredMerge final : public bsp::detail::DeferredTree {
 public:
  DeferredMerge(Arena&& arena, MergeSteps steps) : arena_(std::move(arena)), steps_(std::move(steps)) {}
  const kernel::PlaneTable& planes() const override { return arena_.planes; }
  const FragmentList& boundary() const override { return *arena_.boundary; }
  Solid build() override {
    // A small merge (well under a second) runs in the arena itself, shielded from Ctrl-C: if it
    // throws (out of memory), the work it began cannot be resumed.
    if (arena_.nodes.size() < kCopyBeforeMerge) {
      if (started_) throw std::logic_error("a deferred set operation failed earlier and cannot be completed");
      started_ = true;
      const CancelShield shield;
      return bsp::detail::compact(arena_, steps_.tree(arena_));
    }
    // A large one writes the trees of a copy (and a copy of the steps), so that a merge stopped by
    // Ctrl-C (Cancelled) or out of memory leaves this solid whole, and a later use runs it again.
    // The result's boundary is not copied: only compact(), which makes no cancellation check,
    // reads it; it moves to the copy and back if the merge throws.
    std::optional<FragmentList> boundary = std::exchange(arena_.boundary, std::nullopt);
    bsp::detail::FragmentBoxes boxes = std::exchange(arena_.boundary_boxes, {});
    try {
      Arena work = arena_;
      work.boundary = std::move(boundary);
      work.boundary_boxes = std::move(boxes);
      try {
        MergeSteps steps = steps_;
        return bsp::detail::compact(work, steps.tree(work));
      } catch (...) {
        boundary = std::move(work.boundary);
        boxes = std::move(work.boundary_boxes);
        throw;
      }
    } catch (...) {
      arena_.boundary = std::move(boundary);
      arena_.boundary_boxes = std::move(boxes);
      throw;
    }
  }

 private:
  // Arena nodes (both operands' trees) from which the merge runs on a copy: sphere(1, 400) minus a
  // moved copy (150,000 nodes) merges in about half a second; below, a copy would cost 10-20 %.
  static constexpr std::size_t kCopyBeforeMerge = 100000;
  Arena arena_;
  MergeSteps steps_;
  bool started_ = false;
};

Solid apply(const Solid& x, const Solid& y, const bool table[2][2]) {
  // Partition the smaller tree by the planes of the larger one (cost ~ the larger tree's
  // nodes whose cells meet the smaller solid's cells that are not single leaves).
  const bool swap = x.nodes().size() < y.nodes().size();
  const Solid& a = swap ? y : x;
  const Solid& b = swap ? x : y;
  bool op[2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) op[i][j] = swap ? table[j][i] : table[i][j];
  Arena arena;
  // The operands and the room MergeSteps::tree() reserves for the merge, at once.
  arena.nodes.reserve(a.nodes().size() + 5 * b.nodes().size());
  arena.polygons.reserve(a.nodes().size() + 5 * b.nodes().size());
  const TreeRef ra = arena.append(a);
  FragmentList fa = arena.boundary_of(a);
  const TreeRef rb = arena.append(b);
  FragmentList fb = arena.boundary_of(b);
  MergeSteps steps(ra, rb, b.nodes().size(), op);
  steps.boundary_sides_later(arena, std::move(fa), bsp::detail::SolidAccess::boundary_boxes(a), std::move(fb));
  // The tree waits for its first use (output needs the boundary alone).
  return SolidAccess::deferred(std::make_unique<DeferredMerge>(std::move(arena), std::move(steps)));
}

// apply() with x given away: when x is the larger operand and carries its boundary, its storage
// becomes the arena's instead of being copied into it (the same merge, deferred alike).
Solid apply_adopting(Solid&& x, const Solid& y, const bool table[2][2]) {
  if (&x == &y || x.nodes().size() < y.nodes().size() || !x.has_boundary()) return apply(x, y, table);
  const CancelShield shield;  // x's storage moves into the arena: stopping halfway would lose x
  const std::size_t a_nodes = x.nodes().size(), b_nodes = y.nodes().size();
  Arena arena;
  const TreeRef ra = arena.adopt(std::move(x));
  arena.nodes.reserve(a_nodes + 5 * b_nodes);
  arena.polygons.reserve(a_nodes + 5 * b_nodes);
  FragmentList fa = std::move(*arena.boundary);
  bsp::detail::FragmentBoxes boxes = std::move(arena.boundary_boxes);
  const TreeRef rb = arena.append(y);
  FragmentList fb = arena.boundary_of(y);
  MergeSteps steps(ra, rb, b_nodes, table);
  steps.boundary_sides_later(arena, std::move(fa), std::move(boxes), std::move(fb));
  return SolidAccess::deferred(std::make_unique<DeferredMerge>(std::move(arena), std::move(steps)));
}

// In place: the larger operand's storage is reused and nothing older than the operation is
// moved or renumbered (reclaim_added and finish_in_place, tree_arena.hpp).
// That pays when y is small beside x (a tool on a workpiece). When y has at least half as many
// nodes, most of the result's nodes are new, and placing them one by one after the merge costs
// more than the copying path's compaction, which can also wait for the tree's first use: x is
// copied (docs/benchmarks.md, "Session 15: deferred trees").
Solid apply_in_place(Solid&& x, const Solid& y, const bool table[2][2]) {
  if (&x == &y || x.nodes().size() < 2 * y.nodes().size()) return apply_adopting(std::move(x), y, table);
  const CancelShield shield;  // x's storage moves into the arena: stopping halfway would lose x
  // The boundary of x must be known before its storage moves into the arena.
  std::optional<bsp::detail::Fragments> extracted;
  if (!x.has_boundary()) extracted = bsp::detail::boundary_fragments(x);
  Arena arena;
  const TreeRef ra = arena.adopt(std::move(x));
  const bsp::detail::AddedStorage added{
      .first_plane = arena.planes.size(), .first_node = arena.nodes.size(), .all_fragments = extracted.has_value()};
  FragmentList fa;
  if (extracted) {
    const std::int32_t own = arena.planes.size();
    std::vector<std::int32_t> extra;
    auto map = [&](std::int32_t p) {  // indices beyond x's planes are opposites added by extraction
      if (p < own) return p;
      const auto k = std::size_t(p - own);
      if (extra.size() <= k) extra.resize(k + 1, -1);
      if (extra[k] < 0) extra[k] = arena.planes.add(extracted->planes[p], extracted->planes.auxiliary(p));
      return extra[k];
    };
    fa = std::move(extracted->fragments);
    fa.renumber_planes(map);
  } else {
    fa = std::move(*arena.boundary);
  }
  const TreeRef rb = arena.append(y);
  const FragmentList fb = arena.boundary_of(y);
  MergeSteps steps(ra, rb, y.nodes().size(), table);
  WrittenStorage written;
  steps.boundary(arena, std::move(fa), std::move(arena.boundary_boxes), fb, &written);
  const TreeRef r = steps.tree(arena, &written);
  return bsp::detail::finish_in_place(arena, bsp::detail::reclaim_added(arena, r, added, written));
}

constexpr bool kUnion[2][2] = {{false, true}, {true, true}};
constexpr bool kIntersection[2][2] = {{false, false}, {false, true}};
constexpr bool kDifference[2][2] = {{false, false}, {true, false}};

// True if op(a, b) takes the cell path (local/cell_merge.hpp): both carry their boundary (read
// without building a deferred tree) and together have enough fragments. With `in_place`, a
// workpiece whose tree is built keeps the in-place merge for a tool of under an eighth of its
// fragments: that merge costs what the tool touches, the cell path what both have (strokes).
bool by_cells(const Solid& a, const Solid& b, bool in_place) {
  const Solid::BoundaryView va = a.boundary_view(), vb = b.boundary_view();
  if (!va.fragments || !vb.fragments || va.fragments->empty() || vb.fragments->empty()) return false;
  const std::size_t na = va.fragments->size(), nb = vb.fragments->size();
  if (na + nb < bsp::detail::cell_merge_threshold()) return false;
  return !in_place || a.tree_deferred() || 8 * nb >= na;
}

// The operations work in grid units; the operands' common grid labels the result.
Solid operate(const Solid& a, const Solid& b, const bool table[2][2]) {
  const kernel::Grid grid = common_grid(a, b);
  if (by_cells(a, b, false))
    if (std::optional<Solid> r = bsp::detail::merge_by_cells(a, b, table))
      return SolidAccess::at_grid(std::move(*r), grid);
  return SolidAccess::at_grid(apply(a, b, table), grid);
}
Solid operate(Solid&& a, const Solid& b, const bool table[2][2]) {
  const kernel::Grid grid = common_grid(a, b);
  if (by_cells(a, b, true))
    if (std::optional<Solid> r = bsp::detail::merge_by_cells(a, b, table))
      return SolidAccess::at_grid(std::move(*r), grid);
  return SolidAccess::at_grid(apply_in_place(std::move(a), b, table), grid);
}

}  // namespace

Solid unite(const Solid& a, const Solid& b) { return operate(a, b, kUnion); }
Solid unite(Solid&& a, const Solid& b) { return operate(std::move(a), b, kUnion); }
Solid intersect(Solid&& a, const Solid& b) { return operate(std::move(a), b, kIntersection); }
Solid subtract(Solid&& a, const Solid& b) { return operate(std::move(a), b, kDifference); }
Solid intersect(const Solid& a, const Solid& b) { return operate(a, b, kIntersection); }
Solid subtract(const Solid& a, const Solid& b) { return operate(a, b, kDifference); }

Solid unite_all(std::vector<Solid> solids) {
  if (solids.empty()) return Solid();
  if (solids.size() > 2) {
    // The batch union pushes pieces down every operand's tree: deferred trees (transformed
    // meshes, results of set operations) are built first, side by side. Each solid builds its
    // own, as it would on first use.
    parallel_chunks(solids.size(), 8, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) (void)solids[i].root();
    });
  }
  // The common grid of the operands with planes (leaves take any: see Solid).
  const Solid* first = nullptr;
  for (const Solid& s : solids)
    if (!is_leaf(s.root())) {
      if (first && s.grid() != first->grid()) throw GridMismatch(first->grid(), s.grid());
      if (!first) first = &s;
    }
  const kernel::Grid grid = first ? first->grid() : solids.front().grid();
  if (solids.size() > 2) return SolidAccess::at_grid(bsp::detail::unite_by_boundaries(std::move(solids)), grid);
  if (solids.size() == 1) return SolidAccess::at_grid(std::move(solids.front()), grid);
  return SolidAccess::at_grid(unite(std::move(solids[0]), solids[1]), grid);
}

Solid complement(const Solid& a) {
  Arena arena;
  TreeRef r = arena.append(a);
  if (a.has_boundary()) {
    arena.boundary = arena.boundary_of(a);
    FragmentList& fragments = *arena.boundary;
    for (std::size_t i = 0; i < fragments.size(); ++i) fragments.set_flip(i, !fragments[i].flip);
  }
  bsp::detail::complement_in_place(arena, r);
  return SolidAccess::at_grid(bsp::detail::compact(arena, r), a.grid());
}

std::pair<Solid, Solid> partition(const Solid& solid, const kernel::Plane& plane) {
  Arena arena;
  TreeRef r = arena.append(solid);
  bsp::detail::fill_node_polygons(arena, r);
  const std::int32_t cut = arena.planes.add(plane);
  ConvexPolygon pp = kernel::world_polygon(arena.planes, cut);
  Merger m(arena);
  auto [neg, pos] = m.partition(r, std::move(pp), cut);
  // Each part is bounded by the cutting plane: add it as the root of each result.
  const auto id_neg = std::int32_t(arena.nodes.size());
  arena.nodes.push_back({cut, neg, kOut});
  arena.polygons.push_back(kernel::world_polygon(arena.planes, cut));
  const auto id_pos = std::int32_t(arena.nodes.size());
  arena.nodes.push_back({cut, kOut, pos});
  arena.polygons.push_back(kernel::world_polygon(arena.planes, cut));
  // The two trees share no nodes; compact each separately from a copy of the arena.
  Arena second = arena;
  return {SolidAccess::at_grid(bsp::detail::compact(arena, id_neg), solid.grid()),
          SolidAccess::at_grid(bsp::detail::compact(second, id_pos), solid.grid())};
}

}  // namespace sculpt
