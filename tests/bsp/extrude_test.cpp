// extrude over convex and non-convex polygons: volume = area * height exactly, closed boundary,
// both orientations, and clear errors for crossing, degenerate and flat input.
#include "bsp/extrude.hpp"

#include <gtest/gtest.h>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using checks::EdgesManifoldAndOriented;
using checks::GenusIs;

TEST(Extrude, ANonConvexPolygonInEitherOrientation) {
  // A U shape: 3 x 3 square minus the 1 x 2 notch at the top middle, area 7.
  std::vector<Eigen::Vector2d> u{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  for (int pass = 0; pass < 2; ++pass) {
    const Solid s = extrude(u, -0.5, 1.5);
    EXPECT_DOUBLE_EQ(volume(s), 14.0);
    const PolygonMesh m = to_mesh(s);
    EXPECT_TRUE(EdgesManifoldAndOriented(m));
    EXPECT_TRUE(GenusIs(m, 0));
    EXPECT_EQ(classify(s, {1.5, 2, 0}).location, Location::Outside);  // in the notch
    EXPECT_EQ(classify(s, {1.5, 0.5, 0}).location, Location::Inside);
    std::reverse(u.begin(), u.end());
  }
}

TEST(Extrude, AClosingPointRepeatedIsDropped) {
  const std::vector<Eigen::Vector2d> tri{{0, 0}, {2, 0}, {0, 1}, {0, 0}};
  EXPECT_DOUBLE_EQ(volume(extrude(tri, 0, 3)), 3.0);
}

TEST(Extrude, BadPolygonsAreRefusedWithAReason) {
  const std::vector<Eigen::Vector2d> bow_tie{{0, 0}, {2, 2}, {2, 0}, {0, 1}};  // signed area -1, crossing
  try {
    (void)extrude(bow_tie, 0, 1);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("crosses or touches itself"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)extrude({{0, 0}, {1, 0}, {2, 0}}, 0, 1), InvalidInput);  // zero area
  EXPECT_THROW((void)extrude({{0, 0}, {1, 0}}, 0, 1), InvalidInput);
  EXPECT_THROW((void)extrude({{0, 0}, {1, 0}, {0, 1}}, 1, 1), InvalidInput);
}

}  // namespace
}  // namespace sculpt
