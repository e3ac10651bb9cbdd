// extrude over convex and non-convex polygons: volume = area * height exactly, closed boundary,
// both orientations, and clear errors for crossing, degenerate and flat input. Twisted and scaled
// extrusions (OpenSCAD's linear_extrude): volumes against the frustum and pyramid formulas and
// against the divergence theorem on the triangle mesh the header describes, built here.
#include "bsp/extrude.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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

// ---- twist and scale ----

using Polygon = std::vector<Eigen::Vector2d>;

/// The volume of the linear extrusion's triangle mesh as extrude.hpp describes it (a
/// counter-clockwise polygon, layer k turned clockwise by twist * k / n and scaled by
/// (1 - k/n) + scale * k/n, each side quad split by a-b' for a positive twist, else b-a'),
/// by the divergence theorem on its triangles, without snapping: sum of det[a, b, c] / 6.
double reference_volume(const Polygon& polygon, double h, double twist, Eigen::Vector2d scale, int n) {
  std::vector<std::vector<Eigen::Vector3d>> layers;
  for (int k = 0; k <= n; ++k) {
    const double t = double(k) / n, angle = -twist * t * std::numbers::pi / 180;
    std::vector<Eigen::Vector3d> layer;
    for (const Eigen::Vector2d& p : polygon) {
      const double x = std::cos(angle) * p.x() - std::sin(angle) * p.y();
      const double y = std::sin(angle) * p.x() + std::cos(angle) * p.y();
      layer.emplace_back(((1 - t) + t * scale.x()) * x, ((1 - t) + t * scale.y()) * y, h * t);
    }
    layers.push_back(layer);
  }
  double six_v = 0;
  auto tri = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    six_v += a.dot(b.cross(c));
  };
  const std::size_t m = polygon.size();
  for (int k = 0; k < n; ++k)
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = (i + 1) % m;
      const auto &a = layers[k][i], &b = layers[k][j], &c = layers[k + 1][j], &d = layers[k + 1][i];
      if (twist > 0) {
        tri(a, b, c);
        tri(a, c, d);
      } else {
        tri(a, b, d);
        tri(b, c, d);
      }
    }
  for (std::size_t i = 1; i + 1 < m; ++i) {  // fans of the caps (the top may be a point)
    tri(layers[0][0], layers[0][i + 1], layers[0][i]);
    tri(layers[n][0], layers[n][i], layers[n][i + 1]);
  }
  return six_v / 6;
}

// A finer grid than the default (step 2^-22, range [-8, 8]): snapping moves volumes by < 1e-6.
const kernel::Grid kFine = kernel::Grid::from_shift(22);
const Polygon kSquare{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};  // area 4

TEST(Extrude, ATwistedSquareMatchesItsTriangleMeshAndConvergesToAreaTimesHeight) {
  const double h = 3, a = 4;
  double previous_error = 0;
  for (int slices : {18, 180}) {
    const Solid s = extrude(kSquare, 0, h, {.twist = 90, .slices = slices, .grid = kFine});
    const double expected = reference_volume(kSquare, h, 90, {1.0, 1.0}, slices);
    EXPECT_NEAR(volume(s), expected, 1e-6 * expected) << slices;
    // The sides bulge outwards: a little more than area * height, the excess first order in each
    // layer's turn (about 0.5 / slices here), so ten times the slices leave a tenth of it.
    const double error = (volume(s) - a * h) / (a * h);
    EXPECT_GT(error, 0) << slices;
    EXPECT_LT(error, 0.6 / slices) << slices;
    if (slices == 180) {
      EXPECT_LT(error, previous_error / 5);
    }
    previous_error = error;
    const PolygonMesh m = to_mesh(s);
    EXPECT_TRUE(EdgesManifoldAndOriented(m));
    EXPECT_TRUE(GenusIs(m, 0));
  }
  // The default slicing turns at most 5 degrees a layer: 18 layers for 90 degrees.
  EXPECT_EQ(default_slices(90), 18);
  EXPECT_EQ(default_slices(-360), 72);
  EXPECT_EQ(default_slices(0), 1);
  EXPECT_NEAR(volume(extrude(kSquare, 0, h, {.twist = 90, .grid = kFine})),
              reference_volume(kSquare, h, 90, {1.0, 1.0}, 18), 1e-5);
  // A negative twist splits by the other diagonal: the same volume by symmetry (mirror in x = 0).
  EXPECT_NEAR(volume(extrude(kSquare, 0, h, {.twist = -90, .slices = 18, .grid = kFine})),
              reference_volume(kSquare, h, -90, {1.0, 1.0}, 18), 1e-5);
}

TEST(Extrude, APositiveTwistTurnsClockwiseSeenFromAbove) {
  // A bar along +x from x = 1 to 2; turned by 90 degrees clockwise its top lies along -y.
  const Polygon bar{{1, -0.1}, {2, -0.1}, {2, 0.1}, {1, 0.1}};
  const Solid s = extrude(bar, 0, 1, {.twist = 90});
  EXPECT_EQ(classify(s, {0, -1.5, 0.99}).location, Location::Inside);
  EXPECT_EQ(classify(s, {0, 1.5, 0.99}).location, Location::Outside);
  EXPECT_EQ(classify(s, {1.5, 0, 0.01}).location, Location::Inside);
}

