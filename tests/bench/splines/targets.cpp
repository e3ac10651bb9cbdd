// Prints the figures of issue 15's targets: iterations, rms/max distances, times.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <Eigen/Dense>

#include "common.hpp"
#include "splines/analytic.hpp"
#include "splines/splines.hpp"

using namespace sculpt::splines;
using V = Eigen::Vector3d;
namespace t = sculpt::splines::testing;
constexpr double kPi = std::numbers::pi;

using sculpt::splines::bench::ellipse_offset;
using sculpt::splines::testing::interpolant;
namespace {
double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
std::vector<V> points_of(const t::Curve3& c, int n) {
  std::vector<V> p(n);
  for (int i = 0; i < n; ++i) p[i] = c(2 * kPi * i / n)[0];
  return p;
}
std::vector<V> ring(int n, double r) { return points_of(t::ellipse(r, r), n); }
int rms_steps(const FitResult& r, double fraction) {
  for (const auto& h : r.history)
    if (h.rms_distance <= (1 + fraction) * r.history.back().rms_distance) return h.iteration;
  return -1;
}
int objective_steps(const FitResult& r, double fraction) {
  for (const auto& h : r.history)
    if (h.objective <= (1 + fraction) * r.history.back().objective) return h.iteration;
  return -1;
}
}  // namespace

