#pragma once
/// \file boundary_clipper.hpp
/// Internal: pushing boundary fragments down a tree (Thibault & Naylor 1987; Naylor et al. 1990
/// sec. 5), shared by the two-operand boundary merge and the union of many solids. A piece inside
/// a cell gets that cell's status on both of its sides; a piece on a node's plane is pushed down
/// the child behind it, then down the child in front of it. Every decision is an exact predicate.

#include <algorithm>
#include <vector>

#include "base/cancel.hpp"
#include "bsp/tree/tree_arena.hpp"

namespace sculpt::bsp::detail {

// Which sides of a piece lying on a node's plane the traversal still has to find out.
enum class ClipMode : std::uint8_t {
  Both,   // the piece is inside the cells it passes: one leaf gives both sides
  Back,   // on a node's plane: following the child behind it, then `then_front`
  Front,  // on a node's plane: following the child in front of it; `back_in` is known
};

// A piece's fate in the result: dropped, kept as it is, kept reversed; or, for a piece that was
// split, Mixed (its parts were decided separately).
constexpr int kUndecided = -2, kDrop = -1, kKeep = 0, kReverse = 1, kMixed = 2, kPending = 3;

class Clipper {
 public:
  explicit Clipper(Arena& arena) : a_(arena), nodes_(&arena.nodes) {}
  /// The nodes the trees pushed down are read from: the arena's (the default), or a task's own
  /// on the arena's planes (the cell merge's local trees). The list must outlive the pushes.
  void read_nodes(const std::vector<BspNode>& nodes) { nodes_ = &nodes; }

  // Pushes fragment `f` down the subtree `t`. Each piece that reaches its cell(s) gets
  // fate(front_in, back_in, on_plane): the tree's status in front of the piece (the side its
  // outward normal points to) and behind it; on_plane: the piece lies on a plane of the tree.
  // Kept pieces go to emit(polygon, fate). Where both parts of a split get the same fate, their
  // parent is emitted instead (the split was needless: fewer, larger fragments).
  // Returns the fate of `f` as a whole: kKeep, kReverse or kDrop when every piece had that fate
  // (then `f` itself was emitted, or nothing), kMixed when its parts differ.
  template <typename Fate, typename Emit>
  int push(TreeRef t, const FragmentRef& f, Fate&& fate, Emit&& emit) {
    whole_ = kPending;
    stack_.clear();
    splits_.clear();
    stack_.emplace_back(t, kernel::ConvexPolygon::copy_of(f.polygon), kernel::corner_box(f.polygon), ClipMode::Both,
                        false, kOut, -1, 0);
    while (!stack_.empty()) {
      poll_.tick();
      Item& top = stack_.back();
      if (is_leaf(top.at)) {
        const bool in = top.at == kIn;
        if (top.mode == ClipMode::Back) {  // behind known: now the side in front
          top.back_in = in;
          top.mode = ClipMode::Front;
          top.at = top.then_front;
          continue;
        }
        const int v = fate(in, top.mode == ClipMode::Both ? in : top.back_in, top.mode != ClipMode::Both);
        kernel::ConvexPolygon poly = std::move(top.polygon);
        const int parent = top.parent, which = top.which;
        stack_.pop_back();
        report(parent, which, v, std::move(poly), emit);
        continue;
      }
      const BspNode& n = (*nodes_)[std::size_t(top.at)];
      const kernel::Side quick = kernel::box_side(top.box, a_.planes[n.plane]);
      if (quick == kernel::Side::Negative || quick == kernel::Side::Positive) {
        top.at = quick == kernel::Side::Negative ? n.negative : n.positive;
        continue;
      }
      kernel::PolygonSplit s = kernel::split(a_.planes, top.polygon, n.plane, a_.opposite(n.plane));
      switch (s.side) {
        case kernel::Side::Negative: top.at = n.negative; break;
        case kernel::Side::Positive: top.at = n.positive; break;
        case kernel::Side::Both: {
          const auto id = int(splits_.size());
          splits_.emplace_back(top.polygon, top.parent, top.which);
          const kernel::CornerBox nb = kernel::corner_box(s.negative), pb = kernel::corner_box(s.positive);
          const ClipMode mode = top.mode;
          const bool back_in = top.back_in;
          const TreeRef then_front = top.then_front;
          top.at = n.negative;
          top.polygon = std::move(s.negative);
          top.box = nb;
          top.parent = id;
          top.which = 0;
          stack_.emplace_back(n.positive, std::move(s.positive), pb, mode, back_in, then_front, id, 1);  // top dangles
          break;
        }
        case kernel::Side::On: {
          // The outward normal points to the node's positive side when the support plane has the
          // node plane's orientation and the fragment is not flipped, or neither.
          const bool same = a_.planes[top.polygon.support] == a_.planes[n.plane];
          const bool front_positive = same != f.flip;
          const TreeRef front = front_positive ? n.positive : n.negative;
          const TreeRef back = front_positive ? n.negative : n.positive;
          if (top.mode == ClipMode::Both) {
            top.mode = ClipMode::Back;
            top.then_front = front;
            top.at = back;
          } else {  // cannot happen (a descendant on the same plane cuts no cell); stay consistent
            top.at = top.mode == ClipMode::Back ? back : front;
          }
          break;
        }
      }
    }
    return whole_;
  }

