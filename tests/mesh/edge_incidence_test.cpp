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

// triangle_neighbours against its definition by brute force: for side k of triangle f (from
// corner k to k + 1), the one other face that runs the same edge backwards, when the edge has just
// these two uses (counted over every face's sides, degenerate sides aside) and both faces are
// triangles. Random small meshes of triangles and quadrilaterals on a few vertices, with repeated
// corners, flipped, repeated and extra faces.
TEST(TriangleNeighbours, AgreeWithTheDefinitionOnRandomFaceSets) {
  std::mt19937 rng(11);
  int found = 0, missing = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    PolygonMesh m = trial % 2 ? test_shapes::octahedron() : test_shapes::tetrahedron();
    const int nv = int(m.vertices.size());
    std::uniform_int_distribution<int> vertex(0, nv - 1), coin(0, 3);
    if (coin(rng) == 0) m.faces.push_back({vertex(rng), vertex(rng), vertex(rng)});
    if (coin(rng) == 0) m.faces.push_back({vertex(rng), vertex(rng), vertex(rng), vertex(rng)});
    if (coin(rng) == 0)
      m.faces.erase(m.faces.begin() + std::uniform_int_distribution<long>(0, long(m.faces.size()) - 1)(rng));
    if (coin(rng) == 0) std::reverse(m.faces[0].begin(), m.faces[0].end());
    if (coin(rng) == 0) m.faces.push_back(m.faces[std::uniform_int_distribution<size_t>(0, m.faces.size() - 1)(rng)]);
    std::map<std::pair<int, int>, int> uses;  // undirected edge -> its sides' count
    for (const auto& f : m.faces)
      for (size_t k = 0; k < f.size(); ++k) {
        const int a = f[k], b = f[(k + 1) % f.size()];
        if (a != b) ++uses[{std::min(a, b), std::max(a, b)}];
      }
    const std::vector<std::array<int, 3>> got = triangle_neighbours(m);
    ASSERT_EQ(got.size(), m.faces.size());
    for (size_t fi = 0; fi < m.faces.size(); ++fi)
      for (size_t k = 0; k < 3; ++k) {
        int expected = -1;
        const auto& f = m.faces[fi];
        const int a = f[k], b = f[(k + 1) % f.size()];
        if (f.size() == 3 && a != b && uses[{std::min(a, b), std::max(a, b)}] == 2)
          for (size_t g = 0; g < m.faces.size(); ++g) {
            const auto& h = m.faces[g];
            if (h.size() != 3) continue;
            for (size_t j = 0; j < 3; ++j)
              if (h[j] == b && h[(j + 1) % 3] == a && !(g == fi && j == k)) expected = int(g);
          }
        ASSERT_EQ(got[fi][k], expected) << "trial " << trial << " face " << fi << " side " << k;
        (expected >= 0 ? found : missing) += 1;
      }
  }
  EXPECT_GT(found, 1000);
  EXPECT_GT(missing, 1000);
}

}  // namespace
}  // namespace sculpt
