#include "implicit/detail/interval_arithmetic.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

namespace sculpt::implicit::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// One ulp of v is at most |v| 2^-52, so subtracting that much (rounded to nearest) moves v
// down by at least one ulp; denorm_min covers 0. Cheaper than std::nextafter.
double down(double v, int ulps = 1) {
  if (std::isnan(v)) return -kInf;
  if (!std::isfinite(v)) return v;
  return v - ulps * (std::abs(v) * 0x1p-52 + std::numeric_limits<double>::denorm_min());
}
double up(double v, int ulps = 1) {
  if (std::isnan(v)) return kInf;
  if (!std::isfinite(v)) return v;
  return v + ulps * (std::abs(v) * 0x1p-52 + std::numeric_limits<double>::denorm_min());
}
Interval widen(double lo, double hi, int ulps = 1) { return {down(lo, ulps), up(hi, ulps)}; }

// Largest k with k * period + phase <= v, as a double (exact enough for the ranges we see; the
// result is only used to decide whether an extremum lies in the interval, and a doubtful case
// widens to [-1, 1]).
bool contains_point_of(Interval a, double phase, double period) {
  const double k = std::ceil((a.lo - phase) / period);
  return k * period + phase <= a.hi;
}

}  // namespace

Interval whole_line() { return {-kInf, kInf}; }
Interval point_interval(double v) { return {v, v}; }

Interval add(Interval a, Interval b) { return widen(a.lo + b.lo, a.hi + b.hi); }
Interval sub(Interval a, Interval b) { return widen(a.lo - b.hi, a.hi - b.lo); }
Interval neg(Interval a) { return {-a.hi, -a.lo}; }

Interval mul(Interval a, Interval b) {
  // 0 * inf is NaN: treat as 0 (the factor 0 is exact, the infinite one a bound).
  auto product = [](double u, double v) {
    const double r = u * v;
    return std::isnan(r) ? 0.0 : r;
  };
  const double c[4] = {product(a.lo, b.lo), product(a.lo, b.hi), product(a.hi, b.lo), product(a.hi, b.hi)};
  return widen(*std::min_element(c, c + 4), *std::max_element(c, c + 4));
}

