// Script functions compiled into implicit expressions (language/implicit_compiler.hpp) against
// the interpreter: compile time of a function, and the cost per point of its value (and value
// with gradient, interval bounds) compiled, against one call of the same fn in the interpreter.
// Median of several runs; CPU time. Figures: docs/implicit.md, "From the language".
//   bench_implicit [points=100000] [runs=7]
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "language/implicit_compiler.hpp"
#include "language/interpreter.hpp"

using namespace sculpt::language;

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

template <typename F>
double median_seconds(int runs, F&& f) {
  std::vector<double> times;
  for (int r = 0; r < runs; ++r) {
    const double t0 = cpu_seconds();
    f();
    times.push_back(cpu_seconds() - t0);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

SourcePtr text(const std::string& s) {
  auto source = std::make_shared<SourceFile>();
  source->name = "<bench>";
  source->text = s;
  return source;
}

struct Case {
  const char* name;
  const char* fn;  // defines f(x, y, z)
};

}  // namespace

int main(int argc, char** argv) {
  const int points = argc > 1 ? std::atoi(argv[1]) : 100000;
  const int runs = argc > 2 ? std::atoi(argv[2]) : 7;
  const Case cases[] = {
      {"fig7 ellipsoid", "fn f(x, y, z) { 36 * pow(x, 2) + 81 * pow(y, 2) + 9 * pow(z, 2) - 324 }"},
      {"torus (locals, p)",
       "R = 1\nr = 0.4\nfn t(p) { q = sqrt(p[0] * p[0] + p[1] * p[1]) - R; q * q + p[2] * p[2] - r * r }\n"
       "fn f(x, y, z) { t([x, y, z]) }"},
      {"blend (calls)",
       "fn ball(x, y, z, c) { sqrt(pow(x - c, 2) + y * y + z * z) - 1 }\n"
       "fn f(x, y, z) { min(ball(x, y, z, -0.6), ball(x, y, z, 0.6)) - 0.2 * exp(-abs(x)) * cos(3 * y) }"},
  };
  std::printf("%-18s %6s %10s %12s %12s %12s %12s %9s\n", "function", "nodes", "compile us", "value ns",
              "grad ns", "bounds ns", "interp ns", "speed-up");
  for (const Case& c : cases) {
    std::ostringstream out;
    Interpreter interpreter({.out = &out});
    interpreter.run(text(c.fn));
    const auto& f = *interpreter.global("f")->get<std::shared_ptr<const UserFunction>>();
    ImplicitCompileOptions options;
    options.global = [&](const std::string& n) { return interpreter.global(n); };
    sculpt::implicit::Expression e;
    const int compiles = 1000;
    const double compile = median_seconds(runs, [&] {
                             for (int i = 0; i < compiles; ++i) e = compile_implicit(*f, options);
                           }) / compiles;

    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    std::vector<Eigen::Vector3d> ps(static_cast<std::size_t>(points));
    for (auto& p : ps) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
    volatile double sink = 0;
    const double value = median_seconds(runs, [&] {
                           double s = 0;
                           for (const auto& p : ps) s += e.value(p);
                           sink = s;
                         }) / points;
    const double grad = median_seconds(runs, [&] {
                          double s = 0;
                          for (const auto& p : ps) s += e.value_gradient(p).gradient.x();
                          sink = s;
                        }) / points;
    const double bounds = median_seconds(runs, [&] {
                            double s = 0;
                            for (const auto& p : ps) {
                              s += e.bounds({.lo = p, .hi = p + Eigen::Vector3d::Constant(0.1)}).range.hi;
                            }
                            sink = s;
                          }) / points;
    // The interpreter: a loop calling f at the same points, minus the same loop without the call.
    const int calls = std::min(points, 20000);
    std::ostringstream loop, empty;
    loop << "s = 0\nfor i in range(0, " << calls << ") { s = s + f(i * 1e-4, 0.5, -0.25) }\n";
    empty << "s = 0\nfor i in range(0, " << calls << ") { s = s + (i * 1e-4 + 0.5 - 0.25) }\n";
    const SourcePtr loop_source = text(loop.str()), empty_source = text(empty.str());
    const double with_calls = median_seconds(runs, [&] { interpreter.run(loop_source); });
    const double without = median_seconds(runs, [&] { interpreter.run(empty_source); });
    const double interp = (with_calls - without) / calls;
    (void)sink;
    std::printf("%-18s %6zu %10.1f %12.1f %12.1f %12.1f %12.1f %8.0fx\n", c.name, e.size(), compile * 1e6,
                value * 1e9, grad * 1e9, bounds * 1e9, interp * 1e9, interp / value);
  }
  return 0;
}
