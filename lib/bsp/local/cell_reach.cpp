#include "bsp/local/cell_reach.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace sculpt::bsp::detail {

namespace {

using Point = std::array<double, 3>;
constexpr std::size_t kMaxPoints = 64;  // a clip adds one point per wall; more corners: undecided

}  // namespace

bool certainly_reaches(kernel::PolygonView poly, const CellBounds& bounds) {
  const std::size_t n = poly.corners.size();
  if (n < 3 || n + 6 > kMaxPoints) return false;
  // The corners' box and largest error bound (a corner without an approximation: undecided).
  double lo[3], hi[3], err = 0, sum = 0;  // sum: NaN if a coordinate is (min and max skip NaN)
  {
    const kernel::ApproxPoint a = poly.corners[0].at();
    lo[0] = hi[0] = a.x, lo[1] = hi[1] = a.y, lo[2] = hi[2] = a.z;
  }
  for (const kernel::Corner& c : poly.corners) {
    const kernel::ApproxPoint a = c.at();
    if (!(a.err >= 0)) return false;
    err = std::max(err, a.err);
    sum += a.x + a.y + a.z;
    lo[0] = std::min(lo[0], a.x), hi[0] = std::max(hi[0], a.x);
    lo[1] = std::min(lo[1], a.y), hi[1] = std::max(hi[1], a.y);
    lo[2] = std::min(lo[2], a.z), hi[2] = std::max(hi[2], a.z);
  }
  // The walls some corner may lie beyond; with none, every corner is inside and so is the polygon.
  if (!std::isfinite(sum)) return false;
  bool crossed[3][2];
  bool any = false;
  double magnitude = 1;
  for (int k = 0; k < 3; ++k) {
    const double wall_lo = 0.5 * double(bounds.lo[k]), wall_hi = 0.5 * double(bounds.hi[k]);
    crossed[k][0] = !(lo[k] - err > wall_lo);
    crossed[k][1] = !(hi[k] + err < wall_hi);
    any = any || crossed[k][0] || crossed[k][1];
    magnitude = std::max({magnitude, std::fabs(lo[k]), std::fabs(hi[k]), std::fabs(wall_lo), std::fabs(wall_hi)});
  }
  if (!any) return true;
  std::array<Point, kMaxPoints> buffer[2];
  for (std::size_t i = 0; i < n; ++i) {
    const kernel::ApproxPoint a = poly.corners[i].at();
    buffer[0][i] = {a.x, a.y, a.z};
  }
  // Sutherland & Hodgman against the walls crossed (lo[k] / 2 <= x_k <= hi[k] / 2). Every point made
  // lies within a few units in the last place of a point on an edge of the previous polygon, so
  // within 4 u |x| per wall of the convex hull of the approximations; misjudged sides near a wall
  // only change which part is kept.
  std::size_t count = n;
  int current = 0;
  for (int k = 0; k < 3; ++k)
    for (int upper = 0; upper < 2; ++upper) {
      if (!crossed[k][upper]) continue;
      const double wall = 0.5 * double(upper ? bounds.hi[k] : bounds.lo[k]);
      const double sign = upper ? 1.0 : -1.0;  // inside: sign (x_k - wall) <= 0
      const std::array<Point, kMaxPoints>& in = buffer[current];
      std::array<Point, kMaxPoints>& out = buffer[1 - current];
      std::size_t m = 0;
      for (std::size_t i = 0; i < count; ++i) {
        const Point& p = in[i];
        const Point& q = in[i + 1 == count ? 0 : i + 1];
        const double dp = sign * (p[std::size_t(k)] - wall), dq = sign * (q[std::size_t(k)] - wall);
        if (m + 2 > kMaxPoints) return false;
        if (dp <= 0) out[m++] = p;
        if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
          const double t = dp / (dp - dq);
          Point r;
          for (std::size_t j = 0; j < 3; ++j) r[j] = p[j] + t * (q[j] - p[j]);
          r[std::size_t(k)] = wall;
          out[m++] = r;
        }
      }
      if (m == 0) return false;
      count = m;
      current = 1 - current;
    }
  // The centre of what is left: a convex combination of the points, so within the error of the
  // clip (at most 24 u |x|), the summation's ((count + 2) u |x|) and the approximations' bound of
  // a point of the polygon. 2^-44 |x| covers the first two for up to 64 points.
  Point centre = {0, 0, 0};
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t j = 0; j < 3; ++j) centre[j] += buffer[current][i][j];
  const double margin = err * (1 + 0x1p-20) + magnitude * 0x1p-44;
  for (std::size_t j = 0; j < 3; ++j) {
    const double c = centre[j] / double(count);
    if (!(c - margin > 0.5 * double(bounds.lo[j]) && c + margin < 0.5 * double(bounds.hi[j]))) return false;
  }
  return true;
}

}  // namespace sculpt::bsp::detail
