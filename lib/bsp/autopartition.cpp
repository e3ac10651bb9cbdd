#include "bsp/autopartition.hpp"

#include <cmath>
#include <cstdlib>
#include <utility>

#include "bsp/tree_builder.hpp"

namespace sculpt::detail {

using kernel::ConvexPolygon;
using kernel::CornerBox;
using kernel::Side;

namespace {

// A fragment's piece in the cell being partitioned, with its outward plane (its box is kept
// apart, in an array of its own: scoring reads boxes far more often than polygons).
struct Piece {
  ConvexPolygon polygon;
  std::int32_t outward;  // support, or its opposite for a flipped fragment
};

struct Node {
  std::int32_t plane;
  TreeRef negative = kOut, positive = kOut;
};

// Side of a piece with respect to a plane: the box first, the corners when it is undecided.
Side side_of(const kernel::PlaneTable& planes, const Piece& p, const CornerBox& box, std::int32_t plane) {
  const Side quick = kernel::box_side(box, planes[plane]);
  return quick != Side::Both ? quick : kernel::classify(planes, p.polygon, plane);
}

}  // namespace

Solid autopartition(Arena& arena, std::vector<BoundaryFragment> fragments, const AutopartitionOptions& options) {
  if (fragments.empty()) return Solid();
  const kernel::PlaneTable& planes = arena.planes;
  // Pieces live in one pool (split parts are appended); frames hold indices into it.
  std::vector<Piece> pool;
  std::vector<CornerBox> boxes;
  pool.reserve(2 * fragments.size());
  boxes.reserve(2 * fragments.size());
  for (const BoundaryFragment& f : fragments) {
    const std::int32_t s = f.polygon.support;
    pool.push_back({f.polygon, f.flip ? arena.opposite(s) : s});
    boxes.push_back(kernel::corner_box(f.polygon));
  }

  struct Frame {
    std::vector<std::int32_t> pieces;
    std::int32_t parent;  // -1: the root
    int side;
  };
  std::vector<Node> nodes;
  std::vector<Frame> stack;
  {
    std::vector<std::int32_t> all(pool.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = std::int32_t(i);
    stack.push_back({std::move(all), -1, 0});
  }
  TreeRef root = kOut;
  const std::size_t candidates = std::size_t(std::max(1, options.candidates));
  const std::size_t sample = std::size_t(std::max(1, options.sample));
  ConvexPolygon neg_part, pos_part;
  while (!stack.empty()) {
    Frame f = std::move(stack.back());
    stack.pop_back();
    const std::size_t n = f.pieces.size();
    // Score a few candidate planes against a sample of the cell's pieces.
    std::size_t best = 0;
    double best_score = 1e300;
    const std::size_t k = std::min(n, candidates), m = std::min(n, sample);
    for (std::size_t c = 0; c < k && n > 1; ++c) {
      const std::size_t i = c * n / k;
      const std::int32_t plane = pool[std::size_t(f.pieces[i])].outward;
      int neg = 0, pos = 0, both = 0;
      for (std::size_t j = 0; j < m; ++j) {
        const auto q = std::size_t(f.pieces[j * n / m]);
        const Side s = side_of(planes, pool[q], boxes[q], plane);
        neg += s == Side::Negative;
        pos += s == Side::Positive;
        both += s == Side::Both;
      }
      const double score = options.split_weight * both + std::abs(neg - pos);
      if (score < best_score) best_score = score, best = i;
    }
    const std::int32_t plane = pool[std::size_t(f.pieces[best])].outward;
    const std::int32_t opposite = arena.opposite(plane);
    const kernel::Plane pv = planes[plane], po = planes[opposite];
    std::vector<std::int32_t> negative, positive;
    for (const std::int32_t id : f.pieces) {
      Piece& p = pool[std::size_t(id)];
      const std::int32_t s = p.polygon.support;
      if (s == plane || s == opposite || planes[s] == pv || planes[s] == po) continue;  // used up
      Side side = kernel::box_side(boxes[std::size_t(id)], pv);
      if (side == Side::Both) side = kernel::split(planes, p.polygon, plane, opposite, neg_part, pos_part);
      switch (side) {
        case Side::Negative: negative.push_back(id); break;
        case Side::Positive: positive.push_back(id); break;
        case Side::Both: {
          const std::int32_t outward = p.outward;  // p dies when the pool grows
          negative.push_back(std::int32_t(pool.size()));
          pool.push_back({neg_part, outward});
          boxes.push_back(kernel::corner_box(neg_part));
          positive.push_back(std::int32_t(pool.size()));
          pool.push_back({pos_part, outward});
          boxes.push_back(kernel::corner_box(pos_part));
          break;
        }
        case Side::On: break;  // cannot happen: a piece on the plane has that support
      }
    }
    const auto id = TreeRef(nodes.size());
    nodes.push_back({plane, negative.empty() ? kIn : kOut, kOut});
    if (f.parent < 0)
      root = id;
    else
      (f.side == 0 ? nodes[std::size_t(f.parent)].negative : nodes[std::size_t(f.parent)].positive) = id;
    if (!negative.empty()) stack.push_back({std::move(negative), id, 0});
    if (!positive.empty()) stack.push_back({std::move(positive), id, 1});
  }

  // Bottom-up into the builder (children have larger indices), with the planes in use.
  TreeBuilder b;
  std::vector<std::int32_t> plane_map(std::size_t(planes.size()), -1);
  for (std::int32_t i = 0; i < kernel::kWorldPlanes; ++i) plane_map[std::size_t(i)] = i;  // shared world box
  auto use = [&](std::int32_t p) {
    if (plane_map[std::size_t(p)] < 0) plane_map[std::size_t(p)] = b.add_plane(planes[p]);
    return plane_map[std::size_t(p)];
  };
  std::vector<TreeRef> made(nodes.size(), kOut);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& nd = nodes[i];
    auto child = [&](TreeRef c) { return is_leaf(c) ? c : made[std::size_t(c)]; };
    made[i] = b.add_node(use(nd.plane), child(nd.negative), child(nd.positive));
  }
  if (!options.carry_boundary) return std::move(b).build(made[std::size_t(root)], BuildOptions{.nodes_cut_cells = true});
  for (BoundaryFragment& f : fragments) {
    f.polygon.support = use(f.polygon.support);
    for (auto& c : f.polygon.corners) c.edge = use(c.edge), c.p = use(c.p), c.q = use(c.q);
  }
  return std::move(b).build(made[std::size_t(root)], std::move(fragments), {.nodes_cut_cells = true});
}

}  // namespace sculpt::detail
