#include "reports/range_query_tree.hpp"

#include <cmath>

#include "kernel/grid.hpp"

namespace sculpt::reports {

RangeQueryTree::RangeQueryTree(const Solid& solid) : root_(solid.root()) {
  nodes_.reserve(solid.nodes().size());
  for (const BspNode& n : solid.nodes()) {
    const kernel::Plane& p = solid.planes()[n.plane];
    // f(grid point) = a X + b Y + c Z + d with X = x / step: in world units divide d by step.
    const double a = double(p.a), b = double(p.b), c = double(p.c);
    const double d = solid.grid().to_world(double(p.d));
    const double norm = std::sqrt(a * a + b * b + c * c);
    nodes_.push_back({a / norm, b / norm, c / norm, d / norm, {n.negative, n.positive}});
  }
}

}  // namespace sculpt::reports
