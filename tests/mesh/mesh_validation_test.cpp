// validate_closed_manifold finds each kind of defect in hand-built broken meshes and says where.
#include "mesh/mesh_validation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "base/errors.hpp"
#include "shapes.hpp"

namespace sculpt {
namespace {

using ::testing::HasSubstr;
using test_shapes::box;
using test_shapes::merged;

size_t count(const PolygonMesh& m, DefectKind k) { return check_closed_manifold(m).count(k); }

TEST(Validation, ClosedSolidsPass) {
  EXPECT_TRUE(check_closed_manifold(test_shapes::unit_cube()).ok());
  EXPECT_TRUE(check_closed_manifold(test_shapes::tetrahedron()).ok());
  EXPECT_TRUE(check_closed_manifold(test_shapes::octahedron()).ok());
  EXPECT_TRUE(check_closed_manifold(test_shapes::torus(12, 8)).ok());
  EXPECT_TRUE(check_closed_manifold(test_shapes::uv_sphere(64)).ok());
  EXPECT_NO_THROW(validate_closed_manifold(test_shapes::uv_sphere(16)));
  // Disjoint solids, and nested ones (a cavity, inner faces reversed), are fine.
  EXPECT_TRUE(check_closed_manifold(merged(box({0, 0, 0}, {1, 1, 1}), box({2, 0, 0}, {3, 1, 1}))).ok());
  PolygonMesh cavity = box({0.25, 0.25, 0.25}, {0.75, 0.75, 0.75});
  for (auto& f : cavity.faces) std::reverse(f.begin(), f.end());
  EXPECT_TRUE(check_closed_manifold(merged(box({0, 0, 0}, {1, 1, 1}), cavity)).ok());
}

// What the validator's first checks find, without messages: short faces, indices out of range and
// non-finite coordinates make it false, anything else (an open or non-manifold mesh) does not.
TEST(Validation, IndicesAndCoordinatesValidAgreesWithTheFirstChecks) {
  const PolygonMesh box = test_shapes::box({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(indices_and_coordinates_valid(box));
  PolygonMesh open = box;
  open.faces.pop_back();
  EXPECT_TRUE(indices_and_coordinates_valid(open));
  PolygonMesh bad = box;
  bad.faces[3][1] = int(bad.vertices.size());
  EXPECT_FALSE(indices_and_coordinates_valid(bad));
  bad = box;
  bad.faces[2][0] = -1;
  EXPECT_FALSE(indices_and_coordinates_valid(bad));
  bad = box;
  bad.faces[1].resize(2);
  EXPECT_FALSE(indices_and_coordinates_valid(bad));
  bad = box;
  bad.vertices[5].y() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(indices_and_coordinates_valid(bad));
  bad.vertices[5].y() = std::nan("");
  EXPECT_FALSE(indices_and_coordinates_valid(bad));
  for (const PolygonMesh& m : {box, open}) {
    const ValidationReport r = check_closed_manifold(m);
    EXPECT_EQ(r.count(DefectKind::InvalidIndex) + r.count(DefectKind::NonFiniteCoordinate), 0u);
  }
}

TEST(Validation, OpenEdgeGivesItsCoordinates) {
  PolygonMesh m = test_shapes::unit_cube();
  m.faces.erase(m.faces.begin() + 1);  // remove the top (z = 1)
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.count(DefectKind::OpenEdge), 4u);
  EXPECT_EQ(r.defects.size(), 4u);
  EXPECT_THAT(r.summary(), HasSubstr("open edge: 4"));
  EXPECT_THAT(r.summary(), HasSubstr("open edge (0, 0, 1) - (1, 0, 1) (vertices 4, 5) has only face"));
  try {
    validate_closed_manifold(m);
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_THAT(e.what(), HasSubstr("mesh is not a closed manifold: open edge: 4"));
    EXPECT_FALSE(e.where().known());
  }
  try {
    validate_closed_manifold(m, {.source = "models/open.stl"});
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith("models/open.stl: mesh is not a closed manifold"));
    EXPECT_EQ(e.where().file, "models/open.stl");
  }
}

TEST(Validation, NonManifoldEdgeWithThreeFaces) {
  // Two boxes sharing an edge by index plus a fin: simplest is a cube with an extra
  // triangle on one of its edges (edge 0-1 then has 3 faces).
  PolygonMesh m = test_shapes::unit_cube();
  m.vertices.emplace_back(0.5, -1, -1);
  m.faces.push_back({0, 1, 8});
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.count(DefectKind::NonManifoldEdge), 1u);
  EXPECT_THAT(r.summary(), HasSubstr("non-manifold edge (0, 0, 0) - (1, 0, 0) (vertices 0, 1) has 3 faces"));
  EXPECT_EQ(r.count(DefectKind::OpenEdge), 2u);  // the fin's free edges
}

TEST(Validation, FlippedFaceIsInconsistentOrientation) {
  PolygonMesh m = test_shapes::unit_cube();
  std::reverse(m.faces[3].begin(), m.faces[3].end());
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.count(DefectKind::InconsistentOrientation), 4u);
  EXPECT_EQ(r.defects.size(), 4u);
  EXPECT_THAT(r.summary(), HasSubstr("run the same way along edge"));
}

