#pragma once
// Helpers shared by the implicit tests and benchmarks: the implicit equations of Ihm & Naylor's
// Appendix B (and Viviani's curve) as expressions, their analytic parametrizations, and checks
// that use only the parametrizations (independent of the tracer): distance to the curve,
// chord heights, and the ideal chord-height point count, the integral of sqrt(kappa / (8 tol)).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "implicit/expression.hpp"
#include "implicit/trace.hpp"

namespace sculpt::implicit::testing {

using Vec = Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

struct CurvePair {
  Expression f, g;
};

/// Fig. 7: f = 36x^2 + 81y^2 + 9z^2 - 324, g = x^2 + y^2 - 3.94.
inline CurvePair fig7_quartic() {
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y(), z = b.z();
  const Term f = b.sub(b.add(b.add(b.mul(b.constant(36), b.pow(x, 2)), b.mul(b.constant(81), b.pow(y, 2))),
                             b.mul(b.constant(9), b.pow(z, 2))),
                       b.constant(324));
  ExpressionBuilder c;
  const Term g = c.sub(c.add(c.pow(c.x(), 2), c.pow(c.y(), 2)), c.constant(3.94));
  return {b.finish(f), c.finish(g)};
}

/// Fig. 8: f = y^2 - x^2 - x^3, g = z - x^2 + x - 2.
inline CurvePair fig8_sextic() {
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y();
  const Term f = b.sub(b.sub(b.pow(y, 2), b.pow(x, 2)), b.pow(x, 3));
  ExpressionBuilder c;
  const Term cx = c.x();
  const Term g = c.sub(c.add(c.sub(c.z(), c.pow(cx, 2)), cx), c.constant(2));
  return {b.finish(f), c.finish(g)};
}

/// Viviani's curve: sphere x^2 + y^2 + z^2 = 4 and cylinder (x - 1)^2 + y^2 = 1.
inline CurvePair viviani() {
  ExpressionBuilder b;
  const Term f = b.sub(b.add(b.add(b.pow(b.x(), 2), b.pow(b.y(), 2)), b.pow(b.z(), 2)), b.constant(4));
  ExpressionBuilder c;
  const Term g = c.sub(c.add(c.pow(c.sub(c.x(), c.constant(1)), 2), c.pow(c.y(), 2)), c.constant(1));
  return {b.finish(f), c.finish(g)};
}

/// A parametrized curve C(t), t in [t0, t1] (closed: C(t1) = C(t0)).
struct Parametrization {
  std::function<Vec(double)> at;
  double t0 = 0.0, t1 = 1.0;
  bool closed = false;
};

/// Fig. 7's upper (sign = +1) or lower (sign = -1) loop.
inline Parametrization fig7_loop(double sign) {
  return {[sign](double phi) {
            const double r = std::sqrt(3.94), x = r * std::cos(phi), y = r * std::sin(phi);
            return Vec(x, y, sign * std::sqrt((324.0 - 36.0 * x * x - 81.0 * y * y) / 9.0));
          },
          0.0, 2.0 * kPi, true};
}

inline Parametrization viviani_curve() {
  return {[](double t) { return Vec(1 + std::cos(t), std::sin(t), 2 * std::sin(t / 2)); }, 0.0, 4.0 * kPi, true};
}

/// Fig. 8's sextic, x = t^2 - 1, y = t x, z = x^2 - x + 2, for t in [-t1, t1].
inline Parametrization fig8_sextic_curve(double t1) {
  return {[](double t) {
            const double x = t * t - 1, y = t * x;
            return Vec(x, y, x * x - x + 2);
          },
          -t1, t1, false};
}

/// Composite Simpson rule with n (even) intervals.
inline double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += f(a + k * h) * (k % 2 == 1 ? 4.0 : 2.0);
  return s * h / 3.0;
}

inline Vec derivative(const Parametrization& c, double t) {
  const double h = 1e-4;  // five-point stencil: error ~ h^4
  return (-c.at(t + 2 * h) + 8.0 * c.at(t + h) - 8.0 * c.at(t - h) + c.at(t - 2 * h)) / (12.0 * h);
}
inline Vec second_derivative(const Parametrization& c, double t) {
  const double h = 1e-3;
  return (-c.at(t + 2 * h) + 16.0 * c.at(t + h) - 30.0 * c.at(t) + 16.0 * c.at(t - h) - c.at(t - 2 * h)) /
         (12.0 * h * h);
}

inline double arc_length(const Parametrization& c) {
  return simpson([&](double t) { return derivative(c, t).norm(); }, c.t0, c.t1, 20000);
}

/// The ideal chord-height point count: the integral of sqrt(kappa / (8 tol)) ds.
inline double ideal_point_count(const Parametrization& c, double tol) {
  return simpson(
      [&](double t) {
        const Vec d1 = derivative(c, t), d2 = second_derivative(c, t);
        const double speed = d1.norm();
        const double kappa = d1.cross(d2).norm() / (speed * speed * speed);
        return std::sqrt(kappa / (8.0 * tol)) * speed;
      },
      c.t0, c.t1, 20000);
}

/// Distance from p to the parametrized curve: dense sampling, then golden-section refinement.
inline double distance_to_curve(const Parametrization& c, const Vec& p, int samples = 4000) {
  double best_t = c.t0, best = std::numeric_limits<double>::infinity();
  const double dt = (c.t1 - c.t0) / samples;
  for (int k = 0; k <= samples; ++k) {
    const double t = c.t0 + k * dt, d = (c.at(t) - p).squaredNorm();
    if (d < best) best = d, best_t = t;
  }
  double a = std::max(c.t0, best_t - dt), b = std::min(c.t1, best_t + dt);
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int k = 0; k < 100; ++k) {
    const double u = b - ratio * (b - a), v = a + ratio * (b - a);
    if ((c.at(u) - p).squaredNorm() < (c.at(v) - p).squaredNorm())
      b = v;
    else
      a = u;
  }
  return std::min(std::sqrt(best), (c.at(0.5 * (a + b)) - p).norm());
}

/// Largest normalized residual max(|f|/|grad f|, |g|/|grad g|) over the points.
inline double max_residual(const CurvePair& c, const std::vector<Vec>& points) {
  double worst = 0.0;
  for (const Vec& p : points) {
    for (const Expression* e : {&c.f, &c.g}) {
      const ValueGradient vg = e->value_gradient(p);
      const double r = vg.value == 0.0 ? 0.0 : std::abs(vg.value) / vg.gradient.norm();
      worst = std::max(worst, r);
    }
  }
  return worst;
}

/// Number of chords of a traced curve.
inline std::size_t chord_count(const TracedCurve& c) { return c.closed ? c.points.size() : c.points.size() - 1; }

inline double polyline_length(const TracedCurve& c) {
  double l = 0.0;
  for (std::size_t k = 0; k < chord_count(c); ++k) l += (c.points[(k + 1) % c.points.size()] - c.points[k]).norm();
  return l;
}

}  // namespace sculpt::implicit::testing
