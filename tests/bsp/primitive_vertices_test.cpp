// Primitives' vertices (docs/kernel.md, "Primitives' vertices"; issue 35, "flush stays flush"): a
// cylinder's and a cone's vertices are the grid points nearest to where the user's numbers put them,
// so a vertex on a box face stays on it exactly, and the result's boundary reads back from every
// text and binary format as the same solid.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/primitives.hpp"
#include "bsp/rebuild.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_validation.hpp"

namespace sculpt {
namespace {

constexpr double kUnit = 32768;  // grid units per world unit at the default grid (step 2^-15)

// The grid point nearest to v (the default grid; no ties among the values used here).
double snapped(double v) { return std::round(v * kUnit) / kUnit; }

bool on_grid(const Eigen::Vector3d& p) {
  for (int k = 0; k < 3; ++k)
    if (p[k] * kUnit != std::round(p[k] * kUnit)) return false;
  return true;
}

TEST(PrimitiveVertices, CylinderAndConeVerticesAreGridPoints) {
  for (int n : {3, 5, 8, 24, 100}) {
    for (const Solid& s : {cylinder(5, 40, {.segments = n}), cylinder(0.3, 1, {.segments = n, .center = true}),
                           cone(2.5, 3, {.segments = n})}) {
      const PolygonMesh m = to_mesh(s, {.clean = false});
      ASSERT_FALSE(m.vertices.empty());
      for (const Eigen::Vector3d& v : m.vertices) EXPECT_TRUE(on_grid(v)) << n << ": " << v.transpose();
    }
  }
  // The vertices are exactly the snapped circle points (n = 8, radius 5: vertex 3 is at 135 degrees).
  const PolygonMesh m = to_mesh(cylinder(5, 40, {.segments = 8}), {.clean = false});
  const Eigen::Vector3d want(snapped(5 * std::cos(3 * std::numbers::pi / 4)),
                             snapped(5 * std::sin(3 * std::numbers::pi / 4)), 40);
  bool found = false;
  for (const Eigen::Vector3d& v : m.vertices) found = found || v == want;
  EXPECT_TRUE(found);
}

TEST(PrimitiveVertices, FrustumKeepsItsLargerRingOnTheGrid) {
  const PolygonMesh m = to_mesh(cone(2, 1, {.segments = 7, .top_radius = 1.3}), {.clean = false});
  int bottom = 0;
  for (const Eigen::Vector3d& v : m.vertices)
    if (v.z() == 0) {
      EXPECT_TRUE(on_grid(v)) << v.transpose();
      ++bottom;
    }
  EXPECT_EQ(bottom, 7);
}

// Encodes and decodes `mesh` in the text formats and binary PLY and STL, and makes a solid of it:
// its volume is `want_volume` within `tolerance`. Vertices on grid points read back exactly (float32
// of binary STL is within a grid step of them: from_mesh snaps it back).
void expect_reads_back(const PolygonMesh& mesh, double want_volume, double tolerance, const std::string& what) {
  struct Format {
    MeshFormat format;
    bool binary;
  };
  for (const Format f :
       {Format{MeshFormat::Off, false}, Format{MeshFormat::Obj, false}, Format{MeshFormat::Ply, false},
        Format{MeshFormat::Stl, false}, Format{MeshFormat::Ply, true}, Format{MeshFormat::Stl, true}}) {
    const PolygonMesh back = decode_mesh(encode_mesh(mesh, f.format, f.binary), f.format, what);
    Solid solid;
    ASSERT_NO_THROW(solid = from_mesh(back)) << what << " format " << int(f.format) << (f.binary ? " binary" : "");
    EXPECT_NEAR(volume(solid), want_volume, tolerance)
        << what << " format " << int(f.format) << (f.binary ? " binary" : "");
  }
}

// Issue 35's example: the cylinder's vertex at 180 degrees lies on the box face x = 5.
TEST(PrimitiveVertices, CylinderVertexOnABoxFaceStaysFlush) {
  const Solid f = box({5, 5, 0}, {10, 10, 40}) - translate(cylinder(5, 40, {.segments = 8}), {10, 10, 0});
  const PolygonMesh mesh = to_mesh(f);
  int at_five = 0;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    EXPECT_FALSE(v.x() > 5 && v.x() < 5.001) << v.transpose();  // no sliver beside the face
    at_five += v.x() == 5 && v.y() == 10;
  }
  EXPECT_EQ(at_five, 2);  // the vertex at z = 0 and z = 40
  expect_reads_back(mesh, volume(f), 1e-12, "box minus cylinder");
  EXPECT_NEAR(volume(rebuild_from_boundary(f)), volume(f), 1e-12);
}

TEST(PrimitiveVertices, ConeVertexOnABoxFaceStaysFlush) {
  // The cone's base vertex at angle 0 is (3, 0, 0) + (1, 0, 0): on the box face x = 4.
  const Solid c = translate(cone(3, 2, {.segments = 6}), {1, 0, 0});
  const Solid u = unite(box({4, -1, 0}, {6, 1, 1}), c);
  const PolygonMesh mesh = to_mesh(u);
  // No sliver beside the face. The cone's vertex touches the box's face: the face has a copy of it
  // as a corner, which the clean output moves into the box by the smallest step that keeps the
  // copies apart (docs/kernel.md, "Clean output"): a unit in the last place, not a sliver.
  for (const Eigen::Vector3d& v : mesh.vertices)
    EXPECT_FALSE(v.x() > std::nextafter(4.0, 5.0) && v.x() < 4.001) << v.transpose();
  expect_reads_back(mesh, volume(u), 1e-12, "cone and box");
  const Solid d = box({-3, -3, 0}, {4, 3, 2}) - c;
  expect_reads_back(to_mesh(d), volume(d), 1e-12, "box minus cone");
}

// The volume of sphere(r, n) by its definition (primitives.hpp): OpenSCAD's rings of regular
// n-gons at polar angles (k + 0.5) pi / rings, at the grid heights nearest, a vertex at each pole;
// frusta between the rings and a pyramid at each end.
double sphere_polyhedron_volume(double r, int n) {
  const int rings = (n + 1) / 2;
  const double gon = 0.5 * n * std::sin(2 * std::numbers::pi / n);  // area of the n-gon of circumradius 1
  std::vector<std::pair<double, double>> z_area{{-r, 0.0}};
  for (int k = rings - 1; k >= 0; --k) {
    const double phi = (k + 0.5) * std::numbers::pi / rings;
    z_area.emplace_back(snapped(r * std::cos(phi)), gon * std::pow(r * std::sin(phi), 2));
  }
  z_area.emplace_back(r, 0.0);
  double v = 0;
  for (std::size_t k = 0; k + 1 < z_area.size(); ++k) {
    const auto [z0, a0] = z_area[k];
    const auto [z1, a1] = z_area[k + 1];
    v += (z1 - z0) / 3 * (a0 + a1 + std::sqrt(a0 * a1));
  }
  return v;
}

TEST(PrimitiveVertices, SpherePoleOnAPlaneStaysFlush) {
  for (const int n : {8, 16, 33}) {
    const Solid s = sphere(1, {.segments = n});
    // Its volume by definition (ring vertices within about 2^-24 of the ideal polygons').
    EXPECT_NEAR(volume(s), sphere_polyhedron_volume(1, n), 1e-6) << n;
    // One vertex at each pole, exactly.
    int top = 0, bottom = 0;
    for (const Eigen::Vector3d& v : to_mesh(s).vertices) {
      EXPECT_LE(std::fabs(v.z()), 1.0);
      top += v == Eigen::Vector3d(0, 0, 1);
      bottom += v == Eigen::Vector3d(0, 0, -1);
    }
    EXPECT_EQ(top, 1) << n;
    EXPECT_EQ(bottom, 1) << n;
    // Centred r above a plate's top face, it touches the face: sunk by one grid step it overlaps
    // the plate, raised by one step it does not (OpenSCAD's flat caps left a gap of r (1 - cos(pi /
    // (2 rings))), 0.02 at n = 16).
    const Solid plate = box({-2, -2, -1}, {2, 2, 0});
    const double step = 1 / kUnit;
    EXPECT_GT(volume(plate & translate(s, {0, 0, 1 - step})), 0.0) << n;
    EXPECT_EQ(volume(plate & translate(s, {0, 0, 1})), 0.0) << n;
    // A ball standing on the plate: the volumes add.
    EXPECT_NEAR(volume(unite(plate, translate(s, {0, 0, 1}))), volume(plate) + volume(s), 1e-12) << n;
  }
}

// Parts touching at one point inside a face or an edge of the other (docs/kernel.md, "Clean
// output"; mesh/touching_vertices.hpp): the exported mesh has the point as a corner of both, so it
// passes the closed-manifold check with its self-intersection search (what import(strict=true)
// asks) and reads back from every format as the same solid. (A sphere's ring vertices are not grid
// points, so reading a ball back snaps them: the ball on the plate must read back as the plate
// plus the ball read back alone, which it does only if the touching point stays where it is.)
TEST(PrimitiveVertices, PartsTouchingAtAPointShareItInTheMesh) {
  const Solid plate = box({-2, -2, -1}, {2, 2, 0});
  for (const bool triangulate : {false, true}) {
    // A ball standing on the plate: its pole inside the plate's top face.
    const Solid ball = translate(sphere(1, {.segments = 16}), {0, 0, 1});
    const Solid standing = unite(plate, ball);
    const PolygonMesh ball_on_plate = to_mesh(standing, {.triangulate = triangulate});
    const ValidationReport report = check_closed_manifold(ball_on_plate);
    EXPECT_TRUE(report.ok()) << report.summary();
    const double ball_back = volume(from_mesh(to_mesh(ball)));
    EXPECT_GT(std::fabs(ball_back - volume(ball)), 1e-7) << "the ring vertices are snapped";
    expect_reads_back(ball_on_plate, volume(plate) + ball_back, 1e-12, "ball on a plate");
    // The fuzzer's case (tests/fuzz/regressions/cone_vertex_on_box_edge): the cone's base vertex
    // (-2.6875, 0, 0) inside the box's edge x = -2.6875, y = 0.
    const Solid cone_and_box =
        unite(cone(2.6875, 2.6875, {.segments = 22}), box({-4.6875, -4.66015625, -2}, {-2.6875, 0, 1.34375}));
    const PolygonMesh edge_contact = to_mesh(cone_and_box, {.triangulate = triangulate});
    const ValidationReport edge_report = check_closed_manifold(edge_contact);
    EXPECT_TRUE(edge_report.ok()) << edge_report.summary();
    expect_reads_back(edge_contact, volume(cone_and_box), 1e-12, "cone on a box's edge");
  }
}

}  // namespace
}  // namespace sculpt
