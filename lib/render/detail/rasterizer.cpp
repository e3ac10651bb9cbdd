#include "render/detail/rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sculpt::render::detail {
namespace {

/// One edge's inside test in canonical form: value(p) = a * (p.x - o.x) - b * (p.y - o.y) with
/// o the lexicographically smaller corner; `sign` is +1 if the polygon runs the edge from o,
/// else -1. Inside: sign * value > 0, or value == 0 and sign > 0.
struct EdgeTest {
  Eigen::Vector2d o;
  double a = 0, b = 0;
  int sign = 1;
  [[nodiscard]] bool inside(double x, double y) const {
    const double v = a * (x - o.x()) - b * (y - o.y());
    return sign > 0 ? v >= 0 : v < 0;
  }
};

bool less(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
}

}  // namespace

DepthBuffer::DepthBuffer(int w, int h)
    : width(w),
      height(h),
      depth(static_cast<std::size_t>(w) * h, -std::numeric_limits<double>::infinity()),
      face(static_cast<std::size_t>(w) * h, -1) {}

void rasterize(DepthBuffer& buffer, const ScreenPolygon& polygon) {
  const auto& c = polygon.corners;
  std::vector<EdgeTest> edges;
  edges.reserve(c.size());
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Eigen::Vector2d& p = c[k];
    const Eigen::Vector2d& q = c[(k + 1) % c.size()];
    x_lo = std::min(x_lo, p.x()), x_hi = std::max(x_hi, p.x());
    y_lo = std::min(y_lo, p.y()), y_hi = std::max(y_hi, p.y());
    if (p == q) continue;
    const bool forward = less(p, q);
    const Eigen::Vector2d& o = forward ? p : q;
    const Eigen::Vector2d& e = forward ? q : p;
    // Clockwise on screen (y down) means the interior is where (e - o) x (s - o) < 0 for a
    // forward edge; value = -(cross) keeps "inside" positive.
    edges.push_back({.o = o, .a = e.y() - o.y(), .b = e.x() - o.x(), .sign = forward ? 1 : -1});
  }
  if (edges.size() < 3 || !(x_lo < x_hi) || !(y_lo < y_hi)) return;
  // Pixel i's centre is i + 0.5: the rows and columns whose centres lie in the bounding box.
  // Clamped as doubles first: corners far off screen must not overflow the conversion to int.
  auto clamp_to = [](double v, int hi) { return static_cast<int>(std::clamp(v, -1.0, static_cast<double>(hi) + 1)); };
  const int row_lo = std::max(0, clamp_to(std::ceil(y_lo - 0.5), buffer.height));
  const int row_hi = std::min(buffer.height - 1, clamp_to(std::floor(y_hi - 0.5), buffer.height));
  const int col_lo = std::max(0, clamp_to(std::ceil(x_lo - 0.5), buffer.width));
  const int col_hi = std::min(buffer.width - 1, clamp_to(std::floor(x_hi - 0.5), buffer.width));
  if (row_lo > row_hi || col_lo > col_hi) return;
  for (int row = row_lo; row <= row_hi; ++row) {
    const double y = row + 0.5;
    // The span from each edge's crossing (a guess good to far below a pixel), widened by one
    // pixel; the exact tests below decide. Along a row each test is monotone in x, so the
    // inside pixels are contiguous: scan in from both ends.
    double left = col_lo, right = col_hi;
    for (const EdgeTest& e : edges) {
      const double inside_sign = e.sign * e.a;  // d(inside value)/dx
      if (e.a == 0) continue;
      const double x_cross = e.o.x() + e.b * (y - e.o.y()) / e.a;
      if (inside_sign > 0)
        left = std::max(left, std::floor(x_cross - 0.5) - 1);
      else
        right = std::min(right, std::ceil(x_cross - 0.5) + 1);
    }
    if (left > right) continue;
    int x0 = static_cast<int>(left), x1 = static_cast<int>(right);
    auto inside = [&](int col) {
      const double x = col + 0.5;
      for (const EdgeTest& e : edges)
        if (!e.inside(x, y)) return false;
      return true;
    };
    while (x0 <= x1 && !inside(x0)) ++x0;
    while (x1 >= x0 && !inside(x1)) --x1;
    const double row_depth = polygon.dy * y + polygon.d0;
    for (int col = x0; col <= x1; ++col) {
      const double d = polygon.dx * (col + 0.5) + row_depth;
      const std::size_t i = buffer.index(col, row);
      if (d > buffer.depth[i]) {
        buffer.depth[i] = d;
        buffer.face[i] = polygon.id;
      }
    }
  }
}

}  // namespace sculpt::render::detail
