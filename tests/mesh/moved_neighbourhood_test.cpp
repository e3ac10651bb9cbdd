// The faces a marked self-intersection search prepares (mesh/detail/moved_neighbourhood.hpp):
// against brute force, every face whose box meets a moved face's box is kept, and so is every
// moved or invalid face; and the selection leaves faces out where few are moved.
#include "mesh/detail/moved_neighbourhood.hpp"

#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "shapes.hpp"

namespace sculpt {
namespace {

using Eigen::Vector3d;

Eigen::AlignedBox3d box_of(const PolygonMesh& m, const std::vector<int>& face) {
  Eigen::AlignedBox3d b;
  for (int v : face) b.extend(m.vertices[std::size_t(v)]);
  return b;
}

bool moved(const std::vector<int>& face, const std::vector<char>& exact) {
  for (int v : face)
    if (exact[std::size_t(v)] == 0) return true;
  return false;
}

// Every face whose (closed) box meets a moved face's box, by brute force.
std::vector<char> needed(const PolygonMesh& m, const std::vector<char>& exact) {
  std::vector<char> out(m.faces.size(), 0);
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    if (!moved(m.faces[f], exact)) continue;
    const Eigen::AlignedBox3d b = box_of(m, m.faces[f]);
    for (std::size_t g = 0; g < m.faces.size(); ++g) out[g] = out[g] || b.intersects(box_of(m, m.faces[g]));
  }
  return out;
}

TEST(FacesNearMoved, KeepEveryFaceWhoseBoxMeetsAMovedFacesBox) {
  PolygonMesh s = test_shapes::uv_sphere(24);
  PolygonMesh t = test_shapes::torus(32, 12, 1.2, 0.3);
  for (auto& p : t.vertices) p += Vector3d(0.5, 0.25, 0.125);
  const PolygonMesh m =
      test_shapes::merged(test_shapes::merged(s, t), test_shapes::box({-3, -0.1, -0.1}, {3, 0.1, 0.1}));
  std::mt19937 rng(5);
  std::size_t left_out = 0;
  for (const double fraction : {0.7, 0.9, 0.97, 0.995}) {
    SCOPED_TRACE(fraction);
    std::bernoulli_distribution marked(fraction);
    std::vector<char> exact(m.vertices.size());
    for (char& e : exact) e = marked(rng) ? 1 : 0;
    const std::vector<char> kept = mesh::detail::faces_near_moved(m, exact);
    const std::vector<char> need = needed(m, exact);
    if (kept.empty()) continue;  // every face kept
    ASSERT_EQ(kept.size(), m.faces.size());
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      if (need[f]) {
        EXPECT_NE(kept[f], 0) << "face " << f << " meets a moved face's box but was left out";
      }
      left_out += kept[f] == 0 ? 1 : 0;
    }
  }
  EXPECT_GT(left_out, 0U) << "no face was left out: the selection is not exercised";
}

TEST(FacesNearMoved, BoxesThatOnlyTouchAreKept) {
  // Two unit boxes side by side, touching along x = 1: the first one's faces moved (a corner
  // unmarked on each), the second's marked. The second's faces on x = 1 and those with an edge
  // there touch the first's boxes; its face on x = 2 does not.
  const PolygonMesh m =
      test_shapes::merged(test_shapes::box({0, 0, 0}, {1, 1, 1}), test_shapes::box({1, 0, 0}, {2, 1, 1}));
  std::vector<char> exact(m.vertices.size(), 1);
  for (std::size_t v = 0; v < 8; ++v) exact[v] = 0;
  // Many marked faces far away, so that fewer than half are moved.
  PolygonMesh far = test_shapes::uv_sphere(12, 0.5);
  for (auto& p : far.vertices) p += Vector3d(10, 0, 0);
  const PolygonMesh all = test_shapes::merged(m, far);
  exact.resize(all.vertices.size(), 1);
  const std::vector<char> kept = mesh::detail::faces_near_moved(all, exact);
  ASSERT_EQ(kept.size(), all.faces.size());
  const std::vector<char> need = needed(all, exact);
  std::size_t touching = 0;
  for (std::size_t f = 0; f < all.faces.size(); ++f) {
    if (need[f]) {
      EXPECT_NE(kept[f], 0) << "face " << f;
    }
    if (f >= m.faces.size() / 2 && f < m.faces.size() && need[f]) ++touching;
  }
  EXPECT_GE(touching, 5U);  // the second box's faces at x = 1 (their boxes touch the first's)
  for (std::size_t f = m.faces.size(); f < all.faces.size(); ++f) EXPECT_EQ(kept[f], 0) << "far face " << f;
}

