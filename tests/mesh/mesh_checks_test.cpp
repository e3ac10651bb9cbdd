// The shared checkers in tests/support/mesh_checks.hpp must fail on broken meshes.
#include "support/mesh_checks.hpp"
#include "support/mesh_validity.hpp"

#include <gtest/gtest.h>

#include "shapes.hpp"

namespace sculpt {
namespace {

TEST(MeshChecks, AcceptGoodMeshes) {
  const PolygonMesh c = test_shapes::unit_cube();
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(c));
  EXPECT_TRUE(checks::EulerCharacteristicIs(c, 2));
  EXPECT_TRUE(checks::GenusIs(c, 0));
  EXPECT_TRUE(checks::GenusIs(test_shapes::torus(6, 5), 1));
  EXPECT_TRUE(checks::NoDuplicateVertices(c));
  EXPECT_TRUE(checks::NoDegenerateFaces(c));
  EXPECT_TRUE(checks::VolumeNear(c, 1, 1e-15));
  EXPECT_TRUE(checks::ValidSolidMesh(c));
}

TEST(MeshChecks, RejectBrokenMeshes) {
  PolygonMesh open = test_shapes::unit_cube();
  open.faces.pop_back();
  EXPECT_FALSE(checks::EdgesManifoldAndOriented(open));
  EXPECT_FALSE(checks::GenusIs(open, 0));
  PolygonMesh flipped = test_shapes::unit_cube();
  std::reverse(flipped.faces[0].begin(), flipped.faces[0].end());
  EXPECT_FALSE(checks::EdgesManifoldAndOriented(flipped));
  EXPECT_FALSE(checks::EulerCharacteristicIs(test_shapes::torus(6, 5), 2));
  EXPECT_FALSE(checks::GenusIs(test_shapes::torus(6, 5), 0));
  EXPECT_FALSE(checks::GenusIs(test_shapes::merged(test_shapes::unit_cube(), test_shapes::unit_cube()), 0, 1));
  PolygonMesh dup = test_shapes::unit_cube();
  dup.vertices.push_back(dup.vertices[3]);
  EXPECT_FALSE(checks::NoDuplicateVertices(dup));
  PolygonMesh flat = test_shapes::unit_cube();
  flat.vertices.push_back({0.5, 0, 0});
  flat.faces.push_back({0, 8, 1});
  EXPECT_FALSE(checks::NoDegenerateFaces(flat));
  PolygonMesh rep = test_shapes::unit_cube();
  rep.faces[0] = {0, 2, 2, 1};
  EXPECT_FALSE(checks::NoDegenerateFaces(rep));
  EXPECT_FALSE(checks::VolumeNear(test_shapes::unit_cube(), 1.001, 1e-6));
  PolygonMesh bad = test_shapes::unit_cube();
  bad.faces[1][2] = 99;
  EXPECT_FALSE(checks::VolumeNear(bad, 1, 1));
  EXPECT_FALSE(checks::ValidSolidMesh(open));
  EXPECT_FALSE(checks::ValidSolidMesh(test_shapes::merged(test_shapes::unit_cube(), test_shapes::unit_cube())));
}

}  // namespace
}  // namespace sculpt
