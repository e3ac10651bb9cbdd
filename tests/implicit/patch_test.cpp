// Surface patches (Ihm & Naylor sec. 5.2): residuals of every vertex, the mesh invariants
// (4^d triangles, crack-free, consistently oriented, boundary exactly on the clipping planes),
// convergence of the sphere octant's area to pi/2 and of the triangle centres to the surface,
// Fig. 9's quartic patch at d = 3, patches sharing a boundary curve, and the errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include "implicit/detail/plane_curve.hpp"
#include "implicit/patch.hpp"
#include "implicit/patch_testing.hpp"

namespace sculpt::implicit {
namespace {

using Vec = Eigen::Vector3d;
using testing::distance_to_surface;
using testing::normalized_residual;

double corner_scale(const std::array<Vec, 3>& corners) {
  Eigen::AlignedBox3d box;
  for (const Vec& p : corners) box.extend(p);
  return box.diagonal().norm();
}

double triangle_area(const PolygonMesh& m, const std::vector<int>& f) {
  return 0.5 * (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]).norm();
}

Vec centroid(const PolygonMesh& m, const std::vector<int>& f) {
  return (m.vertices[f[0]] + m.vertices[f[1]] + m.vertices[f[2]]) / 3.0;
}

// Checks the mesh invariants of a patch of depth d, independently of how it was built.
void expect_valid_patch(const Expression& f, const PatchResult& r, const std::array<Vec, 3>& corners, int d) {
  const PolygonMesh& m = r.mesh;
  const double scale = corner_scale(corners);
  ASSERT_EQ(m.faces.size(), static_cast<std::size_t>(1) << (2 * d));  // 4^d
  // Every vertex on the surface to Newton accuracy; no vertex twice.
  for (const Vec& p : m.vertices) EXPECT_LE(normalized_residual(f, p), 1e-12 * scale) << p.transpose();
  std::set<std::array<double, 3>> distinct;
  for (const Vec& p : m.vertices) distinct.insert({p.x(), p.y(), p.z()});
  EXPECT_EQ(distinct.size(), m.vertices.size());
  // Directed edges: each at most once (consistent orientation); undirected: two triangles for an
  // interior edge, one for a boundary edge.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& face : m.faces) {
    ASSERT_EQ(face.size(), 3u);
    EXPECT_GT(triangle_area(m, face), 0.0);
    for (int k = 0; k < 3; ++k) ++directed[{face[k], face[(k + 1) % 3]}];
  }
  std::set<std::pair<int, int>> boundary_edges;
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "directed edge " << edge.first << "-" << edge.second << " used twice";
    if (!directed.contains({edge.second, edge.first})) boundary_edges.insert(std::minmax(edge.first, edge.second));
  }
  // The boundary edges are exactly the consecutive pairs of the three boundary chains, which
  // run corner to corner, and every boundary vertex lies on its clipping plane.
  std::set<std::pair<int, int>> chain_edges;
  for (int i = 0; i < 3; ++i) {
    const std::vector<int>& chain = r.boundary[i];
    ASSERT_GE(chain.size(), 2u);
    EXPECT_EQ(chain.front(), i);
    EXPECT_EQ(chain.back(), (i + 1) % 3);
    EXPECT_EQ(chain.size(), (static_cast<std::size_t>(1) << d) + 1);
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) chain_edges.insert(std::minmax(chain[k], chain[k + 1]));
    const PatchPlane& h = r.planes[i];
    for (const int v : chain) EXPECT_LE(std::abs(h.normal.dot(m.vertices[v]) - h.offset), 1e-15 * scale);
  }
  EXPECT_EQ(boundary_edges, chain_edges);
  // Corners: vertices 0, 1, 2.
  for (int i = 0; i < 3; ++i) EXPECT_LE((m.vertices[i] - corners[i]).norm(), 1e-6 * scale);
  // Faces turn their normals to where grad f points.
  for (const auto& face : m.faces) {
    const Vec n = (m.vertices[face[1]] - m.vertices[face[0]]).cross(m.vertices[face[2]] - m.vertices[face[0]]);
    EXPECT_GT(n.dot(f.value_gradient(centroid(m, face)).gradient), 0.0);
  }
}

