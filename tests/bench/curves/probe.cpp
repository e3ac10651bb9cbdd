// Timing probe for one case (used while tuning; not part of the documented tables):
//   curves_probe <curve> <n> <m> <mode> [runs]   mode 0 = optimal, 1 = fast (exact_below = 0),
//   2 = DYNAMIC. SCULPT_CURVES_DEBUG=1 prints the solver's probes to stderr.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench_common.hpp"
#include "curves/methods/dynamic_programming.hpp"
#include "curves/methods/fast_linearization.hpp"
#include "curves/optimal/optimal_linearization.hpp"
#include "curves/appendix_b_curves.hpp"

using namespace sculpt::curves;
using namespace sculpt::curves::detail;  // the internal solvers measured here

int main(int argc, char** argv) {
  const std::string name = argc > 1 ? argv[1] : "folium";
  const int n = argc > 2 ? std::atoi(argv[2]) : 3000;
  const int m = argc > 3 ? std::atoi(argv[3]) : 4;
  const int fast = argc > 4 ? std::atoi(argv[4]) : 0;
  const auto curve = make_appendix_b_curve(*appendix_b_curve_from_name(name), {.points = n});
  const auto points = path_points(curve);
  Linearization la;
  const int runs = argc > 5 ? std::atoi(argv[5]) : 1;
  double fastest = 1e300;
  const double ms = bench::median_ms(runs, [&] {
    const bench::Stopwatch watch;
    la = fast == 1 ? fast_linearization(points, m, Norm::LInf, {.exact_below = 0}) : fast == 2 ? dynamic_linearization(points, m, Norm::LInf) : optimal_min_error(points, m, Norm::LInf);
    fastest = std::min(fastest, watch.ms());
  });
  std::printf("%s n=%d m=%d %s: %.3f ms (fastest %.3f) error %.9g probes %d\n", name.c_str(), n, m,
              fast ? "fast" : "optimal", ms, fastest, la.error, la.iterations);
}
