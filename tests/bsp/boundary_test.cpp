#include "bsp/boundary.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include "base/errors.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "kernel/grid.hpp"
#include "support/bench_solids.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using checks::EdgesManifoldAndOriented;
using checks::GenusIs;
using checks::VolumeNear;

Solid menger_like_cross() {  // a cube with one tunnel: genus 1
  return box({0, 0, 0}, {3, 3, 3}) - box({1, -1, 1}, {2, 4, 2});
}

TEST(Boundary, MengerSpongeLevelsHaveExactVolumeAndGenus) {
  // Volume 20^level unit cells; genus of the level-k sponge surface: known 1-skeleton count.
  const int genus[] = {0, 5, 81, 1409};
  for (int level = 1; level <= 3; ++level) {
    const PolygonMesh m = to_mesh(checks::menger_sponge(level));
    EXPECT_TRUE(EdgesManifoldAndOriented(m)) << level;
    EXPECT_TRUE(VolumeNear(m, std::pow(20.0, level), 1e-13)) << level;
    EXPECT_TRUE(GenusIs(m, genus[level])) << level;
  }
}

TEST(Boundary, TriangulatedMeshesAreClosedWithTheSameVolume) {
  const Solid s = sphere(1.0, {.segments = 16}) - box({0, 0, 0}, {1, 1, 1});
  const PolygonMesh poly = to_mesh(s);
  const PolygonMesh tri = to_mesh(s, {.triangulate = true});
  for (const auto& f : tri.faces) ASSERT_EQ(f.size(), 3u);
  EXPECT_TRUE(EdgesManifoldAndOriented(tri));
  EXPECT_TRUE(GenusIs(tri, 0));
  EXPECT_TRUE(checks::NoDegenerateFaces(tri, 1e-12));
  EXPECT_NEAR(double(checks::reference_signed_volume(tri)), double(checks::reference_signed_volume(poly)), 1e-12);
  // Non-convex merged faces (an L-shaped union) triangulate too.
  const PolygonMesh l = to_mesh(box({0, 0, 0}, {2, 1, 1}) | box({0, 0, 0}, {1, 2, 1}), {.triangulate = true});
  EXPECT_TRUE(EdgesManifoldAndOriented(l));
  EXPECT_TRUE(VolumeNear(l, 3.0, 1e-15));
}

TEST(Boundary, NoDuplicateVerticesOnManifoldResults) {
  EXPECT_TRUE(checks::NoDuplicateVertices(to_mesh(sphere(1.0, {.segments = 32}) - box({0, 0, 0}, {1, 1, 1}))));
  const PolygonMesh u = to_mesh(box({0, 0, 0}, {1, 1, 1}) | box({1, 0, 0}, {2, 1, 1}));
  EXPECT_TRUE(checks::NoDuplicateVertices(u));
  EXPECT_EQ(u.vertices.size(), 8u);  // the shared face and its straight vertices disappear
  EXPECT_EQ(u.faces.size(), 6u);
}

TEST(Boundary, CoplanarFacesOfSeveralSolidsAtOnce) {
  // Three boxes whose top faces are coplanar, one of them nearly (one grid step lower).
  const double step = 1.0 / 32768;
  const Solid s = box({0, 0, 0}, {1, 1, 1}) | box({1, 0, 0}, {2, 1, 1}) | box({0, 1, 0}, {1, 2, 1 - step});
  const PolygonMesh m = to_mesh(s);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
  EXPECT_TRUE(GenusIs(m, 0));
  EXPECT_TRUE(VolumeNear(m, 3.0 - step, 1e-14));
}

// Area of the surface on each plane (unit normal and offset, rounded to 1e-9), from the faces'
// Newell normals: the same surface gives the same map however its planar regions are cut into faces.
std::map<std::array<long long, 4>, double> area_per_plane(const PolygonMesh& m) {
  std::map<std::array<long long, 4>, double> out;
  for (const auto& f : m.faces) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < f.size(); ++i)
      n += m.vertices[std::size_t(f[i])].cross(m.vertices[std::size_t(f[(i + 1) % f.size()])]);
    const double area = 0.5 * n.norm();
    n.normalize();
    const double d = n.dot(m.vertices[std::size_t(f[0])]);
    auto q = [](double x) { return std::llround(x * 1e9); };
    out[{q(n.x()), q(n.y()), q(n.z()), q(d)}] += area;
  }
  return out;
}

