// The depth mode's numbers (lib/view/detail/cell_depths.hpp): the depth of the leaf cell behind
// each boundary triangle, checked by hand on a box (a chain of six nodes: the one in-cell at
// depth 6) and against exact point classification on solids with in-cells at several depths.
#include "view/detail/cell_depths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt::view::detail {
namespace {

struct Triangles {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// The boundary of `solid` as triangles with float32 corners, as a GLB holds them.
Triangles triangles_of(const Solid& solid) {
  const PolygonMesh mesh = to_mesh(solid, {.triangulate = true});
  Triangles out;
  for (const auto& v : mesh.vertices) out.points.push_back(v.cast<float>().cast<double>());
  for (const auto& f : mesh.faces)
    out.triangles.push_back({std::uint32_t(f[0]), std::uint32_t(f[1]), std::uint32_t(f[2])});
  return out;
}

TEST(CellDepths, BoxIsAChainOfSixNodesWithItsInCellAtTheEnd) {
  const Solid cube = box({0, 0, 0}, {1, 2, 3});
  // The tree by hand: six planes, each with an out-leaf on the outer side, the in-leaf last.
  const TreeStats stats = tree_stats(cube);
  ASSERT_EQ(stats.nodes, 6);
  ASSERT_EQ(stats.in_leaves, 1);
  ASSERT_EQ(stats.out_leaves, 6);
  ASSERT_EQ(stats.height, 6);
  const Triangles t = triangles_of(cube);
  ASSERT_EQ(t.triangles.size(), 12u);
  for (const int depth : cell_depths_behind(cube, t.points, t.triangles)) EXPECT_EQ(depth, 6);
}

/// True when a plane of the tree other than the triangle's own passes within `distance` (world
/// units) of `point`: exact classification of a point on a plane descends both sides and counts
/// both, so such points do not measure one cell's depth.
bool near_another_plane(const Solid& solid, const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                        double distance) {
  const kernel::Grid& grid = solid.grid();
  const Eigen::Vector3d g(grid.to_grid(point.x()), grid.to_grid(point.y()), grid.to_grid(point.z()));
  for (const BspNode& node : solid.nodes()) {
    const kernel::Plane& p = solid.planes()[node.plane];
    const double length = p.normal().norm();
    const bool parallel = std::abs(p.normal().dot(normal)) / length > 1 - 1e-9;
    if (!parallel && std::abs(p.normal().dot(g) + p.d_nearest) / length < grid.to_grid(distance)) return true;
  }
  return false;
}

TEST(CellDepths, EqualTheCostOfClassifyingAPointJustInside) {
  // A notched block, a block with a hole through it and a ball: in-cells at several depths.
  const Solid notched = subtract(box({0, 0, 0}, {2, 1, 1}), box({1.5, -1, 0.5}, {3, 2, 2}));
  const Solid holed = subtract(box({0, 0, 0}, {4, 4, 1}), box({1, 1, -1}, {2, 2, 2}));
  const Solid ball = sphere(1, {.segments = 12});
  for (const Solid* solid : {&notched, &holed, &ball}) {
    const Triangles t = triangles_of(*solid);
    const std::vector<int> depths = cell_depths_behind(*solid, t.points, t.triangles);
    ASSERT_EQ(depths.size(), t.triangles.size());
    int lowest = 1 << 30, highest = 0;
    std::size_t checked = 0;
    for (std::size_t k = 0; k < depths.size(); ++k) {
      const Eigen::Vector3d& a = t.points[t.triangles[k][0]];
      const Eigen::Vector3d& b = t.points[t.triangles[k][1]];
      const Eigen::Vector3d& c = t.points[t.triangles[k][2]];
      const Eigen::Vector3d inward = -(b - a).cross(c - a).normalized();
      // 0.001 inside (far more than the grid step, far less than any feature of these solids).
      const Eigen::Vector3d point = (a + b + c) / 3 + 1e-3 * inward;
      if (near_another_plane(*solid, point, inward, 2e-3)) continue;
      ++checked;
      const Classification inside = classify(*solid, point);
      ASSERT_EQ(inside.location, Location::Inside) << "triangle " << k;
      EXPECT_EQ(depths[k], inside.path_length) << "triangle " << k;
      lowest = std::min(lowest, depths[k]);
      highest = std::max(highest, depths[k]);
    }
    EXPECT_LT(lowest, highest) << "the boundary sees in-cells at several depths";
    EXPECT_GT(checked, depths.size() / 2) << "most triangles have no other plane near their centre";
  }
}

}  // namespace
}  // namespace sculpt::view::detail
