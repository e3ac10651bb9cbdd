// The sculpt side of tests/bench/splines/peers.sh.
//   splines_peers fit DIR      the star (500 points, 24 controls) and a noisy star of 10^4 points
//                              (50 controls): writes DIR/<case>_data.txt ("x y" per line), fits with
//                              SDM (default options), writes DIR/<case>_sculpt.txt (spline_io text)
//                              and prints the median thread CPU time of 5 fits;
//   splines_peers measure DIR CASE LABEL FILE...
//                              max and rms distance of DIR/CASE_data.txt to each spline file, by the
//                              library's exact foot points (bracketing and Newton), the same for all.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "splines/analytic.hpp"
#include "splines/splines.hpp"

using namespace sculpt::splines;
using V = Eigen::Vector3d;

namespace {
double thread_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}
void write(const std::string& path, const std::vector<V>& p) {
  std::ofstream out(path);
  out.precision(17);
  for (const V& x : p) out << x.x() << ' ' << x.y() << '\n';
}
std::vector<V> read(const std::string& path) {
  std::ifstream in(path);
  std::vector<V> p;
  double x, y;
  while (in >> x >> y) p.emplace_back(x, y, 0.0);
  return p;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 2 ? argv[1] : "";
  if (mode == "fit") {
    const std::string dir = argv[2];
    const auto star = testing::star(0.3, 5);
    struct Case {
      std::string name;
      int points, controls;
      double noise;
    };
    for (const Case& c : {Case{"star", 500, 24, 0.0}, Case{"star10k", 10000, 50, 0.002}}) {
      std::vector<V> data(c.points);
      std::mt19937 rng(3);
      std::normal_distribution<double> noise(0.0, c.noise > 0 ? c.noise : 1.0);
      for (int i = 0; i < c.points; ++i)
        data[i] = star(2 * std::numbers::pi * i / c.points)[0] + (c.noise > 0 ? V(noise(rng), noise(rng), 0) : V::Zero());
      std::vector<double> times;
      FitResult r = fit_curve(data, {.controls = c.controls, .closed = true});
      for (int run = 0; run < 5; ++run) {
        const double t0 = thread_ms();
        r = fit_curve(data, {.controls = c.controls, .closed = true});
        times.push_back(thread_ms() - t0);
      }
      std::sort(times.begin(), times.end());
      write(dir + "/" + c.name + "_data.txt", data);
      save_spline(r.curve, dir + "/" + c.name + "_sculpt.txt");
      std::printf("%s sculpt SDM: controls %d steps %d median_cpu_ms %.2f\n", c.name.c_str(), r.curve.control_count(), r.iterations,
                  times[2]);
    }
    return 0;
  }
  if (mode == "measure" && argc >= 6 && (argc - 4) % 2 == 0) {
    const std::string dir = argv[2], name = argv[3];
    const std::vector<V> data = read(dir + "/" + name + "_data.txt");
    for (int i = 4; i + 1 < argc; i += 2) {
      const BSpline curve = load_spline(argv[i + 1]);
      const DistanceSummary d = distance(curve, data);
      std::printf("%s %-28s controls %3d exact max %.4e rms %.4e\n", name.c_str(), argv[i], curve.control_count(), d.max, d.rms);
    }
    return 0;
  }
  std::fprintf(stderr, "usage: splines_peers fit DIR | measure DIR CASE LABEL FILE [LABEL FILE...]\n");
  return 2;
}