TEST(FacesNearMoved, AMovedFaceOverManyCellsKeepsTheFacesItMeets) {
  // Moved: a small sphere (its faces set the cells' size) and a long thin box whose long faces
  // meet hundreds of those cells (marked at a coarser level); marked: a ball pierced by the box
  // at its far end, which only the long faces' boxes meet, and a ball beside it that none meets.
  PolygonMesh small = test_shapes::uv_sphere(64, 0.2);
  PolygonMesh rod = test_shapes::box({-1, -1, -1}, {150, -0.9, -0.9});
  PolygonMesh ball = test_shapes::uv_sphere(96, 1), aside = test_shapes::uv_sphere(96, 1);
  for (auto& p : ball.vertices) p += Vector3d(140, -1, -1);
  for (auto& p : aside.vertices) p += Vector3d(140, 30, -1);
  const PolygonMesh moved_part = test_shapes::merged(small, rod);
  const PolygonMesh m = test_shapes::merged(test_shapes::merged(moved_part, ball), aside);
  std::vector<char> exact(m.vertices.size(), 1);
  for (std::size_t v = 0; v < moved_part.vertices.size(); ++v) exact[v] = 0;
  const std::vector<char> kept = mesh::detail::faces_near_moved(m, exact);
  ASSERT_EQ(kept.size(), m.faces.size());
  const std::vector<char> need = needed(m, exact);
  const std::size_t ball_begin = moved_part.faces.size(), aside_begin = ball_begin + ball.faces.size();
  std::size_t ball_needed = 0;
  for (std::size_t f = ball_begin; f < aside_begin; ++f) {
    if (need[f]) {
      ++ball_needed;
      EXPECT_NE(kept[f], 0) << "face " << f << " meets the rod's box but was left out";
    }
  }
  EXPECT_GT(ball_needed, 0U);
  for (std::size_t f = aside_begin; f < m.faces.size(); ++f) EXPECT_EQ(kept[f], 0) << "face " << f << " is far";
}

TEST(FacesNearMoved, InvalidFacesAreKeptAndMostlyMovedMeshesKeepAll) {
  PolygonMesh m = test_shapes::merged(test_shapes::box({0, 0, 0}, {1, 1, 1}), test_shapes::uv_sphere(16, 0.5));
  std::vector<char> exact(m.vertices.size(), 1);
  exact[0] = 0;
  m.faces.push_back({0, 1});                          // too few corners
  m.faces.push_back({2, 3, int(m.vertices.size())});  // an index out of range
  const std::vector<char> kept = mesh::detail::faces_near_moved(m, exact);
  ASSERT_EQ(kept.size(), m.faces.size());
  EXPECT_NE(kept[m.faces.size() - 1], 0);
  EXPECT_NE(kept[m.faces.size() - 2], 0);
  // Half or more of the faces moved: empty (all kept). Marks of the wrong count: likewise.
  const std::vector<char> none(m.vertices.size(), 0);
  EXPECT_TRUE(mesh::detail::faces_near_moved(m, none).empty());
  EXPECT_TRUE(mesh::detail::faces_near_moved(m, std::vector<char>(m.vertices.size() - 1, 1)).empty());
}

}  // namespace
}  // namespace sculpt
