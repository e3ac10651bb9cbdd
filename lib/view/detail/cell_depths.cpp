#include "view/detail/cell_depths.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace sculpt::view::detail {

std::vector<int> cell_depths_behind(const Solid& solid, std::span<const Eigen::Vector3d> points,
                                    std::span<const std::array<std::uint32_t, 3>> triangles) {
  const TreeRef root = solid.root();  // builds a deferred tree
  const std::vector<BspNode>& nodes = solid.nodes();
  const kernel::PlaneTable& planes = solid.planes();
  const kernel::Grid& grid = solid.grid();
  // Each node's plane in grid units as doubles, scaled to a unit normal: f is then a distance.
  struct UnitPlane {
    Eigen::Vector3d n;
    double d;
  };
  std::vector<UnitPlane> unit(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const kernel::Plane& p = planes[nodes[k].plane];
    const double length = p.normal().norm();
    unit[k] = {p.normal() / length, p.d_nearest / length};
  }
  std::vector<int> depths;
  depths.reserve(triangles.size());
  for (const auto& t : triangles) {
    Eigen::Vector3d g[3];
    double largest = 0;
    for (int i = 0; i < 3; ++i) {
      for (int a = 0; a < 3; ++a) g[i][a] = grid.to_grid(points[t[i]][a]);
      largest = std::max(largest, g[i].cwiseAbs().maxCoeff());
    }
    const Eigen::Vector3d centre = (g[0] + g[1] + g[2]) / 3;
    const Eigen::Vector3d outward = (g[1] - g[0]).cross(g[2] - g[0]);
    // The corners are float32 roundings of exact points (2^-24 relative): a plane through the
    // exact triangle passes within a few such units of the centre.
    const double tolerance = 1e-6 * largest + 1e-9;
    int depth = 0;
    for (TreeRef k = root; k >= 0; ++depth) {
      const UnitPlane& p = unit[std::size_t(k)];
      const double f = p.n.dot(centre) + p.d;
      // On the plane: go behind the triangle, where a point pushed inward lies (f = -n.outward).
      const bool positive = std::fabs(f) > tolerance ? f > 0 : p.n.dot(outward) < 0;
      k = positive ? nodes[std::size_t(k)].positive : nodes[std::size_t(k)].negative;
    }
    depths.push_back(depth);
  }
  return depths;
}

}  // namespace sculpt::view::detail
