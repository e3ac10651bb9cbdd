// Fast near-optimal method (docs/benchmarks.md, "Curves"):
//  1. n = 1e6, m = 1000 on every test curve: wall time (median of 3) and error;
//  2. quality: error / optimum for m in {4, 8, 16, 32, 64} on every Appendix-B curve, with the
//     approximate pipeline forced (exact_below = 0) at the paper's n and at n = 5000, and the
//     default (exact below 20000 points) at the paper's n.
//   curves_fast [quick]
#include <algorithm>
#include <cstdio>
#include <string>

#include "bench_common.hpp"
#include "curves/linearize.hpp"
#include "curves/methods/fast_linearization.hpp"
#include "curves/optimal/optimal_linearization.hpp"
#include "curves/appendix_b_curves.hpp"

using namespace sculpt::curves;
using namespace sculpt::curves::detail;  // the internal solvers measured here

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "quick";
  std::printf("## 1. n = 1e6, m = 1000\n\n| curve | ms (median of 3) | error |\n|---|---|---|\n");
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = quick ? 100000 : 1000000});
    Linearization la;
    const double t = bench::median_ms(quick ? 1 : 3, [&] { la = linearize(curve, {.segments = 1000, .method = Method::Fast}); });
    std::printf("| %s | %.0f | %.6g |\n", appendix_b_curve_name(which).c_str(), t, la.error);
    std::fflush(stdout);
  }
  std::printf("\n## 2. error / optimum (approximate pipeline forced)\n\n");
  std::printf("| curve | n | m=4 | m=8 | m=16 | m=32 | m=64 |\n|---|---|---|---|---|---|---|\n");
  double worst = 0.0;
  for (AppendixBCurve which : all_appendix_b_curves())
    for (int n : {paper_point_count(which), 5000}) {
      if (quick && n > 1000) continue;
      const DigitizedCurve curve = make_appendix_b_curve(which, {.points = n});
      const auto points = path_points(curve);
      std::printf("| %s | %d |", appendix_b_curve_name(which).c_str(), n);
      for (int m : {4, 8, 16, 32, 64}) {
        const double optimum = optimal_min_error(points, m, Norm::LInf).error;
        const double fast = fast_linearization(points, m, Norm::LInf, {.exact_below = 0}).error;
        worst = std::max(worst, fast / optimum);
        std::printf(" %.4f |", fast / optimum);
        std::fflush(stdout);
      }
      std::printf("\n");
    }
  std::printf("\nworst ratio: %.4f (default settings at the paper's n are exact: ratio 1)\n", worst);
}