TEST(Extrude, AUniformScaleGivesAFrustumWithPlanarSides) {
  for (double k : {0.5, 2.0}) {
    const Solid s = extrude(kSquare, 0, 3, {.scale = {k, k}});
    EXPECT_NEAR(volume(s), 4 * 3 * (1 + k + k * k) / 3, 1e-9) << k;  // A h (1 + s + s^2) / 3
    EXPECT_EQ(to_mesh(s).faces.size(), 6u) << k;                     // trapezoids: one face each
  }
  // A general polygon (the U), scale 0.5 on the fine grid: still the frustum formula.
  const Polygon u{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};  // area 7
  EXPECT_NEAR(volume(extrude(u, 0, 2, {.scale = {0.5, 0.5}, .grid = kFine})), 7 * 2 * 1.75 / 3, 1e-5);
}

TEST(Extrude, ScaleByXAndY) {
  // An axis-aligned rectangle keeps rectangular sections: V = 4h (1 + (a + b)/2 + ab/3) with
  // a = sx - 1, b = sy - 1 (the integral of the section's area), 13 for [2, 0.5], h = 3.
  EXPECT_NEAR(volume(extrude(kSquare, 0, 3, {.scale = {2.0, 0.5}})), 13.0, 1e-9);
  // A triangle's slanted side is not planar then: two triangles, as the reference mesh says.
  const Polygon tri{{0, 0}, {2, 0}, {0, 2}};
  const Solid s = extrude(tri, 0, 1.5, {.scale = {2, 0.5}, .grid = kFine});
  const double expected = reference_volume(tri, 1.5, 0, {2.0, 0.5}, 1);
  EXPECT_NEAR(volume(s), expected, 1e-6 * expected);
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(s)));
}

TEST(Extrude, ScaleZeroEndsInAnApex) {
  const Solid pyramid = extrude(kSquare, 0, 3, {.scale = {0.0, 0.0}});
  EXPECT_NEAR(volume(pyramid), 4.0 * 3 / 3, 1e-9);  // A h / 3
  EXPECT_EQ(to_mesh(pyramid).vertices.size(), 5u);
  EXPECT_EQ(classify(pyramid, {0, 0, 3}).location, Location::Boundary);
  // Twisted to the apex: the reference mesh's volume.
  const Solid twisted = extrude(kSquare, 0, 3, {.twist = 120, .scale = {0.0, 0.0}, .grid = kFine});
  EXPECT_NEAR(volume(twisted), reference_volume(kSquare, 3, 120, {0.0, 0.0}, 24), 1e-5);
  EXPECT_TRUE(GenusIs(to_mesh(twisted), 0));
}

TEST(Extrude, DownwardsFromTheProfilesPlane) {
  const Solid up = extrude(kSquare, 1, 4, {.twist = 45, .scale = {0.5, 0.5}, .grid = kFine});
  const Solid down = extrude(kSquare, 1, -2, {.twist = 45, .scale = {0.5, 0.5}, .grid = kFine});
  EXPECT_NEAR(volume(down), volume(up), 1e-9);
  const Eigen::AlignedBox3d box = bounding_box(down);
  EXPECT_DOUBLE_EQ(box.min().z(), -2);
  EXPECT_DOUBLE_EQ(box.max().z(), 1);
  EXPECT_EQ(classify(down, {0.9, 0.9, 0.99}).location, Location::Inside);   // full size at z = 1
  EXPECT_EQ(classify(down, {0.9, 0.9, -1.9}).location, Location::Outside);  // half size at z = -2
}

TEST(Extrude, BadTwistsAndScalesAreRefused) {
  EXPECT_THROW((void)extrude(kSquare, 0, 1, {.scale = {-1.0, 1.0}}), InvalidInput);
  EXPECT_THROW((void)extrude(kSquare, 0, 1, {.scale = {1.0, 0.0}}), InvalidInput);
  EXPECT_THROW((void)extrude(kSquare, 0, 1, {.scale = {double(NAN), 1.0}}), InvalidInput);
  EXPECT_THROW((void)extrude(kSquare, 0, 1, {.twist = double(INFINITY)}), InvalidInput);
  EXPECT_THROW((void)extrude(kSquare, 0, 1, {.slices = -1}), InvalidInput);
  EXPECT_THROW((void)extrude(kSquare, 0, 0, {.twist = 10}), InvalidInput);
  // Half a turn in one layer: the sides cross on the axis; refused with the remedy.
  try {
    (void)extrude(kSquare, 0, 1, {.twist = 180, .slices = 1});
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("more slices"), std::string::npos) << e.what();
  }
  // The polygon's own crossing is still named as such.
  try {
    (void)extrude({{0, 0}, {2, 2}, {2, 0}, {0, 1}}, 0, 1, {.twist = 30});
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("crosses or touches itself"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sculpt
