#include "bsp/partition/pending_sides.hpp"

namespace sculpt::bsp::detail {

using kernel::Side;

void resolve_pending_sides(Arena& arena, std::vector<PartitionNode>& nodes, std::vector<PendingSide>& pending) {
  kernel::ConvexPolygon neg_part, pos_part;
  for (auto it = pending.rbegin(); it != pending.rend(); ++it) {
    PartitionNode& node = nodes[std::size_t(it->node)];
    TreeRef t = it->empty_side == 0 ? node.positive : node.negative;
    kernel::ConvexPolygon& poly = it->polygon;
    while (!is_leaf(t)) {
      const PartitionNode& below = nodes[std::size_t(t)];
      const Side s = kernel::split(arena.planes, poly, below.plane, arena.opposite(below.plane), neg_part, pos_part);
      if (s == Side::Both) poly = neg_part;
      t = s == Side::Positive ? below.positive : below.negative;
    }
    (it->empty_side == 0 ? node.negative : node.positive) = t;
  }
}

}  // namespace sculpt::bsp::detail
