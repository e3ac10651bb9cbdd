#include "bsp/convex_path.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "base/errors.hpp"
#include "mesh/predicates.hpp"

namespace sculpt {
namespace {

void check_finite(const Eigen::Vector2d& p, std::size_t i) {
  if (!p.allFinite()) throw InvalidInput("path vertex " + std::to_string(i) + " is not finite");
}

}  // namespace

double ConvexPath::area() const {
  double twice = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const auto& p = vertices[i];
    const auto& q = vertices[(i + 1) % vertices.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

ConvexPath circular_path(int n, double radius) {
  if (!std::isfinite(radius) || !(radius > 0.0)) throw InvalidInput("circle path: radius must be finite and > 0");
  return ellipse_path(radius, radius, n);
}

ConvexPath ellipse_path(double a, double b, int n) {
  if (n < 3) throw InvalidInput("path needs at least 3 edges, got " + std::to_string(n));
  if (!std::isfinite(a) || !std::isfinite(b) || !(a > 0.0) || !(b > 0.0))
    throw InvalidInput("ellipse path: semi-axes must be finite and > 0");
  ConvexPath path;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    path.vertices.emplace_back(a * std::cos(t), b * std::sin(t));
  }
  // cos/sin rounding could in principle spoil strict convexity for huge n: validate all the same.
  return polygon_path(std::move(path.vertices));
}

ConvexPath polygon_path(std::vector<Eigen::Vector2d> v) {
  const std::size_t n = v.size();
  if (n < 3) throw InvalidInput("path needs at least 3 vertices, got " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i) check_finite(v[i], i);
  for (std::size_t i = 0; i < n; ++i)
    if (v[i] == v[(i + 1) % n])
      throw InvalidInput("path vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
                         " coincide");
  // Orientation of the first non-collinear turn decides; every turn must then agree.
  const int first = orient2d(v[n - 1], v[0], v[1]);
  if (first < 0) {
    std::vector<Eigen::Vector2d> reversed(v.rbegin(), v.rend());
    v = std::move(reversed);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const int turn = orient2d(v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
    if (turn == 0)
      throw InvalidInput("path is not strictly convex: vertex " + std::to_string(i) +
                         " is collinear with its neighbours");
    if (turn < 0)
      throw InvalidInput("path is not convex: the turn at vertex " + std::to_string(i) +
                         " goes the other way");
  }
  // All turns left: convex iff the edge directions turn around exactly once, i.e. the sign of
  // the edges' y components changes exactly twice around the polygon (exact comparisons).
  int changes = 0, last = 0;
  for (std::size_t pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < n; ++i) {
      const int s = (v[(i + 1) % n].y() > v[i].y()) - (v[(i + 1) % n].y() < v[i].y());
      if (s == 0) continue;
      if (last != 0 && s != last && pass == 1) ++changes;
      last = s;
    }
  if (changes != 2)
    throw InvalidInput("path is not convex: its boundary winds " + std::to_string(changes / 2) +
                       " times around its interior");
  return ConvexPath{std::move(v)};
}

}  // namespace sculpt