Interval div(Interval a, Interval b) {
  if (b.lo <= 0.0 && 0.0 <= b.hi) return whole_line();
  const double c[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
  for (double v : c)
    if (std::isnan(v)) return whole_line();
  return widen(*std::min_element(c, c + 4), *std::max_element(c, c + 4));
}

Interval pow(Interval a, int exponent) {
  if (exponent == 0) return {1.0, 1.0};
  if (exponent < 0) return div({1.0, 1.0}, pow(a, -exponent));
  // power_by_squaring rounds at most 2 log2(n) times, each within half an ulp.
  const int ulps = 2 * static_cast<int>(std::bit_width(static_cast<unsigned>(exponent)));
  const double l = power_by_squaring(a.lo, exponent), h = power_by_squaring(a.hi, exponent);
  if (exponent % 2 == 1) return widen(l, h, ulps);
  if (a.lo >= 0.0) return widen(l, h, ulps);
  if (a.hi <= 0.0) return widen(h, l, ulps);
  return {0.0, up(std::max(l, h), ulps)};  // even power of an interval around 0
}

Interval sqrt(Interval a, bool& domain_error) {
  if (a.lo < 0.0) domain_error = true;
  if (a.hi < 0.0) return {0.0, 0.0};
  return {std::max(0.0, down(std::sqrt(std::max(a.lo, 0.0)))), up(std::sqrt(a.hi))};
}

Interval sin(Interval a) {
  constexpr double pi = std::numbers::pi;
  if (!std::isfinite(a.lo) || !std::isfinite(a.hi) || a.hi - a.lo >= 2.0 * pi) return {-1.0, 1.0};
  const double s0 = std::sin(a.lo), s1 = std::sin(a.hi);
  double lo = std::min(s0, s1), hi = std::max(s0, s1);
  Interval r = widen(lo, hi, 2);
  if (contains_point_of(a, 0.5 * pi, 2.0 * pi)) r.hi = 1.0;   // a maximum at pi/2 + 2k pi
  if (contains_point_of(a, -0.5 * pi, 2.0 * pi)) r.lo = -1.0;  // a minimum at -pi/2 + 2k pi
  // The computed pi/2 + 2k pi is not exact: within a few ulps of an extremum, take it.
  if (r.hi > 1.0 - 1e-12) r.hi = 1.0;
  if (r.lo < -1.0 + 1e-12) r.lo = -1.0;
  return {std::max(r.lo, -1.0), std::min(r.hi, 1.0)};
}

Interval cos(Interval a) {
  constexpr double pi = std::numbers::pi;
  if (!std::isfinite(a.lo) || !std::isfinite(a.hi) || a.hi - a.lo >= 2.0 * pi) return {-1.0, 1.0};
  const double c0 = std::cos(a.lo), c1 = std::cos(a.hi);
  Interval r = widen(std::min(c0, c1), std::max(c0, c1), 2);
  if (contains_point_of(a, 0.0, 2.0 * pi)) r.hi = 1.0;
  if (contains_point_of(a, pi, 2.0 * pi)) r.lo = -1.0;
  if (r.hi > 1.0 - 1e-12) r.hi = 1.0;
  if (r.lo < -1.0 + 1e-12) r.lo = -1.0;
  return {std::max(r.lo, -1.0), std::min(r.hi, 1.0)};
}

Interval exp(Interval a) { return {std::max(0.0, down(std::exp(a.lo), 2)), up(std::exp(a.hi), 2)}; }

Interval abs(Interval a) {
  if (a.lo >= 0.0) return a;
  if (a.hi <= 0.0) return neg(a);
  return {0.0, std::max(-a.lo, a.hi)};
}

Interval log(Interval a, bool& domain_error) {
  if (a.lo <= 0.0) domain_error = true;
  if (a.hi <= 0.0) return whole_line();
  return {a.lo <= 0.0 ? -kInf : down(std::log(a.lo), 2), up(std::log(a.hi), 2)};
}

// asin and acos: monotone on [-1, 1]; the part of `a` outside is a domain error.
Interval asin(Interval a, bool& domain_error) {
  if (a.lo < -1.0 || a.hi > 1.0) domain_error = true;
  if (a.hi < -1.0 || a.lo > 1.0) return whole_line();
  return widen(std::asin(std::max(a.lo, -1.0)), std::asin(std::min(a.hi, 1.0)), 2);
}

Interval acos(Interval a, bool& domain_error) {
  if (a.lo < -1.0 || a.hi > 1.0) domain_error = true;
  if (a.hi < -1.0 || a.lo > 1.0) return whole_line();
  return widen(std::acos(std::min(a.hi, 1.0)), std::acos(std::max(a.lo, -1.0)), 2);
}

Interval atan(Interval a) { return widen(std::atan(a.lo), std::atan(a.hi), 2); }

Interval sign(Interval a) {
  auto s = [](double v) { return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0; };
  return {s(a.lo), s(a.hi)};
}

// Off the branch cut (x <= 0, y = 0) atan2 is continuous and, in each of the half planes x > 0,
// y > 0, y < 0, monotone in each argument, so its extremes over a box there lie at corners.
Interval atan2(Interval y, Interval x) {
  constexpr double pi = std::numbers::pi;
  const Interval whole{down(-pi), up(pi)};
  if (!(x.lo > 0.0 || y.lo > 0.0 || y.hi < 0.0)) return whole;
  if (!std::isfinite(x.lo) || !std::isfinite(x.hi) || !std::isfinite(y.lo) || !std::isfinite(y.hi)) return whole;
  const double c[4] = {std::atan2(y.lo, x.lo), std::atan2(y.lo, x.hi), std::atan2(y.hi, x.lo), std::atan2(y.hi, x.hi)};
  return widen(*std::min_element(c, c + 4), *std::max_element(c, c + 4), 2);
}

Interval min(Interval a, Interval b) { return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)}; }
Interval max(Interval a, Interval b) { return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)}; }

}  // namespace sculpt::implicit::detail
