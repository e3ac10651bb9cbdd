#include "bsp/boundary_merge.hpp"

#include <algorithm>
#include <cmath>

namespace sculpt::detail {

using kernel::ConvexPolygon;
using kernel::CornerBox;
using kernel::Side;

namespace {

// Which sides of a piece lying on a node's plane the traversal still has to find out.
enum class Mode : std::uint8_t {
  Both,   // the piece is inside the cells it passes: one leaf gives both sides
  Back,   // on a node's plane: following the child behind it, then `then_front`
  Front,  // on a node's plane: following the child in front of it; `back_in` is known
};

// A piece's fate in the result: dropped, kept as it is, kept reversed; or, for a piece that was
// split, Mixed (its parts were decided separately).
constexpr int kUndecided = -2, kDrop = -1, kKeep = 0, kReverse = 1, kMixed = 2, kPending = 3;

class Clipper {
 public:
  explicit Clipper(Arena& arena) : a_(arena) {}

  // Pushes fragment `f` down the subtree `t`. Each piece that reaches its cell(s) gets
  // fate(front_in, back_in, on_plane): the tree's status in front of the piece (the side its
  // outward normal points to) and behind it; on_plane: the piece lies on a plane of the tree.
  // Kept pieces go to emit(polygon, fate). Where both parts of a split get the same fate, their
  // parent is emitted instead (the split was needless: fewer, larger fragments).
  template <typename Fate, typename Emit>
  void push(TreeRef t, const BoundaryFragment& f, Fate&& fate, Emit&& emit) {
    stack_.clear();
    splits_.clear();
    stack_.push_back({t, f.polygon, kernel::corner_box(f.polygon), Mode::Both, false, kOut, -1, 0});
    while (!stack_.empty()) {
      Item& top = stack_.back();
      if (is_leaf(top.at)) {
        const bool in = top.at == kIn;
        if (top.mode == Mode::Back) {  // behind known: now the side in front
          top.back_in = in;
          top.mode = Mode::Front;
          top.at = top.then_front;
          continue;
        }
        const int v = fate(in, top.mode == Mode::Both ? in : top.back_in, top.mode != Mode::Both);
        ConvexPolygon poly = std::move(top.polygon);
        const int parent = top.parent, which = top.which;
        stack_.pop_back();
        report(parent, which, v, std::move(poly), emit);
        continue;
      }
      const BspNode& n = a_.nodes[std::size_t(top.at)];
      const Side quick = kernel::box_side(top.box, a_.planes[n.plane]);
      if (quick == Side::Negative || quick == Side::Positive) {
        top.at = quick == Side::Negative ? n.negative : n.positive;
        continue;
      }
      kernel::PolygonSplit s = kernel::split(a_.planes, top.polygon, n.plane, a_.opposite(n.plane));
      switch (s.side) {
        case Side::Negative: top.at = n.negative; break;
        case Side::Positive: top.at = n.positive; break;
        case Side::Both: {
          const auto id = int(splits_.size());
          splits_.push_back({top.polygon, top.parent, top.which, {kPending, kPending}, {}});
          const CornerBox nb = kernel::corner_box(s.negative), pb = kernel::corner_box(s.positive);
          Item second{n.positive, std::move(s.positive), pb, top.mode, top.back_in, top.then_front, id, 1};
          top.at = n.negative;
          top.polygon = std::move(s.negative);
          top.box = nb;
          top.parent = id;
          top.which = 0;
          stack_.push_back(std::move(second));
          break;
        }
        case Side::On: {
          // The outward normal points to the node's positive side when the support plane has the
          // node plane's orientation and the fragment is not flipped, or neither.
          const bool same = a_.planes[top.polygon.support] == a_.planes[n.plane];
          const bool front_positive = same != f.flip;
          const TreeRef front = front_positive ? n.positive : n.negative;
          const TreeRef back = front_positive ? n.negative : n.positive;
          if (top.mode == Mode::Both) {
            top.mode = Mode::Back;
            top.then_front = front;
            top.at = back;
          } else {  // cannot happen (a descendant on the same plane cuts no cell); stay consistent
            top.at = top.mode == Mode::Back ? back : front;
          }
          break;
        }
      }
    }
  }

