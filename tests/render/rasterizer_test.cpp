// The z-buffer's coverage rule: polygons that tile a region cover every pixel centre inside it
// exactly once, including centres exactly on shared edges and at shared corners.
#include <gtest/gtest.h>

#include <random>

#include "render/detail/rasterizer.hpp"

namespace sculpt::render::detail {
namespace {

/// Coverage counts of polygons drawn one by one into fresh buffers.
std::vector<int> coverage(const std::vector<ScreenPolygon>& polygons, int w, int h) {
  std::vector<int> count(static_cast<std::size_t>(w) * h, 0);
  for (const ScreenPolygon& p : polygons) {
    DepthBuffer buffer(w, h);
    rasterize(buffer, p);
    for (std::size_t i = 0; i < count.size(); ++i) count[i] += buffer.face[i] >= 0;
  }
  return count;
}

/// A grid of (jittered or exact) points triangulated into triangles clockwise on screen.
std::vector<ScreenPolygon> triangulated_grid(int n, double step, double jitter, std::uint32_t seed, double origin) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::vector<Eigen::Vector2d> p;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      p.emplace_back(origin + i * step + (border ? 0 : u(rng)), origin + j * step + (border ? 0 : u(rng)));
    }
  auto at = [&](int i, int j) { return p[static_cast<std::size_t>(j * (n + 1) + i)]; };
  std::vector<ScreenPolygon> out;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Clockwise on screen (y down) = counter-clockwise in a y-up frame: a, b, c with
      // (b - a) x (c - a) < 0 in screen coordinates.
      const bool flip = ((i + j) % 2) == 0;
      if (flip) {
        out.push_back({.corners = {at(i, j), at(i, j + 1), at(i + 1, j + 1)}, .id = 1});
        out.push_back({.corners = {at(i, j), at(i + 1, j + 1), at(i + 1, j)}, .id = 1});
      } else {
        out.push_back({.corners = {at(i, j), at(i, j + 1), at(i + 1, j)}, .id = 1});
        out.push_back({.corners = {at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)}, .id = 1});
      }
    }
  return out;
}

void expect_tiled_once(const std::vector<ScreenPolygon>& polygons, double lo, double hi, int size) {
  const std::vector<int> count = coverage(polygons, size, size);
  int inside = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      const int c = count[static_cast<std::size_t>(y * size + x)];
      if (cx > lo && cx < hi && cy > lo && cy < hi) {
        ++inside;
        ASSERT_EQ(c, 1) << "pixel " << x << ", " << y;
      } else if (cx < lo || cx > hi || cy < lo || cy > hi) {
        ASSERT_EQ(c, 0) << "pixel " << x << ", " << y;
      } else {
        ASSERT_LE(c, 1) << "pixel " << x << ", " << y;  // on the outer border
      }
    }
  EXPECT_GT(inside, 0);
}

TEST(Rasterizer, CornersOnPixelCentresCoverEachCentreOnce) {
  // Every corner and every edge of the grid passes through pixel centres.
  expect_tiled_once(triangulated_grid(12, 4.0, 0.0, 1, 2.5), 2.5, 50.5, 56);
}

TEST(Rasterizer, JitteredTrianglesCoverEachCentreOnce) {
  // Jitter 1.2 on a step of 5 keeps every triangle clockwise (checked), so they tile the square.
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const auto triangles = triangulated_grid(10, 5.0, 1.2, seed, 3.25);
    for (const auto& t : triangles) {
      const Eigen::Vector2d u = t.corners[1] - t.corners[0], v = t.corners[2] - t.corners[0];
      ASSERT_LT(u.x() * v.y() - u.y() * v.x(), 0);
    }
    expect_tiled_once(triangles, 3.25, 53.25, 58);
  }
}

TEST(Rasterizer, ConvexPolygonsSharingEdges) {
  // A regular 9-gon fanned from a pixel centre into convex quadrilaterals and triangles.
  const Eigen::Vector2d c(30.5, 30.5);
  std::vector<Eigen::Vector2d> ring;
  for (int k = 0; k < 9; ++k) {
    const double a = -2 * 3.141592653589793 * k / 9;  // clockwise on screen
    ring.emplace_back(c.x() + 25 * std::cos(a), c.y() + 25 * std::sin(a));
  }
  std::vector<ScreenPolygon> polygons;
  for (int k = 0; k < 9; k += 3) {
    ScreenPolygon p{.corners = {c}, .id = 1};
    for (int j = k; j <= k + 3; ++j) p.corners.push_back(ring[static_cast<std::size_t>(j % 9)]);
    polygons.push_back(p);
  }
  ScreenPolygon whole{.corners = ring, .id = 1};
  const std::vector<int> parts = coverage(polygons, 64, 64), one = coverage({whole}, 64, 64);
  for (std::size_t i = 0; i < parts.size(); ++i) ASSERT_EQ(parts[i], one[i]) << i;
}

TEST(Rasterizer, NearestWins) {
  DepthBuffer buffer(8, 8);
  rasterize(buffer, {.corners = {{0, 0}, {0, 8}, {8, 8}, {8, 0}}, .dx = 0, .dy = 0, .d0 = 1, .id = 3});
  rasterize(buffer, {.corners = {{2, 2}, {2, 6}, {6, 6}, {6, 2}}, .dx = 0, .dy = 0, .d0 = 2, .id = 4});
  rasterize(buffer, {.corners = {{0, 0}, {0, 8}, {8, 8}, {8, 0}}, .dx = 0, .dy = 0, .d0 = 0, .id = 5});
  EXPECT_EQ(buffer.face[buffer.index(0, 0)], 3);
  EXPECT_EQ(buffer.face[buffer.index(3, 3)], 4);
  EXPECT_EQ(buffer.depth[buffer.index(3, 3)], 2);
}

}  // namespace
}  // namespace sculpt::render::detail