TEST(PlaneCurve, QuarterCircleLiesExactlyOnItsCoordinatePlane) {
  const Expression f = testing::unit_sphere();
  const auto plane = detail::PlaneFrame::make(Vec::UnitZ(), 0.0);
  const auto c = detail::trace_on_plane(f, plane, Vec::UnitX(), Vec::UnitY(),
                                        {.tolerance = 1e-4, .max_step = 0.05, .residual_target = 1e-13,
                                         .box = {.lo = Vec::Constant(-2), .hi = Vec::Constant(2)}});
  ASSERT_EQ(c.end, detail::PlaneCurveEnd::Reached);
  EXPECT_EQ(c.points.front(), Vec::UnitX());
  EXPECT_EQ(c.points.back(), Vec::UnitY());
  EXPECT_GE(c.points.size(), 32u);  // length pi/2 at steps of at most 0.05
  for (const Vec& p : c.points) {
    EXPECT_EQ(p.z(), 0.0);
    EXPECT_NEAR(p.norm(), 1.0, 1e-12);
    EXPECT_GE(p.x(), 0.0);
    EXPECT_GE(p.y(), 0.0);
  }
}

TEST(PlaneCurve, GeneralPlaneFrameIsOrthonormal) {
  const Vec n = Vec(1, 2, 3).normalized();
  const auto plane = detail::PlaneFrame::make(n, 0.5);
  EXPECT_NEAR(plane.e1.dot(plane.e2), 0.0, 1e-15);
  EXPECT_NEAR(plane.e1.dot(n), 0.0, 1e-15);
  EXPECT_NEAR(plane.e1.norm(), 1.0, 1e-15);
  EXPECT_NEAR(n.dot(plane.at({0.3, -0.7})), 0.5, 1e-15);
}

TEST(Patch, SphereOctantIsValidAtEveryDepth) {
  const Expression f = testing::unit_sphere();
  const auto corners = testing::sphere_octant_corners();
  for (int d = 0; d <= 5; ++d) {
    SCOPED_TRACE("depth " + std::to_string(d));
    const PatchResult r = patch(f, {.corners = corners, .depth = d});
    expect_valid_patch(f, r, corners, d);
    EXPECT_FALSE(r.flipped);
    // The octant: every vertex has coordinates >= 0, and the boundary vertices have exact zeros.
    for (const Vec& p : r.mesh.vertices) EXPECT_TRUE((p.array() >= 0.0).all()) << p.transpose();
    for (const int v : r.boundary[0]) EXPECT_EQ(r.mesh.vertices[v].z(), 0.0);
    for (const int v : r.boundary[1]) EXPECT_EQ(r.mesh.vertices[v].x(), 0.0);
    for (const int v : r.boundary[2]) EXPECT_EQ(r.mesh.vertices[v].y(), 0.0);
    EXPECT_EQ(r.planes[0].normal, Vec::UnitZ());
  }
}

TEST(Patch, SphereOctantAreaConvergesToHalfPi) {
  const Expression f = testing::unit_sphere();
  double previous = 1.0;
  for (int d = 1; d <= 6; ++d) {
    const PatchResult r = patch(f, {.corners = testing::sphere_octant_corners(), .depth = d});
    double area = 0.0;
    for (const auto& face : r.mesh.faces) area += triangle_area(r.mesh, face);
    const double error = std::numbers::pi / 2 - area;
    EXPECT_GT(error, 0.0);  // an inscribed polyhedron has less area
    EXPECT_LT(error, 0.5 * previous) << "depth " << d;  // about 1/4 per level (second order)
    previous = error;
  }
  EXPECT_LT(previous / (std::numbers::pi / 2), 1e-3);
}

TEST(Patch, TriangleCentresApproachTheSurface) {
  for (const bool sphere : {true, false}) {
    const Expression f = sphere ? testing::unit_sphere() : testing::fig9_quartic();
    const auto corners = sphere ? testing::sphere_octant_corners() : testing::fig9_octant_corners();
    double previous = 1.0;
    for (int d = 0; d <= 5; ++d) {
      const PatchResult r = patch(f, {.corners = corners, .depth = d});
      double worst = 0.0;
      for (const auto& face : r.mesh.faces) {
        const Vec c = centroid(r.mesh, face);
        worst = std::max(worst, sphere ? 1.0 - c.norm() : distance_to_surface(f, c));
      }
      EXPECT_LT(worst, 0.5 * previous) << (sphere ? "sphere" : "fig9") << " depth " << d;
      previous = worst;
    }
    EXPECT_LT(previous, 2e-3 * corner_scale(corners));
  }
}

