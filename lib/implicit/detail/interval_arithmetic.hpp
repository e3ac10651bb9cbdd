#pragma once
/// \file interval_arithmetic.hpp
/// Interval arithmetic with outward rounding for Expression::bounds(): every result bound is
/// moved one or two units in the last place outward, so the exact range is always enclosed
/// (the libm functions are accurate to within one ulp). Used by the tracer to discard boxes in
/// which f = g = 0 cannot hold (Ihm & Naylor sec. 5.1 start points, without user seeds).

#include "implicit/expression.hpp"

namespace sculpt::implicit::detail {

/// x^n by repeated squaring (the value the expression uses too, so bounds and values agree).
/// Inline: the evaluators call it for every power node at every point.
[[nodiscard]] inline double power_by_squaring(double x, int exponent) {
  const bool invert = exponent < 0;
  unsigned n = invert ? -static_cast<unsigned>(exponent) : static_cast<unsigned>(exponent);
  double result = 1.0;
  while (n > 0) {
    if (n & 1U) result *= x;
    x *= x;
    n >>= 1U;
  }
  return invert ? 1.0 / result : result;
}

[[nodiscard]] Interval whole_line();
[[nodiscard]] Interval point_interval(double v);
[[nodiscard]] Interval add(Interval a, Interval b);
[[nodiscard]] Interval sub(Interval a, Interval b);
[[nodiscard]] Interval mul(Interval a, Interval b);
[[nodiscard]] Interval div(Interval a, Interval b);  ///< whole line when b contains 0
[[nodiscard]] Interval neg(Interval a);
[[nodiscard]] Interval pow(Interval a, int exponent);  ///< tight for even powers
[[nodiscard]] Interval sqrt(Interval a, bool& domain_error);
[[nodiscard]] Interval sin(Interval a);
[[nodiscard]] Interval cos(Interval a);
[[nodiscard]] Interval exp(Interval a);
[[nodiscard]] Interval abs(Interval a);
[[nodiscard]] Interval log(Interval a, bool& domain_error);
[[nodiscard]] Interval asin(Interval a, bool& domain_error);
[[nodiscard]] Interval acos(Interval a, bool& domain_error);
[[nodiscard]] Interval atan(Interval a);
[[nodiscard]] Interval sign(Interval a);
[[nodiscard]] Interval atan2(Interval y, Interval x);  ///< [-pi, pi] where the box meets x <= 0, y = 0
[[nodiscard]] Interval min(Interval a, Interval b);
[[nodiscard]] Interval max(Interval a, Interval b);

}  // namespace sculpt::implicit::detail
