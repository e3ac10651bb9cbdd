#include "bsp/partition/piece_pool.hpp"

namespace sculpt::bsp::detail {

using kernel::Side;

std::int32_t PiecePool::add(const kernel::ConvexPolygon& polygon, std::int32_t outward) {
  pieces.push_back({polygon, outward});
  boxes.push_back(kernel::corner_box(polygon));
  return std::int32_t(pieces.size() - 1);
}

bool split_cell(const kernel::PlaneTable& planes, PiecePool& pool, std::span<const std::int32_t> pieces,
                std::int32_t plane, std::int32_t opposite, bool auxiliary, CellSides& sides) {
  sides.negative.clear();
  sides.positive.clear();
  const kernel::Plane pv = planes[plane], po = planes[opposite];
  kernel::ConvexPolygon neg_part, pos_part;
  for (const std::int32_t id : pieces) {
    const std::int32_t s = pool.pieces[std::size_t(id)].polygon.support;
    if (s == plane || s == opposite || planes[s] == pv || planes[s] == po) {
      if (auxiliary) return false;
      continue;  // used up: the node's plane carries it
    }
    Side side = kernel::box_side(pool.boxes[std::size_t(id)], pv);
    if (side == Side::Both)
      side = kernel::split(planes, pool.pieces[std::size_t(id)].polygon, plane, opposite, neg_part, pos_part);
    switch (side) {
      case Side::Negative:
        sides.negative.push_back(id);
        break;
      case Side::Positive:
        sides.positive.push_back(id);
        break;
      case Side::Both: {
        const std::int32_t outward = pool.pieces[std::size_t(id)].outward;  // the pool may grow
        sides.negative.push_back(pool.add(neg_part, outward));
        sides.positive.push_back(pool.add(pos_part, outward));
        break;
      }
      case Side::On:
        break;  // cannot happen: a piece on the plane has that support
    }
  }
  return true;
}

}  // namespace sculpt::bsp::detail