TEST(Patch, Fig9QuarticPatchAtDepth3) {
  const Expression f = testing::fig9_quartic();
  const auto corners = testing::fig9_octant_corners();
  for (const Vec& p : corners) EXPECT_LE(normalized_residual(f, p), 1e-15);
  const PatchResult r = patch(f, {.corners = corners, .depth = 3});
  expect_valid_patch(f, r, corners, 3);
  EXPECT_EQ(r.mesh.faces.size(), 64u);
  EXPECT_EQ(r.mesh.vertices.size(), 45u);  // (2^d + 1)(2^d + 2) / 2
  // The boundary curves lie on the coordinate planes z = 0, x = 0, y = 0, exactly.
  EXPECT_EQ(r.planes[0].normal, Vec::UnitZ());
  EXPECT_EQ(r.planes[1].normal, Vec::UnitX());
  EXPECT_EQ(r.planes[2].normal, Vec::UnitY());
  for (const int v : r.boundary[0]) EXPECT_EQ(r.mesh.vertices[v].z(), 0.0);
  for (const int v : r.boundary[1]) EXPECT_EQ(r.mesh.vertices[v].x(), 0.0);
  for (const int v : r.boundary[2]) EXPECT_EQ(r.mesh.vertices[v].y(), 0.0);
}

TEST(Patch, ThePapersIterHeuristicGivesValidPatchesToo) {
  const Expression f = testing::fig9_quartic();
  const auto corners = testing::fig9_octant_corners();
  for (int d = 0; d <= 5; ++d) {
    SCOPED_TRACE("depth " + std::to_string(d));
    expect_valid_patch(f, patch(f, {.corners = corners, .depth = d, .method = curves::Method::Iter}), corners, d);
  }
}

TEST(Patch, ReversedCornersGiveTheSameSurfaceWithTheSameOrientation) {
  const Expression f = testing::fig9_quartic();
  auto corners = testing::fig9_octant_corners();
  std::swap(corners[1], corners[2]);
  const PatchResult r = patch(f, {.corners = corners, .depth = 2});
  EXPECT_TRUE(r.flipped);
  expect_valid_patch(f, r, corners, 2);
}

TEST(Patch, NeighbouringPatchesShareTheirBoundaryVerticesBitForBit) {
  // The octants z >= 0 and z <= 0 share the quarter circle from (1,0,0) to (0,1,0) in z = 0.
  const Expression f = testing::unit_sphere();
  const PatchResult upper = patch(f, {.corners = {Vec::UnitX(), Vec::UnitY(), Vec::UnitZ()}, .depth = 4});
  const PatchResult lower = patch(f, {.corners = {Vec::UnitY(), Vec::UnitX(), -Vec::UnitZ()}, .depth = 4});
  std::vector<Vec> a, b;
  for (const int v : upper.boundary[0]) a.push_back(upper.mesh.vertices[v]);
  for (const int v : lower.boundary[0]) b.push_back(lower.mesh.vertices[v]);
  std::reverse(b.begin(), b.end());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k], b[k]) << k;
  for (const Vec& p : lower.mesh.vertices) EXPECT_LE(p.z(), 0.0);
}

TEST(Patch, ExplicitPlanesAndCornerProjection) {
  const Expression f = testing::unit_sphere();
  // Corners off the sphere by 1e-8 are moved onto it (and onto their coordinate planes).
  const std::array<Vec, 3> near{Vec(1 + 1e-8, 0, 0), Vec(0, 1 - 1e-8, 0), Vec(0, 0, 1 + 1e-8)};
  const PatchResult r = patch(f, {.corners = near,
                                  .depth = 2,
                                  .planes = std::array<PatchPlane, 3>{PatchPlane{Vec(0, 0, -2), 0.0},
                                                                      PatchPlane{Vec(3, 0, 0), 0.0},
                                                                      PatchPlane{Vec(0, 1, 0), 0.0}},
                                  .corner_tolerance = 1e-6});
  expect_valid_patch(f, r, near, 2);
  EXPECT_EQ(r.mesh.vertices[0], Vec::UnitX());
  EXPECT_EQ(r.planes[0].normal, Vec::UnitZ());  // canonical: unit, first non-zero component > 0
}

