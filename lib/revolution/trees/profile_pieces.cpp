#include "revolution/trees/profile_pieces.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <string>

#include "base/assert.hpp"
#include "base/errors.hpp"
#include "kernel/exact_int.hpp"

namespace sculpt::revolution::detail {
namespace {

using kernel::Int128;
using Point = std::array<std::int64_t, 2>;  // (R, Z) in grid units

int sign(Int128 v) { return (v > 0) - (v < 0); }
/// Twice the signed area of the triangle a, b, c (> 0: counter-clockwise). Exact: |R|, |Z| <= 2^25.
Int128 orient(const Point& a, const Point& b, const Point& c) {
  return Int128(b[0] - a[0]) * (c[1] - a[1]) - Int128(b[1] - a[1]) * (c[0] - a[0]);
}
/// p on the closed segment a-b, given that the three are collinear.
bool within(const Point& a, const Point& b, const Point& p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= p[1] &&
         p[1] <= std::max(a[1], b[1]);
}
/// Whether the closed segments a-b and c-d meet, and a point where they do (approximate).
bool meet(const Point& a, const Point& b, const Point& c, const Point& d, Eigen::Vector2d& where) {
  const int o1 = sign(orient(a, b, c)), o2 = sign(orient(a, b, d));
  const int o3 = sign(orient(c, d, a)), o4 = sign(orient(c, d, b));
  auto at = [&where](const Point& p) {
    where = {double(p[0]), double(p[1])};
    return true;
  };
  if (o1 == 0 && within(a, b, c)) return at(c);
  if (o2 == 0 && within(a, b, d)) return at(d);
  if (o3 == 0 && within(c, d, a)) return at(a);
  if (o4 == 0 && within(c, d, b)) return at(b);
  if (o1 * o2 >= 0 || o3 * o4 >= 0) return false;
  const double t = double(orient(c, d, a)) / double(orient(c, d, a) - orient(c, d, b));
  where = {double(a[0]) + t * double(b[0] - a[0]), double(a[1]) + t * double(b[1] - a[1])};
  return true;
}

std::string point_text(const kernel::Grid& grid, const Eigen::Vector2d& grid_units) {
  std::ostringstream s;
  s << "(r, z) = (" << grid.to_world(grid_units.x()) << ", " << grid.to_world(grid_units.y()) << ")";
  return s.str();
}

/// The polygon is simple: no two edges meet except consecutive ones at their common point.
/// Edges sorted by their lowest z; each is compared with those whose z ranges overlap its own.
void check_simple(const std::vector<Point>& p, const std::vector<int>& index, const kernel::Grid& grid) {
  const std::size_t n = p.size();
  auto zlo = [&](std::size_t e) { return std::min(p[e][1], p[(e + 1) % n][1]); };
  auto zhi = [&](std::size_t e) { return std::max(p[e][1], p[(e + 1) % n][1]); };
  auto edge_text = [&](std::size_t e) {
    return "the edge from point " + std::to_string(index[e]) + " to point " + std::to_string(index[(e + 1) % n]);
  };
  // Consecutive edges a-b, b-c may only share b: collinear and turning back, they overlap.
  for (std::size_t k = 0; k < n; ++k) {
    const Point &a = p[k], &b = p[(k + 1) % n], &c = p[(k + 2) % n];
    const Int128 dot = Int128(a[0] - b[0]) * (c[0] - b[0]) + Int128(a[1] - b[1]) * (c[1] - b[1]);
    if (orient(a, b, c) == 0 && dot > 0)
      throw InvalidInput("closed profile is not a simple polygon: it runs back over itself at point " +
                         std::to_string(index[(k + 1) % n]) + ", " + point_text(grid, {double(b[0]), double(b[1])}));
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t e, std::size_t f) { return zlo(e) < zlo(f); });
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n && zlo(order[j]) <= zhi(order[i]); ++j) {
      const std::size_t e = std::min(order[i], order[j]), f = std::max(order[i], order[j]);
      if (f == e + 1 || (e == 0 && f == n - 1)) continue;  // consecutive: checked above
      Eigen::Vector2d where;
      if (meet(p[e], p[(e + 1) % n], p[f], p[(f + 1) % n], where))
        throw InvalidInput("closed profile is not a simple polygon: " + edge_text(e) + " and " + edge_text(f) +
                           " cross or touch at " + point_text(grid, where) + " (after snapping to the grid of step " +
                           grid.name() + ")");
    }
}