TEST(Boundary, RoundTripThroughAMeshKeepsVolumeAndSurface) {
  // Solids whose vertices are grid points: the round trip is exact. How a planar region is cut
  // into faces may change (it depends on the tree built from the mesh); the surface may not.
  const Solid l = box({0, 0, 0}, {3, 3, 3}) - box({1, 1, -1}, {2, 2, 4});
  for (const Solid& s : {l, rotate(l | box({2.5, 0, 0}, {4, 1, 1}), {0, 1, 0}, 90),
                         menger_like_cross(), box({0, 0, 0}, {1, 1, 1}) | box({1, 1, 0}, {2, 2, 1})}) {
    const PolygonMesh m1 = to_mesh(s);
    const Solid back = from_mesh(m1);
    const PolygonMesh m2 = to_mesh(back);
    EXPECT_TRUE(EdgesManifoldAndOriented(m2));
    EXPECT_EQ(double(checks::reference_signed_volume(m2)), double(checks::reference_signed_volume(m1)));
    const auto a1 = area_per_plane(m1), a2 = area_per_plane(m2);
    ASSERT_EQ(a1.size(), a2.size());
    for (auto i = a1.begin(), j = a2.begin(); i != a1.end(); ++i, ++j) {
      EXPECT_EQ(i->first, j->first);
      EXPECT_NEAR(i->second, j->second, 1e-12);
    }
    const PolygonMesh m3 = to_mesh(from_mesh(m2));
    EXPECT_TRUE(EdgesManifoldAndOriented(m3));
    EXPECT_EQ(double(checks::reference_signed_volume(m3)), double(checks::reference_signed_volume(m1)));
  }
}

TEST(Boundary, RoundTripOfCurvedSolidsKeepsTheVolumeUpToTheGrid) {
  // Vertices of curved solids are not grid points: from_mesh snaps them (docs/kernel.md), so
  // the volume changes by about area * grid step, and non-planar faces become triangles.
  // Non-convex faces whose largest corner is reflex (the caps of a cylinder minus a quarter
  // box) once got an inward plane; sphere(24) - cube was wrong by orders of magnitude for that.
  for (const Solid& s : {sphere(1.0, {.segments = 24}),
                         cylinder(0.5, 2.0, {.segments = 16}) | box({-1, -0.25, 0.5}, {1, 0.25, 1}),
                         cylinder(1.0, 2.0, {.segments = 16}) - box({0, 0, 0}, {1, 1, 3}),
                         sphere(1.0, {.segments = 24}) - box({0, 0, 0}, {1, 1, 1}),
                         sphere(1.0, {.segments = 32}) - box({0.1, 0.1, 0.1}, {1, 1, 1})}) {
    const PolygonMesh m1 = to_mesh(s);
    const PolygonMesh m2 = to_mesh(from_mesh(m1));
    EXPECT_TRUE(EdgesManifoldAndOriented(m2));
    EXPECT_TRUE(GenusIs(m2, 0));
    EXPECT_NEAR(double(checks::reference_signed_volume(m2)), double(checks::reference_signed_volume(m1)),
                surface_area(s) * kernel::kGridStep);
  }
}

TEST(Boundary, FromMeshRejectsAMeshThatFoldsWhenSnapped) {
  // A sliver tetrahedron whose base triangle a, b, c turns over when snapped to the grid:
  // c lies 0.29 steps above the line ab, but after snapping it lies half a step below it.
  const double s = kernel::kGridStep;
  PolygonMesh m;
  m.vertices = {{0, 0.51 * s, 0}, {1, -0.49 * s, 0}, {0.5, 0.3 * s, 0}, {0.5, 0, 1}};
  // Base a, c, b seen from below (outward normal -z), sides outward.
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  EXPECT_GT(checks::reference_signed_volume(m), 0);
  try {
    (void)from_mesh(m);
    ADD_FAILURE() << "expected GeometryError";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("folds when its vertices are snapped"), std::string::npos) << e.what();
  }
}

