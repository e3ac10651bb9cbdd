// Vertices touching a face or an edge they are not a corner of (mesh/touching_vertices.hpp): a
// pyramid standing on a box by its apex, inside a face, on an edge, twice on one face. Checked
// against the self-intersection search (which sees the touching faces before and none after), the
// closed-manifold validation, and the volume, which the insertion must not change.
#include "mesh/touching_vertices.hpp"

#include <gtest/gtest.h>

#include "mesh/mesh_measures.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/self_intersection.hpp"
#include "mesh/triangulate.hpp"
#include "shapes.hpp"

namespace sculpt {
namespace {

using Eigen::Vector3d;

/// A square pyramid with its apex at `apex` pointing down (-z), its base the square of half-side
/// `h` at height `apex.z() + height`, centred at `base_centre` in x and y.
PolygonMesh pyramid(const Vector3d& apex, const Eigen::Vector2d& base_centre, double h, double height) {
  PolygonMesh m;
  const double z = apex.z() + height, x = base_centre.x(), y = base_centre.y();
  m.vertices = {apex, {x - h, y - h, z}, {x + h, y - h, z}, {x + h, y + h, z}, {x - h, y + h, z}};
  // Outward: the base faces up, the sides face out and down.
  m.faces = {{1, 2, 3, 4}, {0, 2, 1}, {0, 3, 2}, {0, 4, 3}, {0, 1, 4}};
  return m;
}

/// Both meshes in one (the second's indices shifted).
PolygonMesh together(PolygonMesh a, const PolygonMesh& b) {
  const int offset = int(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (std::vector<int> f : b.faces) {
    for (int& v : f) v += offset;
    a.faces.push_back(std::move(f));
  }
  return a;
}

struct Outcome {
  TouchingVertices report;
  PolygonMesh mesh;
};

Outcome insert(PolygonMesh m, bool triangles) {
  if (triangles) m = triangulate(m);
  std::vector<char> exact(m.vertices.size(), 1);
  const TouchingVertices report = insert_touching_vertices(m, exact, triangles);
  EXPECT_EQ(exact.size(), m.vertices.size());
  return {report, m};
}

void expect_clean(const PolygonMesh& before, const PolygonMesh& after, bool triangles) {
  EXPECT_FALSE(find_self_intersections(triangulate(before)).empty()) << "the test's meshes touch";
  EXPECT_TRUE(find_self_intersections(triangulate(after)).empty());
  const ValidationReport report = check_closed_manifold(after);
  EXPECT_TRUE(report.ok()) << report.summary();
  EXPECT_DOUBLE_EQ(mesh_volume(after), mesh_volume(before));
  if (triangles) {
    for (const auto& f : after.faces) EXPECT_EQ(f.size(), 3u);
  }
}

TEST(TouchingVertices, ApexInsideAFaceBecomesItsCorner) {
  const PolygonMesh before = together(test_shapes::unit_cube(), pyramid({0.25, 0.5, 1}, {0.25, 0.5}, 0.2, 1));
  for (const bool triangles : {false, true}) {
    const Outcome out = insert(before, triangles);
    EXPECT_EQ(out.report.into_faces, 1) << triangles;
    EXPECT_EQ(out.report.into_edges, 0);
    EXPECT_EQ(out.report.left, 0);
    EXPECT_EQ(out.mesh.vertices.size(), before.vertices.size() + 1) << "one copy of the apex";
    EXPECT_EQ(out.mesh.vertices.back(), Vector3d(0.25, 0.5, 1));
    expect_clean(before, out.mesh, triangles);
  }
}

TEST(TouchingVertices, ApexInsideAnEdgeSplitsItInBothFaces) {
  // The apex on the cube's top front edge (y = 0, z = 1), the pyramid above and in front of it.
  const PolygonMesh before = together(test_shapes::unit_cube(), pyramid({0.5, 0, 1}, {0.5, -0.3}, 0.2, 1));
  for (const bool triangles : {false, true}) {
    const Outcome out = insert(before, triangles);
    EXPECT_EQ(out.report.into_edges, 1) << triangles;
    EXPECT_EQ(out.report.into_faces, 0);
    int faces_with_copy = 0;
    for (const auto& f : out.mesh.faces)
      for (const int v : f) faces_with_copy += v == int(out.mesh.vertices.size()) - 1;
    EXPECT_EQ(faces_with_copy, triangles ? 4 : 2) << "the top and the front face, each once";
    expect_clean(before, out.mesh, triangles);
  }
}

TEST(TouchingVertices, TwoApexesOnOneFaceAndOneOnACornerSharedAlready) {
  // Two pyramids on the top face (the second round finds the second inside a fan triangle or on
  // one of its edges); a third stands on the cube's corner (1, 1, 1), which is a corner already.
  PolygonMesh before = together(test_shapes::unit_cube(), pyramid({0.25, 0.25, 1}, {0.25, 0.25}, 0.1, 1));
  before = together(before, pyramid({0.75, 0.75, 1}, {0.75, 0.75}, 0.1, 1));
  const PolygonMesh corner = pyramid({1, 1, 1}, {1.2, 1.2}, 0.1, 1);
  const Outcome out = insert(together(before, corner), false);
  EXPECT_EQ(out.report.into_faces + out.report.into_edges, 2);
  EXPECT_EQ(out.report.left, 0);
  EXPECT_EQ(out.mesh.vertices.size(), before.vertices.size() + corner.vertices.size() + 2);
  EXPECT_TRUE(find_self_intersections(triangulate(out.mesh)).empty());
  EXPECT_TRUE(check_closed_manifold(out.mesh).ok());
}

TEST(TouchingVertices, OnlyExactVerticesAndFacesAreTested) {
  // The same contact, but the apex is not marked exact (its coordinates were rounded): nothing is
  // decided about it, and nothing changes. Flags of the wrong size: nothing is done.
  PolygonMesh m = together(test_shapes::unit_cube(), pyramid({0.25, 0.5, 1}, {0.25, 0.5}, 0.2, 1));
  std::vector<char> exact(m.vertices.size(), 1);
  exact[8] = 0;  // the apex
  const std::size_t faces = m.faces.size();
  EXPECT_EQ(insert_touching_vertices(m, exact, false).into_faces, 0);
  EXPECT_EQ(m.faces.size(), faces);
  std::vector<char> none;
  EXPECT_EQ(insert_touching_vertices(m, none, false).into_faces, 0);
  EXPECT_EQ(m.faces.size(), faces);
}

TEST(TouchingVertices, AVertexNearButNotOnTheFaceIsLeftAlone) {
  // One unit in the last place above the face: off its plane, decided exactly.
  const PolygonMesh m =
      together(test_shapes::unit_cube(), pyramid({0.25, 0.5, std::nextafter(1.0, 2.0)}, {0.25, 0.5}, 0.2, 1));
  const Outcome out = insert(m, true);
  EXPECT_EQ(out.report.into_faces + out.report.into_edges, 0);
  EXPECT_EQ(out.mesh.faces.size(), triangulate(m).faces.size());
}

}  // namespace
}  // namespace sculpt
