// shell_orientations and the validator's misoriented-shell check, against nestings known by
// construction: boxes in boxes, and random chains of nested spheres with random orientations.
#include "mesh/shell_orientation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mesh/mesh_validation.hpp"
#include "shapes.hpp"

namespace sculpt {
namespace {

using ::testing::HasSubstr;
using test_shapes::box;
using test_shapes::merged;

PolygonMesh reversed(PolygonMesh m) {
  for (auto& f : m.faces) std::reverse(f.begin(), f.end());
  return m;
}

PolygonMesh moved(PolygonMesh m, const Eigen::Vector3d& by) {
  for (auto& v : m.vertices) v += by;
  return m;
}

TEST(ShellOrientation, OneShellFacingInwardsIsWrong) {
  const auto shells = shell_orientations(reversed(test_shapes::unit_cube()));
  ASSERT_EQ(shells.size(), 1u);
  EXPECT_EQ(shells[0].enclosing_shells, 0);
  EXPECT_DOUBLE_EQ(shells[0].signed_volume, -1.0);
  EXPECT_FALSE(shells[0].consistent());
  const ValidationReport r = check_closed_manifold(reversed(test_shapes::unit_cube()));
  EXPECT_EQ(r.count(DefectKind::MisorientedShell), 1u) << r.summary();
  EXPECT_THAT(r.summary(), HasSubstr("shell 0 (6 faces, first corner ("));
  EXPECT_THAT(r.summary(), HasSubstr(")) faces inwards (signed volume -1) but lies inside 0 other shells"));
}

TEST(ShellOrientation, AnInwardShellBesideAnOutwardOneIsWrong) {
  // The case a whole-mesh volume test passes: the larger outward box outweighs the other.
  const PolygonMesh m = merged(box({0, 0, 0}, {4, 4, 4}), reversed(box({5, 0, 0}, {6, 1, 1})));
  const auto shells = shell_orientations(m);
  ASSERT_EQ(shells.size(), 2u);
  EXPECT_TRUE(shells[0].consistent());
  EXPECT_FALSE(shells[1].consistent());
  EXPECT_EQ(check_closed_manifold(m).count(DefectKind::MisorientedShell), 1u);
}

TEST(ShellOrientation, ACavityMustFaceInwardsAndAnIslandInItOutwards) {
  const PolygonMesh outer = box({0, 0, 0}, {4, 4, 4});
  const PolygonMesh cavity = box({1, 1, 1}, {3, 3, 3});
  const PolygonMesh island = box({1.5, 1.5, 1.5}, {2.5, 2.5, 2.5});
  EXPECT_TRUE(check_closed_manifold(merged(merged(outer, reversed(cavity)), island)).ok());
  const auto shells = shell_orientations(merged(merged(outer, cavity), reversed(island)));
  ASSERT_EQ(shells.size(), 3u);
  EXPECT_EQ(shells[0].enclosing_shells, 0);
  EXPECT_EQ(shells[1].enclosing_shells, 1);
  EXPECT_EQ(shells[2].enclosing_shells, 2);
  EXPECT_TRUE(shells[0].consistent());
  EXPECT_FALSE(shells[1].consistent());
  EXPECT_FALSE(shells[2].consistent());
  const ValidationReport r = check_closed_manifold(merged(merged(outer, cavity), reversed(island)));
  EXPECT_EQ(r.count(DefectKind::MisorientedShell), 2u) << r.summary();
  EXPECT_THAT(r.summary(), HasSubstr("lies inside 1 other shell(s), so it bounds a cavity"));
}

TEST(ShellOrientation, ABoxWhoseBoundingBoxFitsButWhichIsOutside) {
  // An L-shaped outer shell: the small box sits in its bounding box but in the notch, outside.
  PolygonMesh l_shape;
  l_shape.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {1, 1, 0}, {1, 4, 0}, {0, 4, 0},
                      {0, 0, 1}, {4, 0, 1}, {4, 1, 1}, {1, 1, 1}, {1, 4, 1}, {0, 4, 1}};
  l_shape.faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
  for (int k = 0; k < 6; ++k) l_shape.faces.push_back({k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k});
  ASSERT_TRUE(check_closed_manifold(l_shape).ok()) << check_closed_manifold(l_shape).summary();
  const auto shells = shell_orientations(merged(l_shape, box({2, 2, 0.25}, {3, 3, 0.75})));
  ASSERT_EQ(shells.size(), 2u);
  EXPECT_EQ(shells[1].enclosing_shells, 0);
  EXPECT_TRUE(shells[1].consistent());
}

TEST(ShellOrientation, RandomChainsOfNestedSpheres) {
  std::mt19937 rng(20261126);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 40; ++trial) {
    PolygonMesh m;
    std::vector<int> depth;
    std::vector<bool> flipped;
    const int chains = 1 + trial % 3;
    for (int c = 0; c < chains; ++c) {
      Eigen::Vector3d centre(10.0 * c, 0.5 * c, -0.25 * c);
      double radius = 2;
      const int length = 1 + static_cast<int>(unit(rng) * 4);
      for (int k = 0; k < length; ++k) {
        const bool flip = unit(rng) < 0.3;
        const PolygonMesh s = moved(test_shapes::uv_sphere(12, radius), centre);
        m = merged(m, flip ? reversed(s) : s);
        depth.push_back(k);
        flipped.push_back(flip);
        // The next sphere lies well inside this one's inscribed polyhedron (inradius about 0.93 r).
        const double next = radius * (0.4 + 0.3 * unit(rng));
        const double room = 0.9 * radius - next;
        centre += room * Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
        radius = next;
      }
    }
    const auto shells = shell_orientations(m);
    ASSERT_EQ(shells.size(), depth.size());
    size_t wrong = 0;
    for (size_t s = 0; s < shells.size(); ++s) {
      EXPECT_EQ(shells[s].enclosing_shells, depth[s]) << "trial " << trial << " shell " << s;
      EXPECT_EQ(shells[s].consistent(), (depth[s] % 2 == 0) != flipped[s]) << "trial " << trial << " shell " << s;
      wrong += (depth[s] % 2 == 0) == flipped[s];
    }
    EXPECT_EQ(check_closed_manifold(m).count(DefectKind::MisorientedShell), wrong) << "trial " << trial;
  }
}

}  // namespace
}  // namespace sculpt