/// A non-horizontal polygon edge, lower end first.
struct Edge {
  Point lo, hi;
  /// r at height z (grid units; approximate).
  [[nodiscard]] double r_at(std::int64_t z) const {
    return double(lo[0]) + double(hi[0] - lo[0]) * (double(z - lo[1]) / double(hi[1] - lo[1]));
  }
};

/// Edge e left of edge f at the height (z0 + z1) / 2 inside a slab both span. Exact: r = N / D with
/// N = 2 R0 (Z1 - Z0) + (R1 - R0) (z0 + z1 - 2 Z0), D = 2 (Z1 - Z0) > 0; |N D| < 2^82.
bool left_of(const Edge& e, const Edge& f, std::int64_t twice_mid) {
  auto num = [twice_mid](const Edge& g) {
    return Int128(2 * g.lo[0]) * (g.hi[1] - g.lo[1]) + Int128(g.hi[0] - g.lo[0]) * (twice_mid - 2 * g.lo[1]);
  };
  return num(e) * (f.hi[1] - f.lo[1]) < num(f) * (e.hi[1] - e.lo[1]);
}

}  // namespace

std::vector<Eigen::Vector2d> closed_profile(const std::vector<Eigen::Vector2d>& profile, const kernel::Grid& grid) {
  for (std::size_t i = 0; i < profile.size(); ++i) check_profile_point(i, profile[i]);
  std::vector<Point> p;
  std::vector<int> index;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const Point q{grid.snap(profile[i].x()), grid.snap(profile[i].y())};
    if (!p.empty() && q == p.back()) continue;  // a repeated point
    p.push_back(q);
    index.push_back(static_cast<int>(i));
  }
  while (p.size() > 1 && p.back() == p.front()) {  // the closing point
    p.pop_back();
    index.pop_back();
  }
  if (p.size() < 3)
    throw InvalidInput("closed profile needs at least 3 distinct points (on the grid of step " + grid.name() +
                       "), got " + std::to_string(p.size()));
  bool flat = true;
  for (std::size_t k = 2; k < p.size() && flat; ++k) flat = orient(p[0], p[1], p[k]) == 0;
  if (flat) throw InvalidInput("closed profile encloses no area: all its points lie on one line");
  check_simple(p, index, grid);
  Int128 area = 0;
  for (std::size_t k = 0; k < p.size(); ++k) area += orient({0, 0}, p[k], p[(k + 1) % p.size()]);
  if (area < 0) std::reverse(p.begin(), p.end());
  std::vector<Eigen::Vector2d> out;
  for (const Point& q : p) out.emplace_back(grid.to_world(double(q[0])), grid.to_world(double(q[1])));
  return out;
}

