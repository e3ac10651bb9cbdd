#include "revolution/trees/revolve_plane_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/errors.hpp"
#include "curves/profiles.hpp"

using namespace sculpt;
using namespace sculpt::revolution;
using namespace sculpt::revolution::detail;

namespace {

/// Independent membership test of the revolved polytope, with a margin: +1 inside, -1 outside,
/// 0 if within `margin` of the boundary (undecided). The solid is {(x, y, z): (x, y) in r(z) P}.
int analytic_side(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path, const Eigen::Vector3d& p,
                  double margin) {
  const double z0 = profile.front().y(), z1 = profile.back().y();
  if (p.z() < z0 - margin || p.z() > z1 + margin) return -1;
  for (const auto& v : profile)
    if (std::abs(p.z() - v.y()) < margin) return 0;
  if (p.z() < z0 || p.z() > z1) return -1;
  std::size_t i = 0;
  while (!(profile[i].y() <= p.z() && p.z() <= profile[i + 1].y())) ++i;
  const double t = (p.z() - profile[i].y()) / (profile[i + 1].y() - profile[i].y());
  const double r = profile[i].x() + t * (profile[i + 1].x() - profile[i].x());
  // Signed distance-like value to each scaled edge line.
  double worst = -1e300;
  for (int e = 0; e < path.edges(); ++e) {
    const Eigen::Vector2d a = r * path.vertices[e], b = r * path.vertices[(e + 1) % path.edges()];
    const Eigen::Vector2d d = b - a;
    const double len = d.norm();
    if (len == 0) return std::hypot(p.x(), p.y()) < margin ? 0 : -1;
    worst = std::max(worst, (d.y() * (p.x() - a.x()) - d.x() * (p.y() - a.y())) / len);  // > 0 outside
  }
  if (std::abs(worst) < margin) return 0;
  return worst < 0 ? 1 : -1;
}

std::vector<Eigen::Vector2d> goblet(int points) {
  return curves::planar_points(curves::sample_profile(curves::goblet_profile(), {.points = points}).points);
}

void check_against_analytic(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path,
                            const RevolveOptions& options, int samples) {
  const PlaneTree tree = revolve_plane_tree(profile, path, options);
  double rmax = 0;
  for (const auto& v : profile) rmax = std::max(rmax, v.x());
  const double zlo = std::min(profile.front().y(), profile.back().y()), zhi = std::max(profile.front().y(), profile.back().y());
  std::mt19937_64 rng(123);
  std::uniform_real_distribution<double> U(-1.2, 1.2), Z(zlo - 0.1 * (zhi - zlo), zhi + 0.1 * (zhi - zlo));
  const auto mono = monotone_profile(profile);
  int decided = 0;
  for (int i = 0; i < samples; ++i) {
    const Eigen::Vector3d p(U(rng) * rmax, U(rng) * rmax, Z(rng));
    const int side = analytic_side(mono, path, p, 1e-9);
    if (side == 0) continue;
    ++decided;
    ASSERT_EQ(tree.classify(p) == kIn, side > 0) << "point " << p.transpose();
  }
  EXPECT_GT(decided, samples * 9 / 10);
}

}  // namespace

TEST(RevolvePlaneTree, ClassifiesLikeTheRevolvedPolytope) {
  check_against_analytic(goblet(21), circular_path(32), {}, 200000);
  check_against_analytic(goblet(33), ellipse_path(1.0, 0.6, 32), {}, 100000);
  const auto face = curves::planar_points(curves::sample_profile(curves::human_profile(), {.points = 33}).points);
  check_against_analytic(face, ellipse_path(1.0, 0.8, 32), {}, 100000);
  // A path not centred on the axis, a triangle, and face planes only.
  check_against_analytic(goblet(11), polygon_path({{-0.5, -0.2}, {1.0, -0.3}, {0.8, 0.9}, {-0.4, 0.7}}), {}, 50000);
  check_against_analytic(goblet(11), polygon_path({{0, -1}, {1, 1}, {-1, 0.5}}), {.face_only_below = 100}, 50000);
}

TEST(RevolvePlaneTree, HandlesStepsAxisPointsAndDecreasingProfiles) {
  // A stepped profile (horizontal runs), ending on the axis at both ends; then reversed.
  const std::vector<Eigen::Vector2d> steps{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {1.5, 2}, {1.5, 3}, {0, 3.5}};
  check_against_analytic(steps, circular_path(16), {}, 100000);
  const std::vector<Eigen::Vector2d> reversed(steps.rbegin(), steps.rend());
  check_against_analytic(reversed, circular_path(16), {}, 50000);
  // A profile running along the axis for a while: that slab is empty.
  const std::vector<Eigen::Vector2d> pinched{{1, 0}, {0, 1}, {0, 2}, {1, 3}};
  check_against_analytic(pinched, circular_path(12), {}, 50000);
}

// Section 6: "If the revolved curve has m segments, then the number of faces is nm and the bsp
// tree is of size O(nm) and height O(log n + log m)".
TEST(RevolvePlaneTree, SizeIsSlabsTimesPathTreeAndHeightIsTheSumOfLogs) {
  for (int m : {1, 2, 5, 20, 32, 100})
    for (int n : {3, 8, 32, 64}) {
      const auto profile = goblet(m + 1);
      const PathTree path_tree = build_path_tree(circular_path(n));
      const PlaneTree tree = revolve_plane_tree(profile, circular_path(n));
      // m slabs of one lifted path tree each, m + 1 horizontal planes.
      EXPECT_EQ(tree.nodes.size(), m * path_tree.nodes.size() + (m + 1)) << n << " " << m;
      EXPECT_EQ(tree.height(), static_cast<int>(std::ceil(std::log2(m + 2))) + path_tree.height()) << n << " " << m;
      EXPECT_LT(2 * static_cast<int>(tree.nodes.size()) + 1, 3 * n * m + 2 * (m + 1) + 16) << n << " " << m;
    }
}

TEST(RevolvePlaneTree, RejectsProfilesItCannotRevolve) {
  const ConvexPath path = circular_path(8);
  EXPECT_THROW(revolve_plane_tree({{1, 0}}, path), InvalidInput);
  EXPECT_THROW(revolve_plane_tree({{1, 0}, {2, 0}}, path), InvalidInput);              // flat
  EXPECT_THROW(revolve_plane_tree({{1, 0}, {-1, 1}}, path), InvalidInput);             // r < 0
  EXPECT_THROW(revolve_plane_tree({{1, 0}, {1, NAN}}, path), InvalidInput);
  try {
    (void)revolve_plane_tree({{0, 0}, {1, 1}, {2, 2}, {1, 1.5}, {0, 1}}, path);       // up, then down
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not monotone"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos) << e.what();
  }
}
