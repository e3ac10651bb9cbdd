// Exact min-# (fewest segments under a tolerance) vs Douglas-Peucker and the center-of-mass
// bisection (docs/benchmarks.md, "Curves"). n = 1e5 per curve; tolerance = 1e-5, 1e-4, 1e-3 times
// the curve's bounding-box diagonal.
//   curves_min_count [quick]
#include <cstdio>
#include <string>

#include "bench_common.hpp"
#include "curves/linearize.hpp"
#include "curves/appendix_b_curves.hpp"

using namespace sculpt::curves;

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "quick";
  const int n = quick ? 10000 : 100000;
  std::printf("n = %d\n\n| curve | tol/diag | min-# segs | min-# ms | DP segs (+%%) | DP ms | center segs | center ms |\n"
              "|---|---|---|---|---|---|---|---|\n", n);
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = n});
    Eigen::Vector3d low = curve.points[0], high = low;
    for (const auto& p : curve.points) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    for (double relative : {1e-5, 1e-4, 1e-3}) {
      const double tol = relative * (high - low).norm();
      Linearization exact, dp, center;
      const double t_exact = bench::median_ms(quick ? 1 : 3, [&] { exact = linearize(curve, {.tolerance = tol}); });
      const double t_dp = bench::median_ms(quick ? 1 : 3, [&] {
        dp = linearize(curve, {.tolerance = tol, .method = Method::DouglasPeucker});
      });
      const double t_center = bench::median_ms(1, [&] {
        center = linearize(curve, {.tolerance = tol, .method = Method::CenterOfMass});
      });
      std::printf("| %s | %.0e | %d | %.0f | %d (+%.0f%%) | %.0f | %d | %.0f |\n", appendix_b_curve_name(which).c_str(),
                  relative, exact.segments(), t_exact, dp.segments(),
                  100.0 * (dp.segments() - exact.segments()) / exact.segments(), t_dp, center.segments(), t_center);
      std::fflush(stdout);
    }
  }
}
