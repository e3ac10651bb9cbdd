#include "mesh/edge_incidence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <utility>

#include "shapes.hpp"

namespace sculpt {
namespace {

// The definition, counted by brute force: every directed side (a != b) occurs once, and so does its reverse.
bool paired_by_count(const PolygonMesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& f : mesh.faces)
    for (size_t k = 0; k < f.size(); ++k)
      if (f[k] != f[(k + 1) % f.size()]) ++uses[{f[k], f[(k + 1) % f.size()]}];
  for (const auto& [side, n] : uses) {
    const auto back = uses.find({side.second, side.first});
    if (n != 1 || back == uses.end() || back->second != 1) return false;
  }
  return true;
}

TEST(EdgesPaired, ClosedSurfacesArePaired) {
  for (const PolygonMesh& m : {test_shapes::unit_cube(), test_shapes::tetrahedron(), test_shapes::octahedron(),
                               test_shapes::torus(6, 4), test_shapes::uv_sphere(8), PolygonMesh{}}) {
    EXPECT_TRUE(edges_paired(m));
    EXPECT_TRUE(paired_by_count(m));
  }
}

TEST(EdgesPaired, SheetsMeetingAtCopiesArePaired) {
  // Two cubes touching along an edge, each with its own copies of the shared corners.
  EXPECT_TRUE(edges_paired(test_shapes::merged(test_shapes::unit_cube(), test_shapes::box({1, 1, 0}, {2, 2, 1}))));
}

TEST(EdgesPaired, OpenFlippedAndFinnedSurfacesAreNot) {
  PolygonMesh open = test_shapes::unit_cube();
  open.faces.pop_back();
  PolygonMesh flipped = test_shapes::unit_cube();
  std::reverse(flipped.faces[3].begin(), flipped.faces[3].end());
  PolygonMesh fin = test_shapes::unit_cube();
  fin.vertices.emplace_back(0.5, -1, -1);
  fin.faces.push_back({0, 1, 8});
  fin.faces.push_back({1, 0, 8});  // both sides of the fin: every side used twice, edge 0-1 four times
  PolygonMesh twice = test_shapes::unit_cube();
  const auto faces = twice.faces;
  twice.faces.insert(twice.faces.end(), faces.begin(), faces.end());
  for (const PolygonMesh& m : {open, flipped, fin, twice}) {
    EXPECT_FALSE(edges_paired(m));
    EXPECT_FALSE(paired_by_count(m));
  }
}

TEST(EdgesPaired, AgreesWithCountingOnRandomFaceSets) {
  // Small random meshes: a few vertices, faces drawn from them and from a closed surface's faces,
  // so that both answers occur often.
  std::mt19937 rng(7);
  int paired = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    PolygonMesh m = test_shapes::tetrahedron();
    std::uniform_int_distribution<int> vertex(0, 3), coin(0, 3);
    if (coin(rng) == 0) m.faces.push_back({vertex(rng), vertex(rng), vertex(rng)});
    if (coin(rng) == 0) m.faces.erase(m.faces.begin() + vertex(rng));
    if (coin(rng) == 0) std::reverse(m.faces[0].begin(), m.faces[0].end());
    if (coin(rng) == 0) m.faces.push_back(m.faces[std::uniform_int_distribution<size_t>(0, m.faces.size() - 1)(rng)]);
    const bool expected = paired_by_count(m);
    paired += expected;
    ASSERT_EQ(edges_paired(m), expected) << "trial " << trial;
  }
  EXPECT_GT(paired, 100);
  EXPECT_LT(paired, 2900);
}

}  // namespace
}  // namespace sculpt
