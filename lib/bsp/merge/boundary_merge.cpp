#include "bsp/merge/boundary_merge.hpp"

#include "bsp/tree/boundary_clipper.hpp"
#include "bsp/merge/extent_pruning.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "base/parallel.hpp"

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::CornerBox;
using kernel::Side;

namespace {

// Keeps a piece whose two sides get `in_behind` / `in_front` in the result: -1 drop, 0 as is,
// 1 reversed.
int fragment_verdict(bool in_behind, bool in_front) {
  return in_behind == in_front ? kDrop : (in_behind ? kKeep : kReverse);
}

// Fragments per parallel chunk, and the least work (fragments to push) worth the set-up of the
// parallel path. Both are constants, so the path taken and the chunks never depend on the thread
// count, and neither does the result.
constexpr std::size_t kChunk = 256;
constexpr std::size_t kParallelWork = 4096;

// Makes the opposite of every node plane of the trees at `roots`, so that pushing fragments down
// them only reads the arena (Arena::opposite then finds each one made) and can run on threads.
void make_opposites(Arena& arena, std::initializer_list<TreeRef> roots) {
  std::vector<TreeRef> stack(roots);
  while (!stack.empty()) {
    const TreeRef t = stack.back();
    stack.pop_back();
    if (is_leaf(t)) continue;
    const BspNode n = arena.nodes[std::size_t(t)];
    arena.opposite(n.plane);
    stack.push_back(n.negative);
    stack.push_back(n.positive);
  }
}

// Pushes fragments [begin, end) of a list (or of `order`) down a tree, one Clipper per chunk;
// each chunk's pieces are kept apart and joined in chunk order, so the output is the serial one.
template <typename PushOne>
void push_in_chunks(Arena& arena, std::size_t n, bool parallel, PushOne&& push_one) {
  if (!parallel) {
    Clipper clip(arena);
    push_one(clip, std::size_t(0), n);
    return;
  }
  parallel_chunks(n, kChunk, [&](std::size_t begin, std::size_t end) {
    Clipper clip(arena);
    push_one(clip, begin, end);
  });
}

}  // namespace