  // Status of the tree in the region around the world box boundary (where `t` has no boundary):
  // the leaf reached by a piece of the world box face x = max.
  bool far_status(TreeRef t) {
    ConvexPolygon poly = kernel::world_polygon(a_.planes, 0);
    while (!is_leaf(t)) {
      const BspNode& n = a_.nodes[std::size_t(t)];
      kernel::PolygonSplit s = kernel::split(a_.planes, poly, n.plane, a_.opposite(n.plane));
      if (s.side == Side::Both) {
        poly = std::move(s.negative);
        t = n.negative;
      } else {
        t = s.side == Side::Positive ? n.positive : n.negative;  // On is impossible: no boundary there
      }
    }
    return t == kIn;
  }

 private:
  struct Item {
    TreeRef at;
    ConvexPolygon polygon;
    CornerBox box;
    Mode mode;
    bool back_in;        // Mode::Front: the status behind the piece
    TreeRef then_front;  // Mode::Back: the child in front of the piece
    int parent, which;   // the split that made this piece (-1: none) and which part it is
  };
  struct Split {
    ConvexPolygon polygon;  // before the split
    int parent, which;
    int fate[2];            // of the two parts (kPending until decided)
    ConvexPolygon part[2];  // a part kept whole, until its sibling is decided
  };

