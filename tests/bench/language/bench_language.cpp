// Parse and run time of a generated 10,000-line script of assignments, arithmetic and calls
// (geometry aside), median of several runs. Target: <= 0.2 s (docs/benchmarks.md, Language).
//   bench_language [lines=10000] [runs=7]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "language/interpreter.hpp"
#include "language/parser.hpp"

using namespace sculpt::language;

namespace {

/// A script mixing the statement kinds a real script has: assignments of arithmetic on earlier
/// names, vector arithmetic, built-in calls, user-function calls, a small loop now and then.
std::string make_script(int lines) {
  std::ostringstream s;
  s << "fn f(a, b) { a * b + 1 }\nx0 = 1\nv0 = [1, 2, 3]\n";
  for (int i = 1; i < lines - 3; ++i) {
    switch (i % 6) {
      case 0: s << "x" << i << " = x" << i - 1 << " * 0.5 + " << i << " - sqrt(" << i << ")\n"; break;
      case 1: s << "x" << i << " = f(x" << i - 1 << ", 2) / 3\n"; break;
      case 2: s << "v" << i << " = [x" << i - 1 << ", 2, 3] * 2 + [1, 1, 1]\n"; break;
      case 3: s << "x" << i << " = max(x" << i - 2 << ", abs(-" << i << "), 7) % 11\n"; break;
      case 4: s << "s" << i << " = 0; for k in range(0, 3) { s" << i << " = s" << i << " + k }\n"; break;
      default: s << "x" << i << " = (x" << i - 2 << " + 1) * (x" << i - 2 << " - 1) + len(v" << i - 3 << ")\n"; break;
    }
  }
  s << "print(x" << lines - 5 << ")\n";
  return s.str();
}

/// Wall time and this process's CPU time (on a shared, loaded machine the CPU time is the
/// figure that does not depend on the other processes).
struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  [[nodiscard]] double wall_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  }
  [[nodiscard]] double cpu_seconds() const { return double(std::clock() - cpu) / CLOCKS_PER_SEC; }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int lines = argc > 1 ? std::atoi(argv[1]) : 10000;
  const int runs = argc > 2 ? std::atoi(argv[2]) : 7;
  auto source = std::make_shared<SourceFile>();
  source->name = "<bench>";
  source->text = make_script(lines);
  std::vector<double> parse_wall, parse_cpu, total_wall, total_cpu;
  for (int r = 0; r < runs; ++r) {
    Stopwatch parse_clock;
    (void)parse(source);
    parse_wall.push_back(parse_clock.wall_seconds());
    parse_cpu.push_back(parse_clock.cpu_seconds());
    std::ostringstream out;
    Interpreter interpreter({.out = &out});
    Stopwatch run_clock;
    interpreter.run(source);  // parses again, then runs
    total_wall.push_back(run_clock.wall_seconds());
    total_cpu.push_back(run_clock.cpu_seconds());
  }
  std::printf("%d lines, %zu bytes, median of %d runs:\n", lines, source->text.size(), runs);
  std::printf("  parse      cpu %.4f s  wall %.4f s\n", median(parse_cpu), median(parse_wall));
  std::printf("  parse+run  cpu %.4f s  wall %.4f s\n", median(total_cpu), median(total_wall));
  return 0;
}
