#include "bsp/merge/batch_union.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

#include "bsp/tree/autopartition.hpp"
#include "bsp/tree/boundary_clipper.hpp"

namespace sculpt::bsp::detail {

using kernel::CornerBox;

namespace {

struct UnionOperand {
  TreeRef root;
  FragmentList faces;
  CornerBox box;  // around its boundary; invalid: unbounded or unknown
  bool far_in;    // status outside the box (a connected region without boundary)
  // Whether it can matter to every other operand's boundary: its box is unknown, or it is in
  // outside its box (so it covers whatever lies there).
  [[nodiscard]] bool everywhere() const { return !box.valid || far_in; }
};

bool may_overlap(const CornerBox& a, const CornerBox& b) {
  if (!a.valid || !b.valid) return true;
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

}  // namespace

Solid unite_by_boundaries(std::vector<Solid> solids) {
  Arena arena;
  std::vector<UnionOperand> ops;
  std::size_t last = 0;  // an operand's index in `solids` (used when it is the only one)
  for (std::size_t i = 0; i < solids.size(); ++i) {
    const Solid& s = solids[i];
    if (is_leaf(s.root())) {
      if (s.root() == kIn) return Solid::leaf(true);
      continue;
    }
    const TreeRef r = arena.append(s);
    ops.push_back({r, arena.boundary_of(s), {}, false});
    last = i;
  }
  if (ops.empty()) return Solid();
  if (ops.size() == 1) return std::move(solids[last]);

  Clipper clip(arena);
  for (UnionOperand& o : ops) {
    o.box = bounds(o.faces);
    o.far_in = clip.far_status(o.root);
  }
  // Pairs of operands whose boxes meet (closed boxes: touching operands share boundary).
  std::vector<std::vector<std::size_t>> near(ops.size());
  std::vector<std::size_t> order(ops.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  auto lo = [&](std::size_t i) { return ops[i].everywhere() ? -1e300 : ops[i].box.lo[0]; };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  for (std::size_t x = 0; x < order.size(); ++x) {
    const std::size_t i = order[x];
    const double hi = ops[i].everywhere() ? 1e300 : ops[i].box.hi[0];
    for (std::size_t y = x + 1; y < order.size() && lo(order[y]) <= hi; ++y) {
      const std::size_t j = order[y];
      if (ops[i].everywhere() || ops[j].everywhere() || may_overlap(ops[i].box, ops[j].box))
        near[i].push_back(j), near[j].push_back(i);
    }
  }
  // Each operand's boundary outside all the others.
  FragmentList result, kept;
  for (std::size_t i = 0; i < ops.size(); ++i) {
    FragmentList& faces = ops[i].faces;
    std::sort(near[i].begin(), near[i].end());
    for (const std::size_t j : near[i]) {
      const UnionOperand& o = ops[j];
      const bool first = i < j;  // on a shared plane region with the same orientation: i keeps it
      kept.clear();
      for (const FragmentRef f : faces) {
        if (o.box.valid && !may_overlap(kernel::corner_box(f.polygon), o.box)) {  // in o's far region
          if (!o.far_in) kept.push_back(f.polygon, f.flip);
          continue;
        }
        clip.push(
            o.root, f,
            [&](bool front_in, bool back_in, bool on_plane) {
              // In front of the piece o is in: the union's interior. On o's plane with o in behind
              // (the same orientation): o's own piece stands for it when o comes first.
              return front_in || (!first && on_plane && back_in) ? kDrop : kKeep;
            },
            [&](kernel::ConvexPolygon piece, int) { kept.push_back({std::move(piece), f.flip}); });
      }
      std::swap(faces, kept);
      if (faces.empty()) break;
    }
    result.append(std::move(faces));
  }
  if (result.empty()) return Solid::leaf(true);  // operands with boundaries whose union has none
  return autopartition(arena, std::move(result));
}

}  // namespace sculpt::bsp::detail
