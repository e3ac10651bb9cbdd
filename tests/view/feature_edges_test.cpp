// Feature edges (lib/view/detail/feature_edges.hpp): the edges between faces that are not
// coplanar, never the diagonals of a flat region, and the borders of open meshes.
#include "view/detail/feature_edges.hpp"

#include <gtest/gtest.h>

#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt::view::detail {
namespace {

TEST(FeatureEdges, BoxHasItsTwelveEdges) {
  const PolygonMesh mesh = to_mesh(box({0, 0, 0}, {1, 2, 3}));
  EXPECT_EQ(feature_edges(mesh).size(), 12u);
}

TEST(FeatureEdges, TriangulatedBoxStillHasTwelve) {
  // The triangles' diagonals lie inside flat faces: they are not features.
  const PolygonMesh mesh = to_mesh(box({0, 0, 0}, {1, 2, 3}), {.triangulate = true});
  ASSERT_GT(mesh.faces.size(), 6u);
  EXPECT_EQ(feature_edges(mesh).size(), 12u);
}

TEST(FeatureEdges, CoplanarPiecesOfACarvedTopAreNotFeatures) {
  // Two boxes side by side make one box: the faces split where they met are flat there.
  const Solid joined = unite(box({0, 0, 0}, {1, 1, 1}), box({1, 0, 0}, {2, 1, 1}));
  const auto edges = feature_edges(to_mesh(joined));
  EXPECT_EQ(edges.size(), 12u);
  // A notch cut from the top adds its own edges and no others: an L-shaped prism has 18 edges.
  const Solid notched = subtract(box({0, 0, 0}, {2, 1, 1}), box({1, -1, 0.5}, {3, 2, 2}));
  EXPECT_EQ(feature_edges(to_mesh(notched)).size(), 18u);
}

TEST(FeatureEdges, BorderOfAnOpenMeshIsAFeature) {
  PolygonMesh square;
  square.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.faces = {{0, 1, 2}, {0, 2, 3}};
  const auto edges = feature_edges(square);
  EXPECT_EQ(edges.size(), 4u);  // the diagonal 0-2 joins two coplanar triangles
  for (const auto& e : edges) EXPECT_FALSE(e[0] == 0 && e[1] == 2);
}

TEST(FeatureEdges, EmptyMeshHasNone) { EXPECT_TRUE(feature_edges(PolygonMesh{}).empty()); }

}  // namespace
}  // namespace sculpt::view::detail
