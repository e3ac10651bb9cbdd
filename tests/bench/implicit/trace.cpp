// Traces the curves of Ihm & Naylor's Appendix B (Fig. 7 quartic, Fig. 8 sextic) and Viviani's
// curve at several tolerances and prints, per curve: points, the ideal chord-height count
// (integral of sqrt(kappa / (8 tol)) on the analytic parametrization), their ratio (target
// <= 1.3), the largest chord height / tol (target <= 1), the largest normalized residual / box
// diagonal (target <= 1e-12) and the time (median of runs). See docs/implicit.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "implicit/implicit_testing.hpp"

using namespace sculpt::implicit;
using namespace sculpt::implicit::testing;

namespace {

struct Case {
  std::string name;
  CurvePair pair;
  Box box;
  std::vector<Parametrization> exact;  // the components, for the ideal count and chord heights
};

double chord_height(const TracedCurve& c, const std::vector<Parametrization>& exact) {
  double worst = 0.0;
  for (std::size_t k = 0; k < chord_count(c); ++k) {
    const Vec mid = 0.5 * (c.points[k] + c.points[(k + 1) % c.points.size()]);
    double d = 1e300;
    for (const Parametrization& p : exact) d = std::min(d, distance_to_curve(p, mid, 2000));
    worst = std::max(worst, d);
  }
  return worst;
}

}  // namespace

int main() {
  std::vector<Case> cases;
  cases.push_back({"fig7-quartic", fig7_quartic(), {.lo = Vec(-2.5, -2.5, -5), .hi = Vec(2.5, 2.5, 5)},
                   {fig7_loop(1.0), fig7_loop(-1.0)}});
  cases.push_back({"viviani", viviani(), {.lo = Vec(-0.5, -1.5, -2.5), .hi = Vec(2.5, 1.5, 2.5)}, {viviani_curve()}});
  cases.push_back({"fig8-sextic", fig8_sextic(), {.lo = Vec(-1.3, -1.5, 1.0), .hi = Vec(0.7, 1.5, 5.0)},
                   {fig8_sextic_curve(std::sqrt(1.7))}});
  std::printf("%-13s %7s %6s %6s %8s %6s %9s %10s %8s %6s %4s\n", "curve", "tol", "comps", "points", "ideal",
              "ratio", "chord/tol", "resid/diag", "ms", "steps", "sing");
  for (const Case& c : cases) {
    const double diagonal = (c.box.hi - c.box.lo).norm();
    for (const double tol : {1e-2, 1e-3, 1e-4}) {
      TraceResult r;
      std::vector<double> ms;
      for (int run = 0; run < 7; ++run) {
        const auto t0 = std::chrono::steady_clock::now();
        r = trace(c.pair.f, c.pair.g, {.box = c.box, .tolerance = tol});
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      std::sort(ms.begin(), ms.end());
      std::size_t points = 0;
      double height = 0.0, residual = 0.0;
      for (const TracedCurve& curve : r.curves) {
        points += curve.closed ? curve.points.size() : curve.points.size() - 1;  // chords
        height = std::max(height, chord_height(curve, c.exact));
        residual = std::max(residual, max_residual(c.pair, curve.points));
      }
      double ideal = 0.0;
      for (const Parametrization& p : c.exact) ideal += ideal_point_count(p, tol);
      std::printf("%-13s %7.0e %6zu %6zu %8.1f %6.3f %9.3f %10.1e %8.2f %6ld %4zu\n", c.name.c_str(), tol,
                  r.curves.size(), points, ideal, points / ideal, height / tol, residual / diagonal, ms[3], r.steps,
                  r.singular_points.size());
    }
  }
  return 0;
}
