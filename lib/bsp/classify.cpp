#include "bsp/classify.hpp"

#include <vector>

namespace sculpt {

Classification classify(const Solid& solid, const Eigen::Vector3d& point) {
  return classify(solid.grid().snap(point), solid.root(), solid.nodes(), solid.planes());
}

Classification classify(const kernel::GridPoint& g, TreeRef root, std::span<const BspNode> nodes,
                        const kernel::PlaneTable& planes) {
  // Depth-first over the nodes the point reaches; a point on a plane takes both sides.
  int visited = 0;
  bool any_in = false, any_out = false;
  std::vector<TreeRef> stack{root};
  while (!stack.empty()) {
    const TreeRef r = stack.back();
    stack.pop_back();
    if (is_leaf(r)) {
      (r == kIn ? any_in : any_out) = true;
      continue;
    }
    ++visited;
    const BspNode& n = nodes[std::size_t(r)];
    const kernel::Sign s = kernel::orient(g, planes[n.plane]);
    if (s != kernel::Sign::Positive) stack.push_back(n.negative);
    if (s != kernel::Sign::Negative) stack.push_back(n.positive);
  }
  const Location loc = any_in && any_out ? Location::Boundary : (any_in ? Location::Inside : Location::Outside);
  return {loc, visited};
}

}  // namespace sculpt