TEST(Validation, DegenerateFaces) {
  PolygonMesh m = test_shapes::tetrahedron();
  // Split edge 0-1 at its midpoint and add a sliver: face {0, 4, 1} is a zero-area triangle.
  m.vertices.emplace_back(0.5, 0, 0);
  m.faces = {{0, 2, 1, 4}, {0, 4, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 1}, {0, 1, 4}};
  EXPECT_EQ(count(m, DefectKind::DegenerateFace), 2u);
  PolygonMesh rep = test_shapes::tetrahedron();
  rep.faces[3] = {1, 2, 2, 3};
  const ValidationReport r = check_closed_manifold(rep);
  EXPECT_EQ(r.count(DefectKind::DegenerateFace), 1u);
  EXPECT_THAT(r.summary(), HasSubstr("face 3 visits vertex 2 (0, 1, 0) twice"));
}

TEST(Validation, NonPlanarFaces) {
  PolygonMesh m = test_shapes::unit_cube();
  m.vertices[7] += Eigen::Vector3d(1e-3, 1e-3, 1e-3);  // corner (1, 1, 1) pulled out: its three quads bend
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.count(DefectKind::NonPlanarFace), 3u) << r.summary();
  EXPECT_EQ(r.defects.size(), 3u) << r.summary();
  EXPECT_THAT(r.summary(), HasSubstr("is not planar: vertex"));
  // Rounding-level deviations pass: the cube rotated by an arbitrary rotation.
  PolygonMesh rotated = test_shapes::unit_cube();
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (auto& p : rotated.vertices) p = rot * p;
  EXPECT_TRUE(check_closed_manifold(rotated).ok()) << check_closed_manifold(rotated).summary();
  EXPECT_TRUE(check_closed_manifold(m, {.planarity_tolerance = 1e-2}).ok());
}

TEST(Validation, SelfCrossingFace) {
  // A prism whose top face is listed as a bow tie (0 1 3 2 order of a square).
  PolygonMesh m = test_shapes::unit_cube();
  m.faces[1] = {4, 5, 6, 7};  // correct order is 4 5 7 6: edges 5-6 and 7-4 cross
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.count(DefectKind::SelfCrossingFace), 1u) << r.summary();
  EXPECT_THAT(r.summary(), HasSubstr("the boundary of face 1 (first corner (0, 0, 1)) crosses itself"));
  EXPECT_GE(r.count(DefectKind::OpenEdge), 1u);  // and its edges no longer match the sides
}

TEST(Validation, BowtieVertexIsNonManifold) {
  // Two tetrahedra sharing only vertex 0 (same index).
  PolygonMesh a = test_shapes::tetrahedron();
  PolygonMesh b = test_shapes::tetrahedron();
  for (auto& p : b.vertices) p = -p;
  for (auto& f : b.faces) std::reverse(f.begin(), f.end());  // reflection flips orientation
  PolygonMesh m = merged(a, b);
  for (auto& f : m.faces)
    for (int& v : f)
      if (v == 4) v = 0;
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.count(DefectKind::NonManifoldVertex), 1u) << r.summary();
  EXPECT_EQ(r.defects.size(), 1u) << r.summary();
  EXPECT_THAT(r.summary(), HasSubstr("non-manifold vertex 0 (0, 0, 0): its faces form more than one fan"));
}

TEST(Validation, TouchingThroughDuplicatedVerticesIsAllowed) {
  // Two cubes sharing an edge (and two touching at a corner), each with its own vertices,
  // as boundary extraction writes a solid that touches itself: 2-manifold sheets, no crossing.
  EXPECT_TRUE(check_closed_manifold(merged(box({0, 0, 0}, {1, 1, 1}), box({1, 1, 0}, {2, 2, 1}))).ok());
  EXPECT_TRUE(check_closed_manifold(merged(box({0, 0, 0}, {1, 1, 1}), box({1, 1, 1}, {2, 2, 2}))).ok());
}

