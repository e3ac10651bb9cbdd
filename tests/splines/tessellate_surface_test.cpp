// Triangle meshes of B-spline surfaces (tessellate_surface.hpp): chord error against the
// tolerance, a closed mesh for a surface closed both ways, exact area of a flat patch.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <map>
#include <utility>

#include "base/errors.hpp"
#include "splines/tessellate_surface.hpp"
#include "surface_shapes.hpp"
#include "test_names.hpp"

namespace {


TEST(TessellateSurface, ChordErrorStaysWithinTheTolerance) {
  const BSplineSurface s = paraboloid();
  for (double tol : {1e-1, 1e-2, 1e-3}) {
    const SurfaceTriangles m = tessellate(s, {.tolerance = tol});
    EXPECT_LE(m.error_bound, tol * (1 + 1e-12));
    double worst = 0;
    for (const auto& t : m.triangles) {
      // The surface at points inside the triangle's parameter triangle against the linear interpolant.
      for (const auto& w : {V(1.0 / 3, 1.0 / 3, 1.0 / 3), V(0.5, 0.5, 0), V(0, 0.5, 0.5), V(0.5, 0, 0.5)}) {
        const Eigen::Vector2d uv = w[0] * m.parameters[t[0]] + w[1] * m.parameters[t[1]] + w[2] * m.parameters[t[2]];
        const V lin = w[0] * m.points[t[0]] + w[1] * m.points[t[1]] + w[2] * m.points[t[2]];
        worst = std::max(worst, (s.point(uv[0], uv[1]) - lin).norm());
      }
    }
    EXPECT_LE(worst, tol);
    EXPECT_GT(worst, 0.05 * tol);  // not absurdly finer than asked
  }
}

TEST(TessellateSurface, SurfaceClosedBothWaysGivesAClosedMesh) {
  std::vector<V> P;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 6; ++j) {
      const double a = 2 * kPi * i / 8, b = 2 * kPi * j / 6;
      P.emplace_back((3 + std::cos(b)) * std::cos(a), (3 + std::cos(b)) * std::sin(a), std::sin(b));
    }
  const SurfaceTriangles m = tessellate(BSplineSurface::uniform({3, 3}, 8, 6, P, {true, true}), {.tolerance = 1e-2});
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  // Every directed edge once and its reverse once: closed and consistently oriented.
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(directed.count({e.second, e.first}), 1u);
  }
  // A torus: V - E + F = 0.
  const long long V_ = static_cast<long long>(m.points.size()), F = static_cast<long long>(m.triangles.size()),
                  E = static_cast<long long>(directed.size()) / 2;
  EXPECT_EQ(V_ - E + F, 0);
}

TEST(TessellateSurface, FlatPatchAreaIsExact) {
  // A planar bilinear patch that is a parallelogram: its area is |e1 x e2|, and a planar mesh of it has the same area.
  const V o(1, 2, 3), e1(2, 0.5, 0), e2(-0.3, 1.5, 0.4);
  std::vector<V> P;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j) P.push_back(o + (i / 4.0) * e1 + (j / 3.0) * e2);
  const SurfaceTriangles m = tessellate(BSplineSurface::uniform({1, 1}, 5, 4, P), {.tolerance = 1e-3});
  double area = 0;
  for (const auto& t : m.triangles) area += 0.5 * (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]).norm();
  EXPECT_NEAR(area, e1.cross(e2).norm(), 1e-12);
  EXPECT_THROW((void)tessellate(paraboloid(), {.tolerance = 0}), InvalidInput);
  EXPECT_THROW((void)tessellate(paraboloid(), {.tolerance = 1e-3, .max_cells = 0}), InvalidInput);
}

}  // namespace
