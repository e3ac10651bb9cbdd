#include "bsp/tree/tree_checks.hpp"

#include <vector>

namespace sculpt::bsp::detail {
namespace {

bool polygon_planes_in_table(kernel::PolygonView polygon, std::int32_t plane_count) {
  const auto in_table = [&](std::int32_t i) { return i >= 0 && i < plane_count; };
  if (polygon.empty()) return true;
  if (!in_table(polygon.support)) return false;
  for (const kernel::Corner& c : polygon.corners)
    if (!in_table(c.edge)) return false;
  return true;
}

}  // namespace

const char* tree_storage_problem(const kernel::PlaneTable& planes, const std::vector<BspNode>& nodes,
                                 const PolygonStore& polygons, TreeRef root, const FragmentList* boundary) {
  if (nodes.size() != polygons.size()) return "nodes and sub-hyperplanes differ in number";
  const auto valid_ref = [&](TreeRef r) { return r == kIn || r == kOut || (r >= 0 && std::size_t(r) < nodes.size()); };
  if (!valid_ref(root)) return "the root is neither a leaf nor a node";
  std::vector<bool> reached(nodes.size(), false);
  std::vector<TreeRef> stack;  // explicit: trees can be deeper than the call stack allows
  if (!is_leaf(root)) stack.push_back(root);
  while (!stack.empty()) {
    const TreeRef at = stack.back();
    stack.pop_back();
    if (reached[std::size_t(at)]) return "a node is reached twice (shared or cyclic subtree)";
    reached[std::size_t(at)] = true;
    const BspNode& node = nodes[std::size_t(at)];
    if (node.plane < 0 || node.plane >= planes.size()) return "a node's plane is not in the plane table";
    const kernel::ConvexPolygon& sub = polygons[std::size_t(at)];
    if (!polygon_planes_in_table(sub, planes.size())) return "a sub-hyperplane uses a plane not in the table";
    if (!sub.empty() && sub.support != node.plane) return "a sub-hyperplane is not on its node's plane";
    for (const TreeRef child : {node.negative, node.positive}) {
      if (!valid_ref(child)) return "a child is neither a leaf nor a node";
      if (!is_leaf(child)) stack.push_back(child);
    }
  }
  if (boundary != nullptr)
    for (const FragmentRef f : *boundary)
      if (!polygon_planes_in_table(f.polygon, planes.size()))
        return "a boundary fragment uses a plane not in the table";
  return nullptr;
}

}  // namespace sculpt::bsp::detail