  // Status of the tree in the region around the world box boundary (where `t` has no boundary):
  // the leaf reached by a piece of the world box face x = max.
  bool far_status(TreeRef t) {
    kernel::ConvexPolygon poly = kernel::world_polygon(a_.planes, 0);
    while (!is_leaf(t)) {
      const BspNode& n = (*nodes_)[std::size_t(t)];
      kernel::PolygonSplit s = kernel::split(a_.planes, poly, n.plane, a_.opposite(n.plane));
      if (s.side == kernel::Side::Both) {
        poly = std::move(s.negative);
        t = n.negative;
      } else {
        t = s.side == kernel::Side::Positive ? n.positive : n.negative;  // On is impossible: no boundary there
      }
    }
    return t == kIn;
  }

 private:
  struct Item {
    // Constructed in place: braces would zero the whole item (the polygon's inline storage) first.
    Item(TreeRef at_, kernel::ConvexPolygon&& polygon_, const kernel::CornerBox& box_, ClipMode mode_, bool back_in_,
         TreeRef then_front_, int parent_, int which_)
        : at(at_), polygon(std::move(polygon_)), box(box_), mode(mode_), back_in(back_in_), then_front(then_front_),
          parent(parent_), which(which_) {}
    TreeRef at;
    kernel::ConvexPolygon polygon;
    kernel::CornerBox box;
    ClipMode mode;
    bool back_in;        // ClipMode::Front: the status behind the piece
    TreeRef then_front;  // ClipMode::Back: the child in front of the piece
    int parent, which;   // the split that made this piece (-1: none) and which part it is
  };
  struct Split {
    // A constructor of its own: value-initializing the parts (`{}`) would zero their inline
    // corner storage first, 2 x 272 bytes per split (a tenth of the boundary merge).
    Split(const kernel::ConvexPolygon& whole, int parent_split, int part_index)
        : polygon(whole), parent(parent_split), which(part_index) {}
    kernel::ConvexPolygon polygon;  // before the split
    int parent, which;
    int fate[2] = {kPending, kPending};  // of the two parts (kPending until decided)
    kernel::ConvexPolygon part[2];       // a part kept whole, until its sibling is decided
  };

  // Records the fate of part `which` of split `parent` and resolves splits whose parts are
  // both decided, upwards (explicit loop).
  template <typename Emit>
  void report(int parent, int which, int fate, kernel::ConvexPolygon poly, Emit& emit) {
    while (true) {
      if (parent < 0) {
        whole_ = fate;
        if (fate == kKeep || fate == kReverse) emit(std::move(poly), fate);
        return;
      }
      Split& s = splits_[std::size_t(parent)];
      s.fate[which] = fate;
      if (fate == kKeep || fate == kReverse) s.part[which] = std::move(poly);
      if (s.fate[1 - which] == kPending) return;
      which = s.which;
      parent = s.parent;
      if (s.fate[0] == s.fate[1] && s.fate[0] != kMixed) {
        poly = std::move(s.polygon);  // both parts alike: the whole polygon goes up
        continue;
      }
      for (int k = 0; k < 2; ++k)
        if (s.fate[k] == kKeep || s.fate[k] == kReverse) emit(std::move(s.part[k]), s.fate[k]);
      fate = kMixed;
    }
  }

  Arena& a_;
  const std::vector<BspNode>* nodes_;
  int whole_ = kPending;  // the fate of the fragment being pushed as a whole
  CancelPoll poll_;       // Ctrl-C (base/cancel.hpp): a boundary merge may run for minutes
  std::vector<Item> stack_;
  std::vector<Split> splits_;
};

// The box around a set of fragments (corner boxes), or invalid if a fragment touches the world
// box (the solid is unbounded there) or has no usable corner approximation.
inline kernel::CornerBox bounds(const FragmentList& faces) {
  kernel::CornerBox box;
  box.valid = !faces.empty();
  for (int k = 0; k < 3; ++k) box.lo[k] = 1e300, box.hi[k] = -1e300;
  for (const FragmentRef f : faces) {
    const kernel::CornerBox b = kernel::corner_box(f.polygon);
    constexpr std::int32_t w = kernel::kWorldPlanes;  // the world box planes come first
    bool world = f.polygon.support < w;
    for (const auto& c : f.polygon.corners) world |= c.edge < w || c.p < w || c.q < w;
    if (!b.valid || world) return {};
    for (int k = 0; k < 3; ++k) box.lo[k] = std::min(box.lo[k], b.lo[k]), box.hi[k] = std::max(box.hi[k], b.hi[k]);
  }
  return box;
}

}  // namespace sculpt::bsp::detail
