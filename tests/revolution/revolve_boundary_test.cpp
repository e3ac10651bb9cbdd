#include "revolution/revolve_boundary.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "curves/profiles.hpp"
#include "support/mesh_checks.hpp"

using namespace sculpt;
using namespace sculpt::revolution;

namespace {
std::vector<Eigen::Vector2d> noisy_samples(const curves::ProfileDesign& d, int points) {
  return curves::planar_points(curves::sample_profile(d, {.points = points, .noise = 0.003, .seed = 2}).points);
}
}  // namespace

TEST(RevolveBoundary, CylinderConeAndFrustumHaveTheirClosedFormVolumes) {
  const double pi = std::numbers::pi;
  for (int n : {3, 4, 7, 32}) {
    const ConvexPath path = circular_path(n);
    const double area = n / 2.0 * std::sin(2 * pi / n);
    EXPECT_NEAR(revolved_volume({{1, 0}, {1, 2}}, path), 2 * area, 1e-14);                 // prism
    EXPECT_NEAR(revolved_volume({{1, 0}, {0, 3}}, path), area, 1e-14);                     // pyramid: A h / 3
    EXPECT_NEAR(revolved_volume({{2, 0}, {1, 1}}, path), area * (4 + 1 + 2) / 3, 1e-13);   // frustum
    const PolygonMesh m = revolve_boundary({{2, 0}, {1, 1}}, path);
    EXPECT_TRUE(checks::VolumeNear(m, area * 7 / 3, 1e-13));
  }
}

TEST(RevolveBoundary, MeshesAreClosedSpheresWithTheAnalyticVolume) {
  const std::vector<std::vector<Eigen::Vector2d>> profiles{
      noisy_samples(curves::goblet_profile(), 21),
      noisy_samples(curves::goblet_profile(), 237),
      noisy_samples(curves::human_profile(), 33),
      noisy_samples(curves::goblet_cavity_profile(), 12),
      noisy_samples(curves::ball_profile(1.5, 6.8), 17),
      {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {1.5, 2}, {1.5, 3}, {0, 3.5}}};
  for (const auto& profile : profiles)
    for (const ConvexPath& path : {circular_path(32), ellipse_path(1.0, 0.6, 32), polygon_path({{0, -1}, {1, 1}, {-1, 0.5}})}) {
      const PolygonMesh m = revolve_boundary(profile, path);
      EXPECT_TRUE(checks::GenusIs(m, 0));
      EXPECT_TRUE(checks::NoDegenerateFaces(m, 1e-12));
      EXPECT_TRUE(checks::VolumeNear(m, revolved_volume(profile, path), 1e-12));
    }
}

TEST(RevolveBoundary, FaceCountIsPathEdgesTimesSlabsPlusCaps) {
  const auto profile = noisy_samples(curves::goblet_profile(), 21);  // neither end on the axis: two caps
  const PolygonMesh m = revolve_boundary(profile, circular_path(32));
  EXPECT_EQ(m.faces.size(), 20u * 32u + 2u);
  const auto face = noisy_samples(curves::human_profile(), 33);  // ends on the axis at the top: one cap
  EXPECT_EQ(revolve_boundary(face, circular_path(32)).faces.size(), 32u * 32u + 1u);
}
