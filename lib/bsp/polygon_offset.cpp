#include "bsp/polygon_offset.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/extrude.hpp"
#include "bsp/hull.hpp"
#include "bsp/set_operations.hpp"
#include "mesh/predicates.hpp"

namespace sculpt {
namespace {

using OffsetRing = std::vector<Eigen::Vector2d>;

/// The polygon's vertices snapped to the grid (world units), repeats dropped, counter-clockwise.
OffsetRing offset_input_ring(const OffsetRing& polygon, const kernel::Grid& grid) {
  OffsetRing ring;
  for (const Eigen::Vector2d& p : polygon) {
    const kernel::GridPoint g = grid.snap(Eigen::Vector3d(p.x(), p.y(), 0.0));
    const Eigen::Vector2d q = grid.to_world(g).head<2>();
    if (ring.empty() || q != ring.back()) ring.push_back(q);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) throw InvalidInput("offset: the polygon needs at least 3 distinct points");
  // Twice the signed area in grid units, exactly (products of grid coordinates fit 128 bits).
  kernel::Int128 area = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
    const auto ax = std::int64_t(grid.to_grid(a.x())), ay = std::int64_t(grid.to_grid(a.y()));
    const auto bx = std::int64_t(grid.to_grid(b.x())), by = std::int64_t(grid.to_grid(b.y()));
    area += kernel::Int128(ax) * by - kernel::Int128(bx) * ay;
  }
  if (area == 0) throw InvalidInput("offset: the polygon has zero area");
  if (area < 0) std::reverse(ring.begin(), ring.end());
  return ring;
}

Eigen::Vector2d offset_turned(const Eigen::Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

/// The slab over the convex hull of `corners` from z = 0 to `height`.
Solid offset_slab(const OffsetRing& corners, double height, const kernel::Grid& grid) {
  std::vector<Eigen::Vector3d> points;
  for (double z : {0.0, height})
    for (const Eigen::Vector2d& p : corners) points.emplace_back(p.x(), p.y(), z);
  return hull(points, grid);
}

/// The wedge at vertex v between the unit offset directions m1 and m2 (turning by angle
/// `theta` in (0, pi) in direction `sense`, +1 counter-clockwise), at distance d.
OffsetRing offset_wedge(const Eigen::Vector2d& v, const Eigen::Vector2d& m1, const Eigen::Vector2d& m2, double theta,
                        double sense, double d, const PolygonOffsetOptions& options) {
  OffsetRing w{v, v + d * m1};
  if (options.join == OffsetJoin::Round) {
    // Edges per full turn as for circles; the small allowance keeps a quarter turn of 32 at 8.
    const double exact = double(options.segments) * theta / (2 * std::numbers::pi);
    const int k = std::max(1, static_cast<int>(std::ceil(exact - 1e-9)));
    for (int j = 1; j < k; ++j) w.push_back(v + d * offset_turned(m1, sense * theta * double(j) / double(k)));
  } else {
    const double half_cos = std::cos(theta / 2), half_sin = std::sin(theta / 2);
    const Eigen::Vector2d bisector = (m1 + m2).normalized();
    if (half_cos * options.miter_limit >= 1.0) {
      w.push_back(v + (d / half_cos) * bisector);  // the corner: distance d / cos(theta / 2)
    } else {
      // Cut across the bisector at distance limit * d: along each offset edge by tau.
      const double tau = (options.miter_limit * d - d * half_cos) / half_sin;
      const Eigen::Vector2d along1 = offset_turned(m1, sense * std::numbers::pi / 2);   // from v + d m1 to the corner
      const Eigen::Vector2d along2 = offset_turned(m2, -sense * std::numbers::pi / 2);  // from v + d m2 to the corner
      w.push_back(v + d * m1 + tau * along1);
      w.push_back(v + d * m2 + tau * along2);
    }
  }
  w.push_back(v + d * m2);
  return w;
}

/// The boundary loops of the solid's top face z = top (its exact vertices rounded), outer loops
/// counter-clockwise first, collinear vertices dropped.
std::vector<OffsetRing> offset_top_loops(const Solid& solid, double top) {
  const PolygonMesh mesh = to_mesh(solid, {.clean = false});
  // Directed edges of the top faces; an edge shared by two fragments cancels its reverse.
  std::map<std::pair<int, int>, int> edges;
  for (const std::vector<int>& f : mesh.faces) {
    if (!std::all_of(f.begin(), f.end(), [&](int i) { return mesh.vertices[std::size_t(i)].z() == top; })) continue;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int a = f[i], b = f[(i + 1) % f.size()];
      if (auto it = edges.find({b, a}); it != edges.end()) {
        if (--it->second == 0) edges.erase(it);
      } else {
        ++edges[{a, b}];
      }
    }
  }
  std::multimap<int, int> next;
  for (const auto& [e, count] : edges)
    for (int c = 0; c < count; ++c) next.emplace(e.first, e.second);
  std::vector<OffsetRing> outer, holes;
  while (!next.empty()) {
    const int start = next.begin()->first;
    std::vector<int> loop;
    int at = start;
    do {
      const auto it = next.find(at);
      if (it == next.end()) throw GeometryError("offset: the result's outline is not closed (internal error)");
      loop.push_back(at);
      at = it->second;
      next.erase(it);
    } while (at != start);
    OffsetRing ring;
    for (int i : loop) ring.push_back(mesh.vertices[std::size_t(i)].head<2>());
    // Drop collinear vertices (exact orientation of the rounded points) until none is left.
    for (bool dropped = true; dropped && ring.size() > 3;) {
      dropped = false;
      for (std::size_t i = 0; i < ring.size() && ring.size() > 3;) {
        const std::size_t n = ring.size();
        if (orient2d(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) == 0) {
          ring.erase(ring.begin() + std::ptrdiff_t(i));
          dropped = true;
        } else {
          ++i;
        }
      }
    }
    double area = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& a = ring[i];
      const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
      area += a.x() * b.y() - b.x() * a.y();
    }
    (area > 0 ? outer : holes).push_back(std::move(ring));
  }
  outer.insert(outer.end(), std::make_move_iterator(holes.begin()), std::make_move_iterator(holes.end()));
  return outer;
}

}  // namespace

