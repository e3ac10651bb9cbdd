// The sculpt side of tests/bench/splines/peers.sh: fits the star (500 points, 24 controls) and a
// noisy star of 10^4 points (50 controls) with SDM, writes the data points and the fitted curve
// densely sampled (one "x y" per line) into a directory, and prints time and control count.
#include <chrono>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include "splines/analytic.hpp"
#include "splines/splines.hpp"

using namespace sculpt::splines;
using V = Eigen::Vector3d;

namespace {
void write(const std::string& path, const std::vector<V>& p) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return;
  for (const V& x : p) std::fprintf(f, "%.17g %.17g\n", x.x(), x.y());
  std::fclose(f);
}
}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  const auto star = testing::star(0.3, 5);
  const double pi = std::numbers::pi;
  struct Case {
    std::string name;
    int points, controls;
    double noise;
  };
  for (const Case& c : {Case{"star", 500, 24, 0.0}, Case{"star10k", 10000, 50, 0.002}}) {
    std::vector<V> data(c.points);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, c.noise > 0 ? c.noise : 1.0);
    for (int i = 0; i < c.points; ++i) data[i] = star(2 * pi * i / c.points)[0] + (c.noise > 0 ? V(noise(rng), noise(rng), 0) : V::Zero());
    const auto t0 = std::chrono::steady_clock::now();
    const FitResult r = fit_curve(data, {.controls = c.controls, .closed = true});
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const DistanceSummary d = distance(r.curve, data);
    write(dir + "/" + c.name + "_data.txt", data);
    write(dir + "/" + c.name + "_sculpt.txt", sample(r.curve, 200000));
    std::printf("%s sculpt controls %d steps %d time_ms %.1f exact_max %.4e exact_rms %.4e\n", c.name.c_str(), r.curve.control_count(),
                r.iterations, ms, d.max, d.rms);
  }
}
