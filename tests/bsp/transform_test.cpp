#include "bsp/transform.hpp"

#include <gtest/gtest.h>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using checks::EdgesManifoldAndOriented;
using checks::GenusIs;

TEST(Transform, TranslationIsExact) {
  const Solid b = translate(box({0, 0, 0}, {1, 2, 3}), {0.5, -1, 2});
  const PolygonMesh m = to_mesh(b);
  EXPECT_TRUE(checks::VolumeNear(m, 6.0, 1e-15));
  const Eigen::AlignedBox3d bb = bounding_box(b);
  EXPECT_EQ(bb.min(), Eigen::Vector3d(0.5, -1, 2));
  EXPECT_EQ(bb.max(), Eigen::Vector3d(1.5, 1, 5));
}

TEST(Transform, QuarterTurnsMirrorsAndIntegerScalesAreExact) {
  const Solid b = box({0, 0, 0}, {1, 2, 3});
  const Solid r = rotate(b, {0, 0, 1}, 90);
  EXPECT_EQ(bounding_box(r).min(), Eigen::Vector3d(-2, 0, 0));
  EXPECT_EQ(bounding_box(r).max(), Eigen::Vector3d(0, 1, 3));
  const Solid m = scale(b, {-1, 2, 3});
  EXPECT_EQ(bounding_box(m).min(), Eigen::Vector3d(-1, 0, 0));
  EXPECT_TRUE(checks::VolumeNear(to_mesh(m), 36.0, 1e-15));
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(m)));
}

TEST(Transform, GeneralRotationKeepsAValidSolidAndItsVolume) {
  const Solid s = sphere(1.0, {.segments = 24});
  const double v = volume(s);
  const Solid r = rotate(s, {1, 2, 3}, 37);
  const PolygonMesh m = to_mesh(r);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0));
  EXPECT_NEAR(volume(r), v, 1e-9);
  // A rotated cube minus itself is still exactly empty; unions with a copy are the same solid.
  const Solid c = rotate(box({-1, -1, -1}, {1, 1, 1}), {1, 1, 0}, 30);
  EXPECT_TRUE((c - c).is_empty());
  EXPECT_NEAR(volume(c | c), 8.0, 1e-9);
  EXPECT_EQ(classify(c, {0, 0, 0}).location, Location::Inside);
}

// Known failure (docs/bsp.md): after a non-integer scale every plane is re-quantized, the five
// planes of each sphere ring vertex no longer meet in one point, and the resulting sub-1e-12
// slivers leave a few unmatched edges in the mesh (4 of ~3000 here). Kept visible, disabled.
TEST(Transform, DISABLED_NonUniformScaleOfASphere) {
  const Solid e = scale(sphere(1.0, {.segments = 32}), {2, 1, 0.5});
  EXPECT_NEAR(volume(e), volume(sphere(1.0, {.segments = 32})), 1e-6);
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(e)));
}

}  // namespace
}  // namespace sculpt
