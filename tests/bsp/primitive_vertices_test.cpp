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
  for (const Eigen::Vector3d& v : mesh.vertices) EXPECT_FALSE(v.x() > 4 && v.x() < 4.001) << v.transpose();
  expect_reads_back(mesh, volume(u), 1e-12, "cone and box");
  const Solid d = box({-3, -3, 0}, {4, 3, 2}) - c;
  expect_reads_back(to_mesh(d), volume(d), 1e-12, "box minus cone");
}

TEST(PrimitiveVertices, SpherePoleCapOnAPlaneStaysFlush) {
  // sphere(1, 16): 8 rings at polar angles (k + 0.5) pi / 8; the top cap is flat at the grid
  // height nearest to cos(pi / 16). A box standing on it touches it exactly.
  const Solid s = sphere(1, {.segments = 16});
  const double top = snapped(std::cos(std::numbers::pi / 16));
  double highest = -1;
  for (const Eigen::Vector3d& v : to_mesh(s, {.clean = false}).vertices) highest = std::max(highest, v.z());
  EXPECT_EQ(highest, top);
  const Solid u = unite(s, box({-0.1, -0.1, top}, {0.1, 0.1, top + 0.5}));
  const double side = 2 * snapped(0.1), height = snapped(top + 0.5) - top;
  EXPECT_NEAR(volume(u), volume(s) + side * side * height, 1e-12);
  // The sphere's other vertices are not grid points: from_mesh snaps them, which moves the surface
  // by at most sqrt(3)/2 steps (area about 4 pi).
  expect_reads_back(to_mesh(u), volume(u), 4 * std::numbers::pi * 1.0 / kUnit, "sphere and box on its cap");
}

}  // namespace
}  // namespace sculpt