  // Records the fate of part `which` of split `parent` and resolves splits whose parts are
  // both decided, upwards (explicit loop).
  template <typename Emit>
  void report(int parent, int which, int fate, ConvexPolygon poly, Emit& emit) {
    while (true) {
      if (parent < 0) {
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
  std::vector<Item> stack_;
  std::vector<Split> splits_;
};

// The box around a set of fragments (corner boxes), or invalid if a fragment touches the world
// box (the solid is unbounded there) or has no usable corner approximation.
CornerBox bounds(const std::vector<BoundaryFragment>& faces) {
  CornerBox box;
  box.valid = !faces.empty();
  for (int k = 0; k < 3; ++k) box.lo[k] = 1e300, box.hi[k] = -1e300;
  for (const BoundaryFragment& f : faces) {
    const CornerBox b = kernel::corner_box(f.polygon);
    constexpr std::int32_t w = kernel::kWorldPlanes;  // the world box planes come first
    bool world = f.polygon.support < w;
    for (const auto& c : f.polygon.corners) world |= c.edge < w || c.p < w || c.q < w;
    if (!b.valid || world) return {};
    for (int k = 0; k < 3; ++k) box.lo[k] = std::min(box.lo[k], b.lo[k]), box.hi[k] = std::max(box.hi[k], b.hi[k]);
  }
  return box;
}

// Keeps a piece whose two sides get `in_behind` / `in_front` in the result: -1 drop, 0 as is,
// 1 reversed.
int verdict(bool in_behind, bool in_front) { return in_behind == in_front ? kDrop : (in_behind ? kKeep : kReverse); }

}  // namespace

void merge_boundaries(Arena& arena, TreeRef a, std::vector<BoundaryFragment> a_faces, FragmentBoxes a_boxes_in,
                      TreeRef b, const std::vector<BoundaryFragment>& b_faces, const bool op[2][2]) {
  Clipper clip(arena);
  // B's fragments against A's tree. Where A has a face on the same plane region (A's status
  // differs across it), A's fragment stands for both.
  std::vector<BoundaryFragment> from_b;
  for (const BoundaryFragment& f : b_faces)
    clip.push(
        a, f,
        [&](bool front_in, bool back_in, bool on_plane) {
          return on_plane && front_in != back_in ? kDrop : verdict(op[back_in][1], op[front_in][0]);
        },
        [&](ConvexPolygon piece, int v) { from_b.push_back({std::move(piece), v == kKeep ? f.flip : !f.flip}); });

  // A's fragments against B's tree, in place. Fragments apart from B's boundary box lie in B's
  // outer region (connected, no boundary of B): decided by one status without being moved.
  std::vector<FragmentBox>& a_boxes = a_boxes_in.each;
  std::vector<FragmentBox>& blocks = a_boxes_in.blocks;
  if (a_boxes.size() != a_faces.size()) {
    a_boxes.clear();
    a_boxes.reserve(a_faces.size());
    for (const BoundaryFragment& f : a_faces) a_boxes.push_back(fragment_box(f.polygon));
    blocks.clear();
  }
  if (blocks.size() != FragmentBoxes::block_count(a_boxes.size())) {
    blocks.assign(FragmentBoxes::block_count(a_boxes.size()), FragmentBox{});
    for (std::size_t j = 0; j < blocks.size(); ++j) a_boxes_in.update_block(j);
  }
  const bool uniform = is_leaf(b) || b_faces.empty();
  const CornerBox b_box = uniform ? CornerBox{} : bounds(b_faces);
  const bool far_in = is_leaf(b) ? b == kIn : (b_box.valid || uniform ? clip.far_status(b) : false);
  const int far_verdict = verdict(op[1][far_in], op[0][far_in]);
  // Strictly apart, with a margin for the rounding of b_box to float (relative 2^-23).
  float below[3], above[3];
  for (int k = 0; k < 3; ++k) {
    const float lo = float(b_box.lo[k]), hi = float(b_box.hi[k]);
    const float m = 1e-6f * (std::fabs(lo) + std::fabs(hi)) + 1e-30f;
    below[k] = lo - m;
    above[k] = hi + m;
  }
  auto near = [&](const FragmentBox& x) {  // false: known to be apart
    bool apart = false;                    // no early exit: a branch-free test over a long array
    for (int k = 0; k < 3; ++k) apart |= (x.hi[k] < below[k]) | (x.lo[k] > above[k]);
    return !(apart & x.valid);
  };
  // The fragments to push down B's tree, downwards (those apart from B keep the far verdict).
  std::vector<std::size_t> todo;
  if (!uniform && b_box.valid && far_verdict == kKeep) {
    constexpr std::size_t w = FragmentBoxes::kBlock;
    for (std::size_t j = blocks.size(); j-- > 0;) {
      if (!near(blocks[j])) continue;  // every fragment of the block is apart
      for (std::size_t i = std::min(a_faces.size(), (j + 1) * w); i-- > j * w;)
        if (near(a_boxes[i])) todo.push_back(i);
    }
  } else {
    todo.resize(a_faces.size());
    for (std::size_t i = 0; i < todo.size(); ++i) todo[i] = todo.size() - 1 - i;
  }
  std::vector<BoundaryFragment> pieces;
  std::vector<std::size_t> changed;  // blocks whose boxes change (below the shortened end)
  std::size_t shortest = a_faces.size();
  // Downwards, so that fragments moved into a freed slot (from the end) are already decided.
  for (const std::size_t i : todo) {
    int v = kUndecided;
    if (uniform || (b_box.valid && a_boxes[i].valid && !near(a_boxes[i]))) v = far_verdict;
    if (v == 0) continue;
    BoundaryFragment& f = a_faces[i];
    if (v == 1) {
      f.flip = !f.flip;
      continue;
    }
    if (v == kUndecided) {
      const std::size_t before = pieces.size();
      clip.push(
          b, f, [&](bool front_in, bool back_in, bool) { return verdict(op[1][back_in], op[0][front_in]); },
          [&](ConvexPolygon piece, int w) { pieces.push_back({std::move(piece), w == kKeep ? f.flip : !f.flip}); });
      if (pieces.size() > before) {  // the first piece takes the fragment's slot
        f = std::move(pieces.back());
        pieces.pop_back();
        a_boxes[i] = fragment_box(f.polygon);
        changed.push_back(i / FragmentBoxes::kBlock);
        continue;
      }
    }
    // Dropped: the last fragment takes its slot.
    if (i + 1 != a_faces.size()) {
      f = std::move(a_faces.back());
      a_boxes[i] = a_boxes.back();
      changed.push_back(i / FragmentBoxes::kBlock);
    }
    a_faces.pop_back();
    a_boxes.pop_back();
    shortest = std::min(shortest, a_faces.size());
  }
  for (std::vector<BoundaryFragment>* more : {&pieces, &from_b})
    for (BoundaryFragment& p : *more) {
      a_boxes.push_back(fragment_box(p.polygon));
      a_faces.push_back(std::move(p));
    }
  // Block boxes: those with a changed fragment, and all from the block where the end moved.
  blocks.resize(FragmentBoxes::block_count(a_boxes.size()));
  for (const std::size_t j : changed)
    if (j < blocks.size()) a_boxes_in.update_block(j);
  for (std::size_t j = shortest / FragmentBoxes::kBlock; j < blocks.size(); ++j) a_boxes_in.update_block(j);
  arena.boundary = std::move(a_faces);
  arena.boundary_boxes = std::move(a_boxes_in);
}

}  // namespace sculpt::detail
