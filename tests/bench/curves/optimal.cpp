// Optimal solver benchmarks (docs/benchmarks.md, "Curves"):
//  1. the paper's case n = 404, m = 64 (and the other Appendix-B curves at their n, m = 64):
//     DYNAMIC vs the optimal solver in the same run, errors compared;
//  2. n = 5000, m = 300 on every test curve;
//  3. growth of the optimal solver's time with n (1e3 .. 1e5) and m, cases predicted to take
//     longer than 20 s are skipped and marked;
//  4. the worst case we know: points scattered uniformly at random (no smoothness to prune by).
//   curves_optimal [quick | paper]   (paper: part 1 only, full run counts; for repeated runs)
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "bench_common.hpp"
#include "curves/linearize.hpp"
#include "curves/appendix_b_curves.hpp"

using namespace sculpt::curves;

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "quick";
  const bool paper_only = argc > 1 && std::string(argv[1]) == "paper";
  std::printf("## 1. DYNAMIC vs optimal, m = 64, paper point counts\n\n");
  std::printf("| curve | n | DYNAMIC ms | optimal ms | speed-up | equal error |\n|---|---|---|---|---|---|\n");
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which);
    Linearization dynamic, optimal;
    // Interleaved (one DYNAMIC run, then 17 optimal runs, three times) so that both see the
    // same conditions on a shared machine; medians of 3 and of 51 runs.
    std::vector<double> dynamic_ms, optimal_ms;
    for (int round = 0; round < (quick ? 1 : 3); ++round) {
      dynamic_ms.push_back(bench::median_ms(1, [&] {
        dynamic = linearize(curve, {.segments = 64, .method = Method::Dynamic});
      }));
      for (int r = 0; r < (quick ? 5 : 17); ++r)
        optimal_ms.push_back(bench::median_ms(1, [&] {
          optimal = linearize(curve, {.segments = 64, .method = Method::Optimal});
        }));
    }
    const double t_dynamic = bench::median(dynamic_ms), t_optimal = bench::median(optimal_ms);
    std::printf("| %s | %zu | %.1f | %.3f | %.0fx | %s (%.6g) |\n", appendix_b_curve_name(which).c_str(), curve.points.size(),
                t_dynamic, t_optimal, t_dynamic / t_optimal, dynamic.error == optimal.error ? "yes" : "NO",
                optimal.error);
  }

  if (paper_only) return 0;
  std::printf("\n## 2. optimal, n = 5000, m = 300\n\n| curve | ms (median of 5) | error | probes |\n|---|---|---|---|\n");
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = 5000});
    Linearization la;
    const double t = bench::median_ms(quick ? 1 : 5, [&] { la = linearize(curve, {.segments = 300}); });
    std::printf("| %s | %.1f | %.6g | %d |\n", appendix_b_curve_name(which).c_str(), t, la.error, la.iterations);
  }

  std::printf("\n## 3. growth (cubic and helix), ms of one run\n\n");
  const int sizes[] = {1000, 3000, 10000, 30000, 100000};
  for (AppendixBCurve which : {AppendixBCurve::Cubic, AppendixBCurve::Helix}) {
    std::printf("%s:\n\n| n | m=16 | m=64 | m=300 | m=1000 | m=n/20 |\n|---|---|---|---|---|---|\n",
                appendix_b_curve_name(which).c_str());
    std::map<int, std::pair<int, double>> previous;  // column -> (n, ms)
    for (int n : sizes) {
      if (quick && n > 10000) break;
      const DigitizedCurve curve = make_appendix_b_curve(which, {.points = n});
      std::printf("| %d |", n);
      const int columns[] = {16, 64, 300, 1000, n / 20};
      for (int c = 0; c < 5; ++c) {
        const int m = columns[c];
        if (m >= n) {
          std::printf(" - |");
          continue;
        }
        if (const auto it = previous.find(c); it != previous.end()) {
          const double ratio = static_cast<double>(n) / it->second.first;
          const double predicted = it->second.second * ratio * ratio;
          if (it->second.second < 0 || predicted > 20000.0) {
            std::printf(" skipped (> 20 s predicted) |");
            previous[c] = {n, -1.0};
            continue;
          }
        }
        Linearization la;
        const double t = bench::median_ms(1, [&] { la = linearize(curve, {.segments = m}); });
        std::printf(" %.0f |", t);
        std::fflush(stdout);
        previous[c] = {n, t};
      }
      std::printf("\n");
    }
    std::printf("\n");
  }

  std::printf("## 4. worst case: scattered points, one run\n\n| points | n | m | DYNAMIC ms | optimal ms | equal error |\n"
              "|---|---|---|---|---|---|\n");
  for (const auto& [n, m, dimension] : {std::tuple{400, 64, 2}, std::tuple{400, 64, 3}, std::tuple{1000, 100, 2}}) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    DigitizedCurve curve;
    curve.dimension = dimension;
    for (int k = 0; k < n; ++k) curve.points.push_back({u(rng), u(rng), dimension == 3 ? u(rng) : 0.0});
    Linearization dynamic, optimal;
    const double t_dynamic = bench::median_ms(1, [&] { dynamic = linearize(curve, {.segments = m, .method = Method::Dynamic}); });
    const double t_optimal = bench::median_ms(1, [&] { optimal = linearize(curve, {.segments = m}); });
    std::printf("| uniform in [-1,1]^%d | %d | %d | %.0f | %.0f | %s |\n", dimension, n, m, t_dynamic, t_optimal,
                dynamic.error == optimal.error ? "yes" : "NO");
  }
}