TEST(PatchErrors, DepthOutOfRange) {
  const Expression f = testing::unit_sphere();
  EXPECT_THROW((void)patch(f, {.corners = testing::sphere_octant_corners(), .depth = -1}), InvalidInput);
  EXPECT_THROW((void)patch(f, {.corners = testing::sphere_octant_corners(), .depth = 9}), InvalidInput);
}

TEST(PatchErrors, CornerOffTheSurfaceIsNamed) {
  const Expression f = testing::unit_sphere();
  try {
    (void)patch(f, {.corners = {Vec::UnitX(), Vec(0, 1.1, 0), Vec::UnitZ()}, .depth = 1});
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("corner P1"), std::string::npos) << message;
    EXPECT_NE(message.find("|f|/|grad f| = 0.0955"), std::string::npos) << message;
  }
}

TEST(PatchErrors, BadOptions) {
  const Expression f = testing::unit_sphere();
  const auto c = testing::sphere_octant_corners();
  EXPECT_THROW((void)patch(f, {.corners = {c[0], c[0], c[2]}}), InvalidInput);
  EXPECT_THROW((void)patch(f, {.corners = {c[0], Vec(0, NAN, 0), c[2]}}), InvalidInput);
  EXPECT_THROW((void)patch(f, {.corners = c, .tolerance = -1.0}), InvalidInput);
  EXPECT_THROW((void)patch(f, {.corners = c, .points_per_segment = 1}), InvalidInput);
  EXPECT_THROW((void)patch(f, {.corners = c, .method = curves::Method::MinCount}), InvalidInput);
  EXPECT_THROW((void)patch(f, {.corners = c, .max_steps = 0}), InvalidInput);
  // A plane that misses its corners.
  EXPECT_THROW((void)patch(f, {.corners = c,
                               .planes = std::array<PatchPlane, 3>{PatchPlane{Vec::UnitZ(), 0.5},
                                                                   PatchPlane{Vec::UnitX(), 0.0},
                                                                   PatchPlane{Vec::UnitY(), 0.0}}}),
               InvalidInput);
}

TEST(PatchErrors, BoundaryCurveThatDoesNotConnectItsCorners) {
  // Two unit spheres, at 0 and at (3, 0, 0): the circle of the first in z = 0 never reaches the
  // corner (3, 1, 0) on the second.
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y(), z = b.z();
  const Term yz = b.add(b.pow(y, 2), b.pow(z, 2));
  const Term first = b.sub(b.add(b.pow(x, 2), yz), b.constant(1));
  const Term second = b.sub(b.add(b.pow(b.sub(x, b.constant(3)), 2), yz), b.constant(1));
  const Expression f = b.finish(b.min(first, second));
  try {
    (void)patch(f, {.corners = {Vec(0, 1, 0), Vec(3, 1, 0), Vec(0, 0, 1)}, .depth = 2});
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("boundary curve"), std::string::npos) << message;
    EXPECT_NE(message.find("does not connect"), std::string::npos) << message;
  }
}

TEST(PatchErrors, StepBudget) {
  const Expression f = testing::unit_sphere();
  EXPECT_THROW((void)patch(f, {.corners = testing::sphere_octant_corners(), .depth = 3, .max_steps = 20}),
               GeometryError);
}

TEST(PatchErrors, NonFiniteFunction) {
  // sqrt(x) has an infinite derivative at x = 0, where corner P1 lies.
  ExpressionBuilder b;
  const Term x = b.x();
  const Term sphere = b.sub(b.add(b.add(b.pow(x, 2), b.pow(b.y(), 2)), b.pow(b.z(), 2)), b.constant(1));
  const Expression f = b.finish(b.add(sphere, b.mul(b.constant(0.0), b.sqrt(x))));
  EXPECT_THROW((void)patch(f, {.corners = testing::sphere_octant_corners(), .depth = 1}), NonFiniteValue);
}

}  // namespace
}  // namespace sculpt::implicit