std::vector<ProfilePiece> monotone_pieces(const std::vector<Eigen::Vector2d>& polygon, const kernel::Grid& grid) {
  const std::size_t n = polygon.size();
  std::vector<Point> p;
  for (const auto& q : polygon) p.push_back({grid.snap(q.x()), grid.snap(q.y())});
  std::vector<std::int64_t> levels;
  for (const Point& q : p) levels.push_back(q[1]);
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  std::vector<Edge> edges;
  for (std::size_t k = 0; k < n; ++k) {
    const Point &a = p[k], &b = p[(k + 1) % n];
    if (a[1] != b[1]) edges.push_back(a[1] < b[1] ? Edge{a, b} : Edge{b, a});
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& e, const Edge& f) { return e.lo[1] < f.lo[1]; });

  // Pieces under construction: per piece the (left, right) edges of its interval in each slab.
  struct Building {
    std::size_t first_slab;
    std::vector<std::array<int, 2>> intervals;
  };
  std::vector<Building> pieces;
  std::vector<int> active;                // edges spanning the current slab, left to right
  std::vector<std::array<int, 2>> below;  // the intervals of the slab below
  std::vector<int> below_piece;           // and their pieces
  std::size_t next = 0;
  for (std::size_t s = 0; s + 1 < levels.size(); ++s) {
    const std::int64_t z0 = levels[s], z1 = levels[s + 1];
    std::erase_if(active, [&](int e) { return edges[e].hi[1] <= z0; });
    for (; next < edges.size() && edges[next].lo[1] == z0; ++next) active.push_back(static_cast<int>(next));
    std::sort(active.begin(), active.end(), [&](int e, int f) { return left_of(edges[e], edges[f], z0 + z1); });
    SCULPT_ASSERT(active.size() % 2 == 0 && !active.empty(), "a simple polygon meets a slab in intervals");
    // Inside a counter-clockwise polygon the region lies between the 1st and 2nd edge, 3rd and 4th, ...
    std::vector<std::array<int, 2>> here;
    for (std::size_t k = 0; k < active.size(); k += 2) here.push_back({active[k], active[k + 1]});
    // An interval continues the first piece below whose top overlaps its bottom (at z0) and that
    // no interval has continued yet; otherwise it starts a piece. Any assignment is correct (a
    // piece's cross-section may jump at a level: a horizontal run of its chains); overlapping
    // neighbours keep the pieces few and connected.
    std::vector<int> here_piece(here.size(), -1);
    std::vector<bool> continued(below.size(), false);
    for (std::size_t i = 0; i < here.size(); ++i) {
      const double a = edges[here[i][0]].r_at(z0), b = edges[here[i][1]].r_at(z0);
      for (std::size_t j = 0; j < below.size() && here_piece[i] < 0; ++j) {
        if (continued[j]) continue;
        const double c = edges[below[j][0]].r_at(z0), d = edges[below[j][1]].r_at(z0);
        if (std::max(a, c) < std::min(b, d)) {
          continued[j] = true;
          here_piece[i] = below_piece[j];
        }
      }
      if (here_piece[i] < 0) {
        here_piece[i] = static_cast<int>(pieces.size());
        pieces.push_back({s, {}});
      }
      pieces[here_piece[i]].intervals.push_back(here[i]);
    }
    below = std::move(here);
    below_piece = std::move(here_piece);
  }

  auto world = [&grid](double v) { return grid.to_world(v); };
  auto slab = [&](const Edge& e, std::int64_t z0, std::int64_t z1) {
    return RevolveSlab{world(double(z0)),      world(double(z1)),      world(e.r_at(z0)),      world(e.r_at(z1)),
                       world(double(e.lo[1])), world(double(e.hi[1])), world(double(e.lo[0])), world(double(e.hi[0]))};
  };
  std::vector<ProfilePiece> out;
  for (const Building& b : pieces) {
    ProfilePiece piece;
    bool on_axis = true;
    for (std::size_t k = 0; k < b.intervals.size(); ++k) {
      const std::int64_t z0 = levels[b.first_slab + k], z1 = levels[b.first_slab + k + 1];
      const Edge &left = edges[b.intervals[k][0]], &right = edges[b.intervals[k][1]];
      piece.inner.push_back(slab(left, z0, z1));
      piece.outer.push_back(slab(right, z0, z1));
      on_axis = on_axis && left.lo[0] == 0 && left.hi[0] == 0;
    }
    if (on_axis) piece.inner.clear();
    out.push_back(std::move(piece));
  }
  return out;
}

}  // namespace sculpt::revolution::detail
