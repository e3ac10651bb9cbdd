// Measures against analytic values.
#include "mesh/mesh_measures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tuple>
#include <algorithm>
#include <numbers>

#include "base/errors.hpp"
#include "mesh/edge_incidence.hpp"
#include "shapes.hpp"

namespace sculpt {
namespace {

using test_shapes::box;
using test_shapes::merged;

TEST(Measures, Cube) {
  const PolygonMesh c = test_shapes::unit_cube();
  EXPECT_DOUBLE_EQ(mesh_volume(c), 1);
  EXPECT_DOUBLE_EQ(mesh_surface_area(c), 6);
  EXPECT_EQ(euler_characteristic(c), 2);
  EXPECT_EQ(component_count(c), 1);
  EXPECT_EQ(genus(c), 0);
  const auto b = mesh_bounding_box(c);
  EXPECT_EQ(b.min(), Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(b.max(), Eigen::Vector3d(1, 1, 1));
}

TEST(Measures, TetrahedronAndOctahedron) {
  EXPECT_NEAR(mesh_volume(test_shapes::tetrahedron()), 1.0 / 6, 1e-16);
  EXPECT_NEAR(mesh_surface_area(test_shapes::tetrahedron()), 1.5 + std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(mesh_volume(test_shapes::octahedron()), 4.0 / 3, 1e-15);
  EXPECT_NEAR(mesh_surface_area(test_shapes::octahedron()), 4 * std::sqrt(3.0), 1e-14);
  EXPECT_EQ(euler_characteristic(test_shapes::octahedron()), 2);
  EXPECT_EQ(genus(test_shapes::octahedron()), 0);
}

TEST(Measures, ReversedOrientationGivesNegativeVolume) {
  PolygonMesh c = box({0, 0, 0}, {2, 3, 4});
  for (auto& f : c.faces) std::reverse(f.begin(), f.end());
  EXPECT_DOUBLE_EQ(mesh_volume(c), -24);
}

TEST(Measures, FarFromTheOriginStaysAccurate) {
  const double o = 1e7;
  const PolygonMesh c = box({o, o, o}, {o + 0.1, o + 0.2, o + 0.3});
  // The box edges are the doubles nearest o + 0.1 etc.: compute the exact expected volume from them.
  const double expected = ((o + 0.1) - o) * ((o + 0.2) - o) * ((o + 0.3) - o);
  EXPECT_NEAR(mesh_volume(c), expected, 1e-15);
}

TEST(Measures, TorusHasGenusOne) {
  const PolygonMesh t = test_shapes::torus(24, 12);
  EXPECT_EQ(euler_characteristic(t), 0);
  EXPECT_EQ(genus(t), 1);
  // The polyhedral torus's volume approaches 2 pi^2 R r^2 from below as it is refined.
  const double exact = 2 * std::numbers::pi * std::numbers::pi * 2 * 0.25;
  EXPECT_LT(mesh_volume(t), exact);
  EXPECT_NEAR(mesh_volume(test_shapes::torus(400, 200)), exact, 2e-3 * exact);
}

TEST(Measures, ComponentsAndTotalGenus) {
  const PolygonMesh two = merged(test_shapes::torus(8, 6), merged(box({5, 5, 5}, {6, 6, 6}), test_shapes::torus(8, 6)));
  EXPECT_EQ(component_count(two), 3);
  EXPECT_EQ(genus(two), 2);
  const auto labels = face_components(two);
  EXPECT_EQ(labels.front(), 0);
  EXPECT_EQ(labels.back(), 2);
}

TEST(Measures, SphereApproachesAnalyticValues) {
  const PolygonMesh s = test_shapes::uv_sphere(256);
  // Inscribed polyhedron: below the sphere's values, within 0.05 % at 256 segments.
  EXPECT_LT(mesh_volume(s), 4 * std::numbers::pi / 3);
  EXPECT_NEAR(mesh_volume(s), 4 * std::numbers::pi / 3, 5e-4 * 4 * std::numbers::pi / 3);
  EXPECT_LT(mesh_surface_area(s), 4 * std::numbers::pi);
  EXPECT_NEAR(mesh_surface_area(s), 4 * std::numbers::pi, 5e-4 * 4 * std::numbers::pi);
  EXPECT_EQ(genus(s), 0);
}

// A TriangleMesh's measures are the PolygonMesh's with the same faces: the same sums in the same
// order, so equal to the last bit (a solid made from a mesh measures itself from one).
TEST(Measures, ATriangleMeshMeasuresAsThePolygonMeshOfItsFaces) {
  const PolygonMesh t = test_shapes::torus(24, 12);
  TriangleMesh tm{.vertices = t.vertices, .triangles = {}};
  for (const auto& f : t.faces)
    for (size_t k = 1; k + 1 < f.size(); ++k) tm.triangles.push_back({f[0], f[k], f[k + 1]});
  const PolygonMesh back = to_polygon_mesh(tm);
  ASSERT_EQ(back.faces.size(), tm.triangles.size());
  EXPECT_EQ(mesh_volume(tm), mesh_volume(back));
  EXPECT_EQ(mesh_surface_area(tm), mesh_surface_area(back));
  EXPECT_NEAR(mesh_volume(tm), mesh_volume(t), 1e-12 * mesh_volume(t));
  tm.triangles[5][1] = int(tm.vertices.size());
  EXPECT_THROW(mesh_volume(tm), InvalidInput);
  EXPECT_THROW(mesh_surface_area(tm), InvalidInput);
}

TEST(Measures, OpenMeshHasNoGenusAndBadIndicesThrow) {
  PolygonMesh c = test_shapes::unit_cube();
  c.faces.pop_back();
  EXPECT_THROW(genus(c), GeometryError);
  c.faces[0][0] = -1;
  EXPECT_THROW(mesh_volume(c), InvalidInput);
  EXPECT_THROW(euler_characteristic(c), InvalidInput);
  EXPECT_TRUE(mesh_bounding_box(PolygonMesh{}).isEmpty());
  EXPECT_EQ(mesh_volume(PolygonMesh{}), 0);
}

}  // namespace
}  // namespace sculpt

namespace sculpt {
namespace {

// sorted_edge_records sorts by counting (lower vertex) and then per vertex: the same order as one
// comparison sort by (lo, hi, face, corner), on random polygon soups with repeated corners,
// high-valence vertices (more sides than the per-vertex insertion sort takes) and unused vertices.
TEST(EdgeRecords, OrderOfOneComparisonSort) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    PolygonMesh m;
    const int nv = 1 + int(rng() % 40);
    m.vertices.assign(size_t(nv), Eigen::Vector3d::Zero());
    const int nf = int(rng() % 60);
    for (int f = 0; f < nf; ++f) {
      std::vector<int> face(3 + rng() % 5);
      for (int& v : face) v = trial % 3 == 0 && rng() % 2 ? 0 : int(rng() % unsigned(nv));  // vertex 0: high valence
      m.faces.push_back(face);
    }
    std::vector<HalfEdgeRecord> expected;
    for (size_t fi = 0; fi < m.faces.size(); ++fi)
      for (size_t k = 0; k < m.faces[fi].size(); ++k) {
        const int a = m.faces[fi][k], b = m.faces[fi][(k + 1) % m.faces[fi].size()];
        if (a != b) expected.push_back({std::min(a, b), std::max(a, b), int(fi), int(k), a < b});
      }
    std::sort(expected.begin(), expected.end(), [](const HalfEdgeRecord& x, const HalfEdgeRecord& y) {
      return std::tie(x.lo, x.hi, x.face, x.corner) < std::tie(y.lo, y.hi, y.face, y.corner);
    });
    const std::vector<HalfEdgeRecord> got = sorted_edge_records(m);
    ASSERT_EQ(got.size(), expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
      ASSERT_EQ(std::tie(got[i].lo, got[i].hi, got[i].face, got[i].corner, got[i].forward),
                std::tie(expected[i].lo, expected[i].hi, expected[i].face, expected[i].corner, expected[i].forward))
          << trial << " " << i;
    }
  }
}

}  // namespace
}  // namespace sculpt