// Inner ring planes and axial planes of a solid of revolution are auxiliary (they carry no face,
// so boundary extraction skips them). A box face on the same plane as a ring must still appear:
// the merge hands the face over to the ring node and clears its mark. Both merge directions
// (the sphere's tree larger, then the boxes' tree larger) and the complement.
TEST(Boundary, FaceOnAnAuxiliaryRingPlaneIsKept) {
  constexpr int kSegments = 16;
  const int rings = (kSegments + 1) / 2;
  for (int k : {2, 4, 5}) {  // ring heights as in primitives.cpp (snapped by box() as well)
    const double z = std::cos((k + 0.5) * std::numbers::pi / rings);
    const Solid s = sphere(1.0, {.segments = kSegments});
    const Solid below = box({-2, -2, -2}, {2, 2, z});
    const double v_below = 16.0 * (kernel::snap(z) * kernel::kGridStep + 2.0);
    const double cap = volume(s & box({-2, -2, z}, {2, 2, 2}));  // the sphere above the ring
    ASSERT_GT(cap, 0.0);
    for (const Solid& u : {s | below, below | s}) {
      const PolygonMesh m = to_mesh(u);
      EXPECT_TRUE(EdgesManifoldAndOriented(m)) << k;
      EXPECT_TRUE(GenusIs(m, 0)) << k;
      EXPECT_NEAR(double(checks::reference_signed_volume(m)), v_below + cap, 1e-9) << k;
    }
    // The boxes' tree larger than the sphere's: many small boxes stacked under the ring plane.
    Solid stack = box({-2, -2, z - 0.25}, {2, 2, z});
    for (int i = 0; i < 40; ++i) stack = std::move(stack) | box({-2 + 0.1 * i, -2, z - 0.5}, {-1.95 + 0.1 * i, 2, z - 0.2});
    const Solid small = sphere(1.0, {.segments = 8});
    const int small_rings = 4;
    const double zs = std::cos((k % small_rings + 0.5) * std::numbers::pi / small_rings);
    Solid stack2 = box({-2, -2, zs - 0.25}, {2, 2, zs});
    for (int i = 0; i < 40; ++i) stack2 = std::move(stack2) | box({-2 + 0.1 * i, -2, zs - 0.5}, {-1.95 + 0.1 * i, 2, zs - 0.2});
    ASSERT_GT(stack2.nodes().size(), small.nodes().size());
    const Solid u2 = stack2 | small;
    const PolygonMesh m2 = to_mesh(u2);
    EXPECT_TRUE(EdgesManifoldAndOriented(m2)) << k;
    EXPECT_NEAR(double(checks::reference_signed_volume(m2)),
                volume(stack2) + volume(small) - volume(stack2 & small), 1e-9) << k;
    const PolygonMesh mc = to_mesh(complement(complement(s) & complement(below)));
    EXPECT_TRUE(EdgesManifoldAndOriented(mc)) << k;
    EXPECT_NEAR(double(checks::reference_signed_volume(mc)), v_below + cap, 1e-9) << k;
    (void)stack;
  }
}

TEST(Boundary, MeasuresOfABox) {
  const Solid b = box({0, 0, 0}, {1, 2, 3});
  EXPECT_DOUBLE_EQ(volume(b), 6.0);
  EXPECT_DOUBLE_EQ(surface_area(b), 22.0);
  EXPECT_EQ(volume(Solid()), 0.0);
  EXPECT_TRUE(bounding_box(Solid()).isEmpty());
}

// The screen's boundary (MeshOptions::approximate) against the exact boundary with every vertex
// correctly rounded: the same faces on the same vertices, each vertex within 2^-20 grid steps of
// the rounded one (plus the rounding's half unit in the last place). The fine sphere has corners
// near its poles whose approximations are looser than that: they must be rounded.
TEST(Boundary, ApproximateCoordinatesForAScreenStayWithinTheirBound) {
  const Solid ball = sphere(1.0, {.segments = 256});
  const Solid turned = transform(box({0, 0, 0}, {1, 2, 3}),
                                 Eigen::Affine3d(Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized())));
  const Solid cases[] = {ball, ball - translate(sphere(1.0, {.segments = 96}), {0.3, 0.2, 0.1}),
                         turned | box({0.5, 0.5, 0.5}, {2, 2, 2})};
  for (std::size_t k = 0; k < std::size(cases); ++k) {
    const PolygonMesh exact = to_mesh(cases[k], {.clean = false});
    const PolygonMesh screen = to_mesh(cases[k], {.clean = false, .approximate = true});
    ASSERT_EQ(screen.faces, exact.faces) << k;
    ASSERT_EQ(screen.vertices.size(), exact.vertices.size()) << k;
    const double step = cases[k].grid().step();
    double worst = 0;
    std::size_t moved = 0;
    for (std::size_t v = 0; v < exact.vertices.size(); ++v) {
      const Eigen::Vector3d d = (screen.vertices[v] - exact.vertices[v]).cwiseAbs();
      const double allowed = std::ldexp(step, -20) + std::ldexp(exact.vertices[v].cwiseAbs().maxCoeff(), -52);
      worst = std::max(worst, d.maxCoeff() / allowed);
      if (d.maxCoeff() > 0) ++moved;
    }
    EXPECT_LE(worst, 1.0) << k;
    if (k < 2) {  // the approximations are used
      EXPECT_GT(moved, exact.vertices.size() / 2) << k;
    }
  }
}

}  // namespace
}  // namespace sculpt
