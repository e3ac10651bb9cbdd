#pragma once
/// \file rasterizer.hpp
/// The z-buffer of pictures (picture.hpp): convex polygons given by screen corners, sampled at
/// pixel centres, the nearest (largest depth) kept. Watertight along shared edges: an edge's
/// function is evaluated in one canonical orientation (its corners in lexicographic order) and
/// negated for the polygon that runs it the other way, so two polygons sharing the edge get
/// opposite values; a centre exactly on the edge goes to the polygon that runs it in the
/// canonical direction (a fixed symbolic perturbation of the sample point, like the top-left
/// rule), so each centre is covered by exactly one of them.

#include <Eigen/Core>
#include <vector>

namespace sculpt::render::detail {

struct DepthBuffer {
  int width = 0;
  int height = 0;
  std::vector<double> depth;  ///< per pixel; -infinity where nothing was drawn
  std::vector<int> face;      ///< per pixel: the id of the nearest polygon, -1 for none

  DepthBuffer(int w, int h);
  [[nodiscard]] std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
};

/// A convex polygon on screen whose corners run clockwise on the screen (pixel rows going down;
/// counter-clockwise seen with y up, as a front face's corners from outside) and its depth
/// plane depth(x, y) = dx * x + dy * y + d0.
struct ScreenPolygon {
  std::vector<Eigen::Vector2d> corners;
  double dx = 0, dy = 0, d0 = 0;
  int id = 0;
};

/// Draws the polygon into the buffer: every pixel centre inside it (ties as above) whose depth
/// is larger than the stored one. Corners that repeat consecutively are skipped.
void rasterize(DepthBuffer& buffer, const ScreenPolygon& polygon);

}  // namespace sculpt::render::detail
