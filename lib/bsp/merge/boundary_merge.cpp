#include "bsp/merge/boundary_merge.hpp"

#include "bsp/tree/boundary_clipper.hpp"
#include "bsp/merge/extent_pruning.hpp"

#include <algorithm>
#include <cmath>

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::CornerBox;
using kernel::Side;

namespace {

// Keeps a piece whose two sides get `in_behind` / `in_front` in the result: -1 drop, 0 as is,
// 1 reversed.
int verdict(bool in_behind, bool in_front) { return in_behind == in_front ? kDrop : (in_behind ? kKeep : kReverse); }

}  // namespace

void merge_boundaries(Arena& arena, TreeRef a, FragmentList a_faces, FragmentBoxes a_boxes_in,
                      TreeRef b, const FragmentList& b_faces, const bool op[2][2],
                      const ExtentSides* a_sides) {
  Clipper clip(arena);
  // B's fragments against A's tree. Where A has a face on the same plane region (A's status
  // differs across it), A's fragment stands for both.
  FragmentList from_b;
  const bool b_matters_inside_a_only = op[0][0] == op[0][1];  // out of A, op does not read B
  for (const BoundaryFragment& f : b_faces) {
    // On a plane with A on one closed side: no interior point of A, so out of A or on A's
    // boundary everywhere (extent_pruning.hpp): dropped like every such piece.
    if (a_sides && b_matters_inside_a_only && a_sides->of(f.polygon.support) != Side::Both) continue;
    clip.push(
        a, f,
        [&](bool front_in, bool back_in, bool on_plane) {
          return on_plane && front_in != back_in ? kDrop : verdict(op[back_in][1], op[front_in][0]);
        },
        [&](ConvexPolygon piece, int v) { from_b.push_back({std::move(piece), v == kKeep ? f.flip : !f.flip}); });
  }

  // A's fragments against B's tree, in place. Fragments apart from B's boundary box lie in B's
  // outer region (connected, no boundary of B): decided by one status without being moved.
  std::vector<FragmentBox>& a_boxes = a_boxes_in.each;
  std::vector<FragmentBox>& blocks = a_boxes_in.blocks;
  complete_boxes(a_faces, a_boxes_in);
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
  FragmentList pieces;
  std::vector<std::size_t> changed;  // fragments rewritten in place (below the shortened end)
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
        changed.push_back(i);
        continue;
      }
    }
    // Dropped: the last fragment takes its slot.
    if (i + 1 != a_faces.size()) {
      f = std::move(a_faces.back());
      a_boxes[i] = a_boxes.back();
      changed.push_back(i);
    }
    a_faces.pop_back();
    a_boxes.pop_back();
    shortest = std::min(shortest, a_faces.size());
  }
  for (FragmentList* more : {&pieces, &from_b})
    for (BoundaryFragment& p : *more) {
      a_boxes.push_back(fragment_box(p.polygon));
      a_faces.push_back(std::move(p));
    }
  // Block boxes: those with a changed fragment, and all from the block where the end moved.
  blocks.resize(FragmentBoxes::block_count(a_boxes.size()));
  for (const std::size_t i : changed)
    if (const std::size_t j = i / FragmentBoxes::kBlock; j < blocks.size()) a_boxes_in.update_block(j);
  for (std::size_t j = shortest / FragmentBoxes::kBlock; j < blocks.size(); ++j) a_boxes_in.update_block(j);
  arena.boundary_changed_from = shortest;  // what changed, for reclaim_added (in-place operations)
  arena.boundary_changed = std::move(changed);
  arena.boundary = std::move(a_faces);
  arena.boundary_boxes = std::move(a_boxes_in);
}

}  // namespace sculpt::bsp::detail
