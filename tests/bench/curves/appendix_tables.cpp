// Appendix A, Tables 1-5 of Ihm & Naylor in the paper's layout: LA_0 (INIT), LA_k (ITER) with
// the iteration count k, LA* (exact optimum) and LA_k / LA*, for our sampling of the same curves
// (appendix_b_curves.hpp; the paper's point counts), beside the paper's published figures.
// alpha = 0.5 for INIT/ITER; an extra row gives the best alpha of {0, 0.1, ..., 1} per m.
// Table 3 uses the goblet profile of profiles.hpp (our own rational Bezier design, 237 points
// equally spaced in arc length, disturbed by seeded uniform noise of amplitude 0.01).
//   curves_appendix_tables
#include <cstdio>
#include <string>
#include <vector>

#include "curves/linearize.hpp"
#include "curves/profiles.hpp"
#include "curves/appendix_b_curves.hpp"

using namespace sculpt::curves;

namespace {

struct PaperTable {
  int number;
  const char* figure;
  AppendixBCurve curve;  // ignored for table 3 (goblet)
  std::vector<int> ms;
  std::vector<double> la0, lak;
  std::vector<int> k;
  std::vector<double> optimum;
};

void print_row(const char* label, const std::vector<std::string>& cells) {
  std::printf("| %-14s |", label);
  for (const auto& c : cells) std::printf(" %-15s |", c.c_str());
  std::printf("\n");
}

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.5e", value);
  return buffer;
}

}  // namespace

int main() {
  const std::vector<PaperTable> tables = {
      {1, "Figure 3 (folium)", AppendixBCurve::Folium, {4, 8, 16, 32, 64},
       {5.25619e-1, 2.21325e-1, 8.09768e-2, 2.66073e-2, 8.98677e-3},
       {4.02838e-1, 1.12507e-1, 3.08774e-2, 1.23695e-2, 3.76437e-3}, {5, 9, 17, 16, 14},
       {4.02838e-1, 1.12507e-1, 3.04525e-2, 8.94592e-3, 2.76188e-3}},
      {2, "Figure 4 (cubic)", AppendixBCurve::Cubic, {2, 4, 8, 16, 32, 64},
       {3.41045e-1, 2.24775e-1, 5.47018e-2, 1.42360e-2, 3.80354e-3, 1.19389e-3},
       {3.41045e-1, 9.53494e-2, 2.75688e-2, 8.92481e-3, 2.95337e-3, 8.66971e-4}, {0, 86, 50, 80, 66, 381},
       {2.73563e-1, 8.95572e-2, 2.63278e-2, 6.62991e-3, 2.02041e-3, 5.45924e-4}},
      {3, "Figure 5 (goblet)", AppendixBCurve::Folium, {8, 16, 32, 64},
       {1.03375e-1, 6.11455e-2, 2.95784e-2, 8.24535e-3},
       {6.07749e-2, 2.90067e-2, 7.76577e-3, 5.63440e-3}, {12, 17, 20, 5},
       {5.87190e-2, 2.06813e-2, 5.12219e-3, 1.75973e-3}},
      {4, "Figure 7 (quartic)", AppendixBCurve::Quartic, {4, 8, 16, 32, 64},
       {2.01399e0, 3.63921e-1, 9.66444e-2, 2.67485e-2, 8.39998e-3},
       {1.86220e0, 2.26435e-1, 7.78874e-2, 2.24510e-2, 6.98709e-3}, {4, 32, 16, 10, 8},
       {1.85530e0, 2.26435e-1, 7.60669e-2, 2.05613e-2, 5.69636e-3}},
      {5, "Figure 8 (sextic)", AppendixBCurve::Sextic, {4, 8, 16, 32, 64},
       {7.24214e-1, 1.72242e-1, 5.32029e-2, 1.64083e-2, 1.60168e-2},
       {4.81844e-1, 1.34728e-1, 3.69400e-2, 1.53000e-2, 3.80315e-3}, {15, 15, 13, 2, 11},
       {4.81844e-1, 1.34728e-1, 3.65433e-2, 1.05332e-2, 3.16273e-3}},
  };
  const double alpha = 0.5;
  for (const PaperTable& t : tables) {
    const DigitizedCurve curve = t.number == 3
                                     ? sample_profile(goblet_profile(), {.points = 237, .noise = 0.01, .seed = 1})
                                     : make_appendix_b_curve(t.curve);
    std::printf("### Table %d: the curve in %s, n = %zu, alpha = %.1f\n\n", t.number, t.figure, curve.points.size(),
                alpha);
    std::vector<std::string> ms, la0, lak, la_opt, ratio, p_la0, p_lak, p_opt, p_ratio, best_alpha;
    for (std::size_t c = 0; c < t.ms.size(); ++c) {
      const int m = t.ms[c];
      const auto init = linearize(curve, {.segments = m, .method = Method::Init, .alpha = alpha});
      const auto iter = linearize(curve, {.segments = m, .method = Method::Iter, .alpha = alpha});
      const auto optimal = linearize(curve, {.segments = m, .method = Method::Optimal});
      ms.push_back(std::to_string(m));
      la0.push_back(number(init.error));
      lak.push_back(number(iter.error) + " (" + std::to_string(iter.iterations) + ")");
      la_opt.push_back(number(optimal.error));
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, "%.3f", iter.error / optimal.error);
      ratio.push_back(buffer);
      double best = 1e300, best_a = 0.0;
      for (int a = 0; a <= 10; ++a) {
        const double e = linearize(curve, {.segments = m, .method = Method::Iter, .alpha = a / 10.0}).error;
        if (e < best) {
          best = e;
          best_a = a / 10.0;
        }
      }
      std::snprintf(buffer, sizeof buffer, "%.3f (a=%.1f)", best / optimal.error, best_a);
      best_alpha.push_back(buffer);
      p_la0.push_back(number(t.la0[c]));
      p_lak.push_back(number(t.lak[c]) + " (" + std::to_string(t.k[c]) + ")");
      p_opt.push_back(number(t.optimum[c]));
      std::snprintf(buffer, sizeof buffer, "%.3f", t.lak[c] / t.optimum[c]);
      p_ratio.push_back(buffer);
    }
    print_row("m", ms);
    std::printf("|---|");
    for (std::size_t c = 0; c < ms.size(); ++c) std::printf("---|");
    std::printf("\n");
    print_row("LA_0", la0);
    print_row("LA_k (k)", lak);
    print_row("LA*", la_opt);
    print_row("LA_k/LA*", ratio);
    print_row("best alpha", best_alpha);
    print_row("paper LA_0", p_la0);
    print_row("paper LA_k (k)", p_lak);
    print_row("paper LA*", p_opt);
    print_row("paper LA_k/LA*", p_ratio);
    std::printf("\n");
  }
}
