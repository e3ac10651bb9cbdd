// Ring primitives split first by the coordinate planes through their axis where the path has
// vertices there (bsp/rings/sector_tree.hpp, SectorOptions::axis_vertex): which paths qualify (decided
// exactly), that the ring vertices there lie exactly on those planes, that the solids stay the
// same (closed, same volume), and that a box sharing the planes is absorbed by the merge.
#include <gtest/gtest.h>

#include <numbers>

#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/rings/ring_solid.hpp"
#include "bsp/set_operations.hpp"
#include "kernel/predicates.hpp"
#include "support/mesh_checks.hpp"
#include "support/solid_checks.hpp"

namespace sculpt {
namespace {

using checks::vol;

using checks::EdgesManifoldAndOriented;

const kernel::Plane kY0 = kernel::make_plane(0, 1, 0, 0), kX0 = kernel::make_plane(1, 0, 0, 0);

// Nodes whose plane is `p` or its opposite.
int nodes_on(const Solid& s, const kernel::Plane& p) {
  int count = 0;
  for (const BspNode& n : s.nodes()) {
    const kernel::Plane& q = s.planes()[n.plane];
    count += q == p || q == p.opposite();
  }
  return count;
}

TEST(AxisPlanes, CirclesSplitAtTheirVerticesOnTheAxes) {
  for (const int n : {8, 12, 30, 31, 32, 33, 64}) {
    SCOPED_TRACE(testing::Message() << "segments " << n);
    const Solid s = sphere(1.0, {.segments = n});
    const int bands = (n + 1) / 2 + 1;  // between the rings, and a fan at each pole
    // Vertices at angles 0 and pi for even n, also at pi / 2 and 3 pi / 2 for n divisible by 4:
    // y = 0 splits every band, x = 0 each half of it.
    EXPECT_EQ(nodes_on(s, kY0), n % 2 == 0 ? bands : 0);
    // The poles lie on x = 0 as well: for even n it splits each pole's fan there too.
    EXPECT_EQ(nodes_on(s, kX0), n % 4 == 0 ? 2 * bands : (n % 2 == 0 ? 2 : 0));
    // The boundary's corners near those planes lie exactly on them (the splits are at vertices).
    for (const FragmentRef f : s.boundary())
      for (const kernel::Corner& c : f.polygon.corners) {
        const kernel::Plane& sp = s.planes()[f.polygon.support];
        for (const kernel::Plane* axis : {&kY0, &kX0}) {
          const double value = axis == &kY0 ? c.at().y : c.at().x;
          if (std::abs(value) > 1.0) continue;  // grid units: other corners are far from the plane
          const kernel::Sign g = kernel::orient(sp, s.planes()[c.p], s.planes()[c.q], c.at(), *axis);
          const bool split = axis == &kY0 ? n % 2 == 0 : n % 4 == 0;
          if (split) {
            EXPECT_EQ(g, kernel::Sign::Zero) << c.at().x << " " << c.at().y;
          }
        }
      }
    const PolygonMesh m = to_mesh(s);
    EXPECT_TRUE(EdgesManifoldAndOriented(m));
    EXPECT_TRUE(checks::GenusIs(m, 0));
  }
}

TEST(AxisPlanes, AsymmetricPathsKeepTheFaceMiddleSplits) {
  // A vertex on +x whose two edges are not mirror images: the ring vertices there are not on
  // y = 0, so no band may split there.
  const std::vector<Eigen::Vector2d> path = {{1, 0}, {0.3, 0.9}, {-1, 0.2}, {-0.6, -1}, {0.5, -0.7}};
  const Solid prism = bsp::detail::revolve_rings(path, {{0, 1}, {1, 1}});
  EXPECT_EQ(nodes_on(prism, kY0), 0);
  EXPECT_EQ(nodes_on(prism, kX0), 0);
  double area = 0;  // shoelace: the revolved prism's volume is area * height
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector2d& p = path[i];
    const Eigen::Vector2d& q = path[(i + 1) % path.size()];
    area += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  EXPECT_NEAR(vol(prism), area, 1e-6);
  // A symmetric path with vertices on all four axes (a diamond): both planes.
  const Solid diamond = bsp::detail::revolve_rings({{1, 0}, {0, 1}, {-1, 0}, {0, -1}}, {{0, 1}, {1, 1}});
  EXPECT_EQ(nodes_on(diamond, kY0), 1);
  EXPECT_EQ(nodes_on(diamond, kX0), 2);
  EXPECT_NEAR(vol(diamond), 2.0, 1e-6);  // edge normals are rounded to 2^-26
}

TEST(AxisPlanes, ABoxOnTheAxisPlanesIsAbsorbedByTheMerge) {
  // The cube's faces x = 0, y = 0 coincide with the sphere's first splits: the merge follows
  // them instead of partitioning the cube in every wedge, so the result is no larger than the
  // sphere (it was 1,049 nodes against the sphere's 961 when the first splits were at face middles).
  const Solid s = sphere(1.0, {.segments = 32});
  const Solid r = s - box({0, 0, 0}, {1, 1, 1});
  EXPECT_LT(tree_stats(r).nodes, tree_stats(s).nodes);
  EXPECT_NEAR(vol(r), 7 * vol(s) / 8, 1e-9);
  const PolygonMesh m = to_mesh(r);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(checks::VerticesManifold(m));
}

}  // namespace
}  // namespace sculpt