void merge_boundaries(Arena& arena, TreeRef a, FragmentList a_faces, FragmentBoxes a_boxes_in, TreeRef b,
                      const FragmentList& b_faces, const bool op[2][2], const ExtentSides* a_sides,
                      WrittenStorage* written) {
  Clipper clip(arena);
  // B's fragments against A's tree, in chunks (see push_in_chunks). Where A has a face on the
  // same plane region (A's status differs across it), A's fragment stands for both.
  const bool b_matters_inside_a_only = op[0][0] == op[0][1];  // out of A, op does not read B
  auto push_b = [&](Clipper& c, std::size_t begin, std::size_t end, FragmentList& out) {
    for (std::size_t i = begin; i < end; ++i) {
      const FragmentRef f = b_faces[i];
      // On a plane with A on one closed side: no interior point of A, so out of A or on A's
      // boundary everywhere (extent_pruning.hpp): dropped like every such piece.
      if (a_sides && b_matters_inside_a_only && a_sides->of(f.polygon.support) != Side::Both) continue;
      c.push(
          a, f,
          [&](bool front_in, bool back_in, bool on_plane) {
            return on_plane && front_in != back_in ? kDrop : fragment_verdict(op[back_in][1], op[front_in][0]);
          },
          [&](ConvexPolygon piece, int v) {
            out.push_back({std::move(piece), v == kKeep ? f.flip : !f.flip});
          });
    }
  };

  // A's fragments against B's tree, in place. Fragments apart from B's boundary box lie in B's
  // outer region (connected, no boundary of B): decided by one status without being moved.
  std::vector<FragmentBox>& a_boxes = a_boxes_in.each;
  std::vector<FragmentBox>& blocks = a_boxes_in.blocks;
  complete_boxes(a_faces, a_boxes_in);
  const bool uniform = is_leaf(b) || b_faces.empty();
  const CornerBox b_box = uniform ? CornerBox{} : bounds(b_faces);
  const bool far_in = is_leaf(b) ? b == kIn : (b_box.valid || uniform ? clip.far_status(b) : false);
  const int far_verdict = fragment_verdict(op[1][far_in], op[0][far_in]);
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
  // Each fragment's verdict: far_verdict, or kUndecided to push it down B's tree.
  auto verdict_of = [&](std::size_t i) {
    return uniform || (b_box.valid && a_boxes[i].valid && !near(a_boxes[i])) ? far_verdict : kUndecided;
  };
  // Pushing the undecided ones reads only the arena, so it runs first, in chunks of `todo`. The
  // pieces of todo[k] end at pieces_end[k] in its chunk's list (and start where those of
  // todo[k - 1] end, or at 0 for a chunk's first), in the order they were emitted.
  const std::size_t work = todo.size() + b_faces.size();
  const bool parallel = work >= kParallelWork && arena.nodes.size() <= 16 * work;
  if (parallel) make_opposites(arena, {a, b});
  const std::size_t chunk = parallel ? kChunk : std::max<std::size_t>(todo.size(), 1);
  std::vector<FragmentList> chunk_pieces((todo.size() + chunk - 1) / chunk + 1);
  std::vector<std::uint32_t> pieces_end(todo.size());
  auto push_a = [&](Clipper& c, std::size_t begin, std::size_t end) {
    FragmentList& out = chunk_pieces[begin / chunk];
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t i = todo[k];
      if (verdict_of(i) == kUndecided) {
        const FragmentRef f = a_faces[i];
        c.push(
            b, f, [&](bool front_in, bool back_in, bool) { return fragment_verdict(op[1][back_in], op[0][front_in]); },
            [&](ConvexPolygon piece, int w) {
              out.push_back({std::move(piece), w == kKeep ? f.flip : !f.flip});
            });
      }
      pieces_end[k] = std::uint32_t(out.size());
    }
  };
  std::vector<FragmentList> b_chunk_pieces(parallel ? (b_faces.size() + kChunk - 1) / kChunk : 1);
  auto run_b = [&] {
    push_in_chunks(arena, b_faces.size(), parallel, [&](Clipper& c, std::size_t begin, std::size_t end) {
      push_b(c, begin, end, b_chunk_pieces[parallel ? begin / kChunk : 0]);
    });
  };
  auto run_a = [&] { push_in_chunks(arena, todo.size(), parallel, push_a); };
  if (parallel) {
    parallel_invoke(run_b, run_a);
  } else {
    run_b();
    run_a();
  }
  FragmentList from_b = std::move(b_chunk_pieces[0]);
  for (std::size_t j = 1; j < b_chunk_pieces.size(); ++j) from_b.append(std::move(b_chunk_pieces[j]));

  FragmentList pieces;
  std::vector<std::size_t> changed;  // fragments rewritten in place (below the shortened end)
  std::size_t shortest = a_faces.size();
  // Downwards, so that fragments moved into a freed slot (from the end) are already decided.
  for (std::size_t k = 0; k < todo.size(); ++k) {
    const std::size_t i = todo[k];
    const int v = verdict_of(i);
    if (v == 0) continue;
    if (v == 1) {
      a_faces.set_flip(i, !a_faces[i].flip);
      continue;
    }
    if (v == kUndecided) {
      const FragmentList& made = chunk_pieces[k / chunk];
      const std::size_t first = k % chunk == 0 ? 0 : pieces_end[k - 1], last = pieces_end[k];
      if (last > first) {  // the last piece takes the fragment's slot, the others are appended
        for (std::size_t j = first; j + 1 < last; ++j) {
          const FragmentRef g = made[j];
          pieces.push_back(g.polygon, g.flip);
        }
        const FragmentRef g = made[last - 1];
        a_faces.replace(i, g.polygon, g.flip);
        a_boxes[i] = fragment_box(g.polygon);
        changed.push_back(i);
        continue;
      }
    }
    // Dropped: the last fragment takes its slot.
    if (i + 1 != a_faces.size()) {
      const FragmentRef g = a_faces.back();
      a_faces.replace(i, g.polygon, g.flip);
      a_boxes[i] = a_boxes.back();
      changed.push_back(i);
    }
    a_faces.pop_back();
    a_boxes.pop_back();
    shortest = std::min(shortest, a_faces.size());
  }
  for (FragmentList* more : {&pieces, &from_b}) {
    for (const FragmentRef p : *more) a_boxes.push_back(fragment_box(p.polygon));
    a_faces.append(std::move(*more));
  }
  // Room left by dropped and replaced fragments is given back when it is a quarter of the list.
  a_faces.pack_if_sparse();
  // Block boxes: those with a changed fragment, and all from the block where the end moved.
  blocks.resize(FragmentBoxes::block_count(a_boxes.size()));
  for (const std::size_t i : changed)
    if (const std::size_t j = i / FragmentBoxes::kBlock; j < blocks.size()) a_boxes_in.update_block(j);
  for (std::size_t j = shortest / FragmentBoxes::kBlock; j < blocks.size(); ++j) a_boxes_in.update_block(j);
  if (written) {  // what changed, for reclaim_added
    written->boundary_changed_from = shortest;
    written->boundary_changed = std::move(changed);
  }
  arena.boundary = std::move(a_faces);
  arena.boundary_boxes = std::move(a_boxes_in);
}

}  // namespace sculpt::bsp::detail
