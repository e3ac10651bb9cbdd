// Active surfaces (issue 18): the sculpt side of the OpenCascade comparison in peers.sh and the
// timing target.
//   splines_surfaces fit DIR       the known patches (40 x 40 grids, corners included): a spherical
//                                  cap and a wave; writes DIR/<case>_data.txt ("x y z" per line,
//                                  row-major), fits 8 x 8 bicubic controls with SDM in at most 7
//                                  steps, writes DIR/<case>_sculpt.txt and prints the history and
//                                  the median thread CPU time of 5 fits;
//   splines_surfaces measure DIR CASE LABEL FILE...
//                                  max and rms distance of DIR/CASE_data.txt to each surface file
//                                  by the library's exact foot points (the same for all);
//   splines_surfaces timing        10^4 points (100 x 100 grid of the wave), 8 x 8 controls, SDM:
//                                  thread CPU time per step, median over the steps of 5 fits.
// Surface files: "degree p q", "knots_u ...", "knots_v ..." (expanded), "size nu nv", then nu * nv
// lines "x y z" (u outer).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "bench_timing.hpp"
#include "splines/splines.hpp"

using namespace sculpt::splines;
using V = Eigen::Vector3d;

namespace {

struct Case {
  std::string name;
  double (*f)(double, double);
};
const Case kCases[] = {
    {"sphere", [](double x, double y) { return std::sqrt(4 - x * x - y * y); }},
    {"wave", [](double x, double y) { return 0.3 * std::sin(2 * x) * std::cos(3 * y); }},
};

std::vector<V> grid(const Case& c, int n) {
  std::vector<V> p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -1 + 2.0 * i / (n - 1), y = -1 + 2.0 * j / (n - 1);
      p.emplace_back(x, y, c.f(x, y));
    }
  return p;
}

void write_points(const std::string& path, const std::vector<V>& p) {
  std::ofstream out(path);
  out.precision(17);
  for (const V& x : p) out << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
}

std::vector<V> read_points(const std::string& path) {
  std::ifstream in(path);
  std::vector<V> p;
  double x, y, z;
  while (in >> x >> y >> z) p.emplace_back(x, y, z);
  return p;
}

void write_surface(const std::string& path, const BSplineSurface& s) {
  std::ofstream out(path);
  out.precision(17);
  out << "degree " << s.degree(0) << ' ' << s.degree(1);
  for (int d = 0; d < 2; ++d) {
    out << (d ? "\nknots_v" : "\nknots_u");
    for (double k : s.knots(d)) out << ' ' << k;
  }
  out << "\nsize " << s.count(0) << ' ' << s.count(1) << '\n';
  for (const V& c : s.controls()) out << c.x() << ' ' << c.y() << ' ' << c.z() << '\n';
}

BSplineSurface read_surface(const std::string& path) {
  std::ifstream in(path);
  std::string line, word;
  int p = 0, q = 0, nu = 0, nv = 0;
  std::array<std::vector<double>, 2> knots;
  std::getline(in, line);
  std::istringstream(line) >> word >> p >> q;
  for (int d = 0; d < 2; ++d) {
    std::getline(in, line);
    std::istringstream s(line);
    s >> word;
    double k;
    while (s >> k) knots[d].push_back(k);
  }
  std::getline(in, line);
  std::istringstream(line) >> word >> nu >> nv;
  std::vector<V> P;
  double x, y, z;
  while (in >> x >> y >> z) P.emplace_back(x, y, z);
  return BSplineSurface({p, q}, knots, nu, nv, P, {false, false});
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "fit" && argc == 3) {
    const std::string dir = argv[2];
    for (const Case& c : kCases) {
      const std::vector<V> data = grid(c, 40);
      write_points(dir + "/" + c.name + "_data.txt", data);
      const FitSurfaceOptions options{.controls = {8, 8}, .iterations = 7};
      FitSurfaceResult r = fit_surface(data, options);
      const auto t = sculpt::bench::median_ms(5, [&] { r = fit_surface(data, options); });
      write_surface(dir + "/" + c.name + "_sculpt.txt", r.surface);
      std::printf("%s sculpt SDM: controls 8 x 8, steps %d, median_cpu_ms %.1f; history (max distance by step):", c.name.c_str(),
                  r.iterations, t.cpu);
      for (const auto& h : r.history) std::printf(" %.2e", h.max_distance);
      std::printf("\n");
    }
    return 0;
  }
  if (mode == "measure" && argc >= 6 && (argc - 4) % 2 == 0) {
    const std::string dir = argv[2], name = argv[3];
    const std::vector<V> data = read_points(dir + "/" + name + "_data.txt");
    for (int i = 4; i + 1 < argc; i += 2) {
      const BSplineSurface s = read_surface(argv[i + 1]);
      const DistanceSummary d = distance(s, data);
      std::printf("%s %-38s controls %d x %d exact max %.4e rms %.4e\n", name.c_str(), argv[i], s.count(0), s.count(1), d.max, d.rms);
    }
    return 0;
  }
  if (mode == "timing") {
    const std::vector<V> data = grid(kCases[1], 100);
    std::vector<double> steps, starts;
    int iterations = 0;
    double final_max = 0;
    for (int run = 0; run < 5; ++run) {
      const FitSurfaceResult r = fit_surface(data, {.controls = {8, 8}, .iterations = 7});
      starts.push_back(r.history[0].cpu_ms);
      for (std::size_t k = 1; k < r.history.size(); ++k) steps.push_back(r.history[k].cpu_ms);
      iterations = r.iterations;
      final_max = r.history.back().max_distance;
    }
    std::sort(steps.begin(), steps.end());
    std::sort(starts.begin(), starts.end());
    std::printf("timing: %zu points, 8 x 8 controls, SDM, %d steps, final max %.2e: thread CPU per step median %.1f ms, "
                "slowest %.1f ms (a step includes its halvings); start foot points median %.1f ms\n",
                data.size(), iterations, final_max, steps[steps.size() / 2], steps.back(), starts[starts.size() / 2]);
    return 0;
  }
  std::fprintf(stderr, "usage: splines_surfaces fit DIR | measure DIR CASE LABEL FILE [LABEL FILE...] | timing\n");
  return 2;
}
