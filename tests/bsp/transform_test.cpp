#include "bsp/transform.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

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

// General maps move each boundary vertex to the nearest grid point (docs/kernel.md): by at most
// sqrt(3)/2 grid steps, so the volume changes by less than the surface area times one step.
double snap_bound(const Solid& s) { return surface_area(s) * kernel::kGridStep; }

TEST(Transform, GeneralRotationKeepsAValidSolidAndItsVolume) {
  const Solid s = sphere(1.0, {.segments = 24});
  const double v = volume(s);
  const Solid r = rotate(s, {1, 2, 3}, 37);
  const PolygonMesh m = to_mesh(r);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0));
  EXPECT_NEAR(volume(r), v, snap_bound(s));
  // The vertices are the rotated ones, snapped: as many as before, each within a grid step.
  const PolygonMesh before = to_mesh(s);
  EXPECT_EQ(m.vertices.size(), before.vertices.size());
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(37 * std::numbers::pi / 180, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const Eigen::Vector3d& p : before.vertices) {
    double nearest = 1e300;
    for (const Eigen::Vector3d& q : m.vertices) nearest = std::min(nearest, (rot * p - q).norm());
    EXPECT_LE(nearest, 0.87 * kernel::kGridStep);
  }
  // A rotated cube minus itself is still exactly empty; unions with a copy are the same solid.
  const Solid c = rotate(box({-1, -1, -1}, {1, 1, 1}), {1, 1, 0}, 30);
  EXPECT_TRUE((c - c).is_empty());
  EXPECT_NEAR(volume(c | c), 8.0, 24 * kernel::kGridStep);
  EXPECT_EQ(volume(c | c), volume(c));
  EXPECT_EQ(to_mesh(c).vertices.size(), 8u);
  EXPECT_EQ(classify(c, {0, 0, 0}).location, Location::Inside);
}

// What the user meant survives a general rotation: a cone keeps one apex, a box eight corners, a
// cylinder its two rings (issue 14: planes rotated one by one used to split each such vertex into
// a cluster within 1e-15, joined by slivers). Every vertex is a distinct point.
TEST(Transform, GeneralRotationsKeepEveryVertexOnce) {
  const Solid solids[] = {cone(1.0, 2.0, {.segments = 24}), box({-1, -0.5, 0}, {1, 0.5, 0.25}),
                          cylinder(0.5, 2.0, {.segments = 32}), sphere(1.0, {.segments = 20})};
  for (const Solid& s : solids) {
    const std::size_t count = to_mesh(s).vertices.size();
    for (const double degrees : {13.0, 37.0, 71.5}) {
      const PolygonMesh m = to_mesh(rotate(translate(s, {0.3, -0.2, 0.1}), {1, 2, -0.7}, degrees));
      EXPECT_EQ(m.vertices.size(), count) << degrees;
      std::vector<Eigen::Vector3d> sorted = m.vertices;
      std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
      });
      EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << degrees;
      EXPECT_TRUE(EdgesManifoldAndOriented(m)) << degrees;
      EXPECT_TRUE(GenusIs(m, 0)) << degrees;
    }
  }
}

// After a non-integer scale every plane is re-quantized: the five planes of each sphere ring
// vertex no longer meet in one point, and the solid gains slivers far below 1e-12 whose edges
// are shorter than the doubles can tell apart (zero-length in floating point). The mesh must
// still close exactly (this once left 4 unmatched edges: T-junction tests skipped the exact
// path for such edges and sorted inserted vertices by approximate position).
TEST(Transform, NonUniformScaleOfASphere) {
  const Solid s = sphere(1.0, {.segments = 32});
  const Solid e = scale(s, {2, 1, 0.5});
  const PolygonMesh m = to_mesh(e);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0));
  // det = 1: the volume is unchanged up to the snapping of the vertices.
  EXPECT_NEAR(checks::reference_signed_volume(m), volume(s), snap_bound(e));
  EXPECT_EQ(classify(e, {1.9, 0, 0}).location, Location::Inside);
  EXPECT_EQ(classify(e, {0, 0, 0.52}).location, Location::Outside);
}

TEST(Transform, NonUniformScalesAndRotationsOfSetOperationResultsStayClosed) {
  const Solid base = sphere(1.0, {.segments = 48}) - box({0, 0, 0}, {1, 1, 1});
  const double v = volume(base);
  const Eigen::Vector3d factors[] = {{1.3, 0.7, 2.1}, {0.37, 1.0, 1.0}, {3.0, 0.25, 1.5}};
  for (const Eigen::Vector3d& f : factors) {
    const Solid e = scale(base, f);
    const PolygonMesh m = to_mesh(e);
    EXPECT_TRUE(EdgesManifoldAndOriented(m)) << f.transpose();
    EXPECT_TRUE(GenusIs(m, 0)) << f.transpose();
    EXPECT_NEAR(checks::reference_signed_volume(m), v * f.prod(), snap_bound(e)) << f.transpose();
    // A rotation after the scale, then a set operation with the transformed solid itself.
    const Solid r = rotate(e, {1, -2, 0.5}, 23);
    const PolygonMesh mr = to_mesh(r);
    EXPECT_TRUE(EdgesManifoldAndOriented(mr)) << f.transpose();
    EXPECT_NEAR(checks::reference_signed_volume(mr), v * f.prod(), 2 * snap_bound(e)) << f.transpose();
    EXPECT_TRUE((r - r).is_empty());
  }
}

// Re-quantized planes that met at a ring vertex (face planes, the ring plane, the axis planes
// through the vertex) leave edges shorter than the doubles' resolution; where such an edge has
// more than two faces, the sheets are paired by angles from the planes (no vertex positions).
TEST(Transform, RotatedAndScaledRingPrimitivesStayClosed) {
  const Solid solids[] = {sphere(1.0, {.segments = 16}), sphere(1.0, {.segments = 48}),
                          cylinder(1.0, 2.0, {.segments = 24}), sphere(1.0, {.segments = 32}) - box({0, 0, 0}, {1, 1, 1})};
  for (const Solid& s : solids) {
    const double v = double(checks::reference_signed_volume(to_mesh(s)));
    for (const double degrees : {7.0, 23.0, 41.0}) {
      const Eigen::Vector3d f(1.3, 0.7, 2.1);
      const Solid t = rotate(scale(s, f), {1, -2, 0.5}, degrees);
      const PolygonMesh m = to_mesh(t);
      EXPECT_TRUE(EdgesManifoldAndOriented(m)) << degrees;
      EXPECT_TRUE(checks::VerticesManifold(m)) << degrees;
      EXPECT_NEAR(checks::reference_signed_volume(m), v * f.prod(), 2 * snap_bound(t)) << degrees;
    }
  }
}

}  // namespace
}  // namespace sculpt