TEST(Validation, OverlappingSolidsSelfIntersect) {
  const PolygonMesh m = merged(box({0, 0, 0}, {1, 1, 1}), box({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}));
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.defects.size(), r.count(DefectKind::SelfIntersection));
  // Each of the three faces of A at x,y,z = 1 crosses two faces of B, and vice versa: 6 pairs
  // cross (A's face x=1 meets B's faces y=0.5 and z=0.5, ...).
  EXPECT_EQ(r.count(DefectKind::SelfIntersection), 6u) << r.summary(20);
  EXPECT_THAT(r.summary(), HasSubstr(") intersect"));
}

TEST(Validation, CoplanarOverlapAndTouchingAreSelfIntersections) {
  // Face to face contact of two boxes with separate vertices: the faces overlap in a plane.
  const PolygonMesh touching = merged(box({0, 0, 0}, {1, 1, 1}), box({0.2, 0.2, 1}, {0.8, 0.8, 2}));
  EXPECT_GE(count(touching, DefectKind::SelfIntersection), 1u);
  // A vertex of one cube pushed exactly onto a face of another: touching at a point.
  // A tetrahedron standing on its corner (0,0,0), mirrored in z and lifted so that the corner
  // touches the cube's top face at (0.25, 0.25, 1).
  PolygonMesh tip = test_shapes::tetrahedron();
  for (auto& p : tip.vertices) p = Eigen::Vector3d(p.x() + 0.25, p.y() + 0.25, 2 - p.z());
  for (auto& f : tip.faces) std::reverse(f.begin(), f.end());
  ASSERT_EQ(tip.vertices[3], Eigen::Vector3d(0.25, 0.25, 1));
  const PolygonMesh poke = merged(box({0, 0, 0}, {1, 1, 1}), tip);
  const ValidationReport r = check_closed_manifold(poke);
  // The three faces of the tetrahedron at its corner touch the cube's top face.
  EXPECT_EQ(r.count(DefectKind::SelfIntersection), 3u) << r.summary();
  EXPECT_EQ(r.defects.size(), r.count(DefectKind::SelfIntersection));
}

TEST(Validation, VertexPushedThroughTheOppositeFace) {
  PolygonMesh m = test_shapes::octahedron();
  m.vertices[4] = {0.3, 0.3, -0.5};  // top apex moved down and out through face (0, 2, 5)
  EXPECT_GE(count(m, DefectKind::SelfIntersection), 1u);
  m.vertices[4] = {0.1, 0.1, 0.01};  // still above the equator: fine
  EXPECT_TRUE(check_closed_manifold(m).ok()) << check_closed_manifold(m).summary();
}

TEST(Validation, FoldedAdjacentFacesOverlap) {
  // Two coplanar triangles on the same side of their shared edge.
  PolygonMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 0.5, 0}};
  m.faces = {{0, 1, 2}, {1, 0, 3}};
  EXPECT_EQ(count(m, DefectKind::SelfIntersection), 1u);
  m.vertices[3] = {0.5, -0.5, 0};  // opposite side: a flat open sheet, no overlap
  EXPECT_EQ(count(m, DefectKind::SelfIntersection), 0u);
}

TEST(Validation, BadIndicesAndCoordinatesStopEarly) {
  PolygonMesh m = test_shapes::unit_cube();
  m.faces[2][1] = 42;
  m.faces.push_back({0, 1});
  const ValidationReport r = check_closed_manifold(m);
  EXPECT_EQ(r.count(DefectKind::InvalidIndex), 2u);
  EXPECT_EQ(r.defects.size(), 2u);
  PolygonMesh n = test_shapes::unit_cube();
  n.vertices[3].y() = std::numeric_limits<double>::infinity();
  EXPECT_THAT(check_closed_manifold(n).summary(), HasSubstr("vertex 3 (1, inf, 0) has a non-finite coordinate"));
}

TEST(Validation, ManyDefectsAreCapped) {
  PolygonMesh m = test_shapes::uv_sphere(64);
  m.faces.resize(m.faces.size() / 2);  // half a sphere: 64 open edges
  const ValidationReport r = check_closed_manifold(m, {.max_defects_per_kind = 10});
  EXPECT_EQ(r.count(DefectKind::OpenEdge), 10u);
  EXPECT_THAT(r.summary(3), HasSubstr("... and 7 more"));
}

}  // namespace
}  // namespace sculpt