int main() {
  {
    const BSpline e = interpolant(t::ellipse(2, 1), 96);
    for (double d : {-0.3, 0.2, 0.5, 1.0, -0.6}) {
      const auto t0 = std::chrono::steady_clock::now();
      const OffsetResult r = offset_curve(e, d, {.max_controls = 32});
      const double ms = ms_since(t0);
      double worst = 0;  // one-sided, exact (analytic offset; for d = -0.6 includes the corner regions)
      for (const V& x : sample(r.curve, 400)) worst = std::max(worst, t::exact_distance(ellipse_offset(d), x, 0, 2 * kPi, false, 1000));
      std::printf("ellipse 2x1 offset d = %+.1f: %d controls, %zu corners, reported two-sided error %.3e, exact one-sided %.3e, %d steps, %.0f ms\n", d,
                  r.curve.control_count(), r.corners.size(), r.max_error, worst, static_cast<int>(r.history.size()) - 1, ms);
    }
  }
  {
    const auto data = ring(1000, 1.0);
    const auto t0 = std::chrono::steady_clock::now();
    const FitResult r = fit_curve(data, {.controls = 8, .closed = true, .smoothing = 1e-3, .start = BSpline::periodic(3, ring(8, 0.7))});
    const double ms = ms_since(t0);
    double rad = 0;
    for (const auto& c : r.curve.controls()) rad += c.norm() / 8;
    std::printf("circle 1000 pts, 8 controls from r=0.7: %d steps, rms %.4e max %.4e, net radius %.5f, %.1f ms\n", r.iterations,
                r.history.back().rms_distance, r.history.back().max_distance, rad, ms);
  }
  {
    const auto star = t::star(0.3, 5);
    const auto data = points_of(star, 500);
    const BSpline start = BSpline::periodic(3, ring(24, 1.5));
    for (int variant = 0; variant < 4; ++variant) {
      const Method m = variant == 1 ? Method::SDM : variant == 2 ? Method::PDM : variant == 3 ? Method::TDM : Method::SDM;
      FitOptions o{.closed = true, .method = m, .iterations = 100, .tolerance = 1e-7, .start = start};
      o.second_order = variant == 0;
      const auto t0 = std::chrono::steady_clock::now();
      const FitResult r = fit_curve(data, o);
      std::printf("star 500 pts, 24 controls, %s: %d steps (converged %d), objective within 1e-3 after %d, rms within 1%% after %d, rms %.4e max %.4e, %.0f ms\n",
                  variant == 1 ? "sdm (plain, second_order=false)" : method_name(m).c_str(), r.iterations, r.converged, objective_steps(r, 1e-3),
                  rms_steps(r, 0.01), r.history.back().rms_distance, r.history.back().max_distance, ms_since(t0));
    }
    auto noisy = data;
    const double sigma = 0.026;
    std::mt19937 rng(15);
    std::normal_distribution<double> noise(0.0, sigma);
    for (auto& p : noisy) p += V(noise(rng), noise(rng), 0);
    const FitResult r = fit_curve(noisy, {.controls = 24, .closed = true});
    double s = 0;
    for (const V& x : sample(r.curve, 400)) s += std::pow(t::exact_distance(star, x, 0, 2 * kPi, false, 1000), 2);
    std::printf("noisy star (sigma %.3f): rms to the clean curve %.4e = %.2f sigma\n", sigma, std::sqrt(s / 400), std::sqrt(s / 400) / sigma);
  }
  {
    const std::vector<BSpline> curves = {
        BSpline::bezier({V(0, 0, 0), V(1, 2, 0), V(2, 2, 0), V(3, 0, 0), V(4, -2, 0), V(5, -2, 0), V(6, 0, 0)}),
        BSpline::bezier({V(0, 0, 0), V(0.5, 1.5, 0), V(1.5, 2.5, 0), V(3, 3, 0), V(4.5, 2.5, 0), V(5.5, 1.5, 0), V(6, 0, 0)}),
        BSpline::bezier({V(0, 0, 0), V(2, 0, 0), V(3, 1, 0), V(3, 3, 0), V(1, 4, 0), V(-1, 3, 0), V(-1, 1, 0)}),
        BSpline::bezier({V(0, 0, 0), V(1, 1, 0), V(2, -1, 0), V(3, 1, 0), V(4, -1, 0), V(5, 1, 0), V(6, 0, 0)}),
        BSpline::bezier({V(0, 0, 0), V(1, 3, 0), V(3, 4, 0), V(5, 3, 0), V(5, 1, 0), V(3.5, 0.5, 0), V(3, 1.5, 0)})};
    for (std::size_t i = 0; i < curves.size(); ++i) {
      const BSpline& b = curves[i];
      const BSpline eck = reduce_degree_l2(b, 4), eck2 = reduce_degree_l2(reduce_degree_l2(b, 5), 4);
      const FitResult a = reduce_degree(b, 4);
      const TargetCurve target = target_of(b);
      const double ea = one_sided_error(a.curve, target).sum, ee = one_sided_error(eck, target).sum,
                   ee2 = one_sided_error(eck2, target).sum;
      const double ha = hausdorff_distance(a.curve, b), he = hausdorff_distance(eck, b), he2 = hausdorff_distance(eck2, b);
      std::printf("degree 6->4 curve %zu: eq.12 active %.3e, Eck once %.3e, twice %.3e (factor %.0f); Hausdorff %.3e vs %.3e, %.3e (factor %.1f); %d steps\n",
                  i + 1, ea, ee, ee2, std::min(ee, ee2) / ea, ha, he, he2, std::min(he, he2) / ha, a.iterations);
    }
  }
  {
    const TargetCurve helix{.evaluate = t::helix(0.2), .t0 = 0, .t1 = 2 * kPi, .closed = false, .samples = 256};
    const V a = helix.evaluate(0)[0], b = helix.evaluate(2 * kPi)[0];
    std::vector<V> chord(7);
    for (int i = 0; i < 7; ++i) chord[i] = a + (b - a) * (i / 6.0);
    const auto t0 = std::chrono::steady_clock::now();
    const FitResult r = approximate(helix, BSpline::clamped(3, chord, 3), {.fixed = {0, 6}});
    const double ms = ms_since(t0);
    double dev = 0;
    for (int i = 0; i <= 1000; ++i) dev = std::max(dev, t::exact_distance(helix.evaluate, r.curve.point(i / 1000.0), 0, 2 * kPi, true));
    std::printf("helix, 7 controls from the chord: %d steps to tolerance, rms within 1%% after %d, max deviation %.4e, %.1f ms\n",
                r.iterations, rms_steps(r, 0.01), dev, ms);
  }
  {
    std::vector<V> data(10000);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.002);
    for (int i = 0; i < 10000; ++i) data[i] = t::star(0.3, 5)(2 * kPi * i / 10000)[0] + V(noise(rng), noise(rng), 0);
    // Median of 5 runs, wall and CPU time (the machine is shared: CPU time is the steadier figure).
    for (int iterations : {5, 10, 0}) {
      std::vector<double> wall, cpu;
      FitResult r = fit_curve(data, {.controls = 50, .closed = true, .iterations = 1});
      for (int run = 0; run < 5; ++run) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        r = iterations > 0 ? fit_curve(data, {.controls = 50, .closed = true, .iterations = iterations, .tolerance = 0})
                           : fit_curve(data, {.controls = 50, .closed = true});
        cpu.push_back(1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
        wall.push_back(ms_since(t0));
      }
      std::sort(wall.begin(), wall.end());
      std::sort(cpu.begin(), cpu.end());
      std::printf("10^4 points, 50 controls, SDM, %s: %d steps, median %.1f ms wall, %.1f ms CPU (%.1f ms CPU per step), rms %.4e\n",
                  iterations > 0 ? "fixed steps" : "default options", r.iterations, wall[2], cpu[2], cpu[2] / r.iterations,
                  r.history.back().rms_distance);
    }
  }
}
