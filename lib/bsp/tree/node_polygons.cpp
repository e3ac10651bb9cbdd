#include "bsp/tree/node_polygons.hpp"
#include "base/cancel.hpp"
#include "base/dispose.hpp"

#include <stdexcept>

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::Side;

CellCut clip_to_cell(kernel::PlaneTable& planes, std::int32_t plane, std::span<const std::int32_t> path,
                     ConvexPolygon& polygon, std::int32_t& on) {
  // Two buffers: each clip writes the other one (no copy back).
  ConvexPolygon buffers[2] = {kernel::world_polygon(planes, plane, {.quick_corners = true}), {}};
  int current = 0;
  kernel::CornerBox box = kernel::corner_box(buffers[0]);  // kept equal to the current polygon's
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const std::int32_t c = *it;
    const Side s = kernel::clip_to_negative(planes, buffers[current], buffers[1 - current], box, c);
    if (s == Side::Both) {
      current = 1 - current;
    } else if (s == Side::On) {  // the same plane as an ancestor's
      on = c;
      return planes[c] == planes[plane] ? CellCut::Negative : CellCut::Positive;
    } else if (s == Side::Positive) {
      return CellCut::Empty;
    }
  }
  polygon = std::move(buffers[current]);
  kernel::refresh_world_corners(planes, polygon);  // the usual bits on kept world corners
  return CellCut::Cuts;
}

ConvexPolygon node_polygon(Arena& arena, std::int32_t plane, std::span<const std::int32_t> path) {
  ConvexPolygon poly;
  std::int32_t on = -1;
  if (clip_to_cell(arena.planes, plane, path, poly, on) != CellCut::Cuts)
    throw std::logic_error("BSP tree invariant violated: a node's plane does not cut its cell");
  return poly;
}

void fill_node_polygons(Arena& arena, TreeRef root) {
  if (is_leaf(root)) return;
  struct Frame {
    TreeRef node;
    std::size_t depth;  // constraints inherited from the ancestors
    std::int32_t add;   // constraint this node adds to its parent's, -1 at the root
  };
  std::vector<std::int32_t> path;
  std::vector<Frame> stack{{root, 0, -1}};
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  while (!stack.empty()) {
    poll.tick();
    const Frame f = stack.back();
    stack.pop_back();
    path.resize(f.depth);
    if (f.add >= 0) path.push_back(f.add);
    const BspNode n = arena.nodes[std::size_t(f.node)];
    if (pending(arena.polygons[std::size_t(f.node)]))
      arena.polygons[std::size_t(f.node)] = node_polygon(arena, n.plane, path);
    if (!is_leaf(n.positive)) stack.push_back({n.positive, path.size(), arena.opposite(n.plane)});
    if (!is_leaf(n.negative)) stack.push_back({n.negative, path.size(), n.plane});
  }
}

Arena with_node_polygons(const Solid& solid) {
  Arena arena;
  try {
    arena.copy_planes(solid.planes());
    arena.nodes = solid.nodes();
    // Copied one by one with Ctrl-C checks: hundreds of MB on a large tree.
    CancelPoll poll;
    arena.polygons.reserve(solid.polygons().size());
    for (const ConvexPolygon& p : solid.polygons()) {
      poll.tick();
      arena.polygons.push_back(p);
    }
    fill_node_polygons(arena, solid.root());
  } catch (const Cancelled&) {
    dispose_in_background(std::move(arena));  // freed on another thread (base/dispose.hpp)
    throw;
  }
  return arena;
}

}  // namespace sculpt::bsp::detail