std::vector<std::vector<Eigen::Vector2d>> offset_polygon(const std::vector<Eigen::Vector2d>& polygon, double distance,
                                                         const PolygonOffsetOptions& options) {
  if (!std::isfinite(distance)) throw InvalidInput("offset: the distance is not a finite number");
  if (options.segments < 3) throw InvalidInput("offset: segments must be at least 3");
  if (!(options.miter_limit >= 1.0) || !std::isfinite(options.miter_limit))
    throw InvalidInput("offset: the miter limit must be a finite number >= 1");
  const kernel::Grid& grid = options.grid;
  const OffsetRing ring = offset_input_ring(polygon, grid);
  const double height = grid.to_world(1024.0);
  Solid prism;
  try {
    prism = extrude(ring, 0.0, height, grid);
  } catch (const GeometryError& e) {
    std::string message = e.what();
    if (message.starts_with("extrude:")) message = "offset:" + message.substr(8);
    throw GeometryError(message);
  }
  if (distance == 0) return {ring};

  // Offset side: +1 outwards (right of a counter-clockwise ring), -1 inwards.
  const double side = distance > 0 ? 1.0 : -1.0, d = std::abs(distance);
  const std::size_t n = ring.size();
  auto normal = [&](std::size_t i) {  // unit outward normal of edge i -> i + 1
    const Eigen::Vector2d u = (ring[(i + 1) % n] - ring[i]).normalized();
    return Eigen::Vector2d(u.y(), -u.x());
  };
  std::vector<Solid> pieces;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d &a = ring[i], &b = ring[(i + 1) % n];
    const Eigen::Vector2d m = side * d * normal(i);
    pieces.push_back(offset_slab({a, b, b + m, a + m}, height, grid));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& v = ring[i];
    const Eigen::Vector2d u1 = (v - ring[(i + n - 1) % n]).normalized(), u2 = (ring[(i + 1) % n] - v).normalized();
    const double cross = u1.x() * u2.y() - u1.y() * u2.x();
    // The corner opens on the offset side where the boundary turns towards the other side:
    // left (convex) for an outward offset, right (reflex) for an inward one.
    if (side * cross <= 0) continue;
    const double theta = std::atan2(std::abs(cross), u1.dot(u2));
    const OffsetRing w =
        offset_wedge(v, side * normal((i + n - 1) % n), side * normal(i), theta, cross > 0 ? 1.0 : -1.0, d, options);
    pieces.push_back(offset_slab(w, height, grid));
  }
  const Solid result = side > 0 ? [&] {
    pieces.push_back(prism);
    return unite_all(std::move(pieces));
  }()
                                : subtract(prism, unite_all(std::move(pieces)));
  if (result.is_empty()) return {};
  return offset_top_loops(result, height);
}

}  // namespace sculpt
