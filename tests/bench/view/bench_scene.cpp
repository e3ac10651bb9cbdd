// What `sculpt --view` does between a script's end and the message to the page, stage by stage
// (repl/view_mode.cpp): the parts (each solid's exact boundary and measures, view::scene_of) and
// the message (GLB and feature edges, view::encode_scene). Each run starts a new interpreter, as
// the view does; what a stage frees is freed after its clock stops (the view frees a run's values
// after publishing). Medians of several runs, wall clock. tests/bench/view_latency.py measures the
// whole way to the screen in a browser.
//   bench_scene [RUNS] [STATEMENTS | FILE.bsp]   default: 5 runs of show(sphere(1, segments=1000), name="ball")
// Prints one line:
//   bench stage=view_scene runs=<r> script_ms= boundary_ms= parts_ms= message_ms= after_script_ms=
//         faces=<faces of the first solid's boundary> bytes=<message bytes>
// boundary_ms is the first part's exact boundary alone, when it is a solid (to_mesh without output rounding),
// part of parts_ms; after_script_ms = parts_ms + message_ms.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "base/memory_policy.hpp"
#include "language/interpreter.hpp"
#include "language/solid_values.hpp"
#include "view/scene.hpp"
#include "view/scene_message.hpp"

using namespace sculpt;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  use_huge_pages(argv);  // as the sculpt executable does (base/memory_policy.hpp); may restart
  keep_freed_memory();
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string what = argc > 2 ? argv[2] : "show(sphere(1, segments=1000), name=\"ball\")";
  language::SourcePtr source;
  if (what.ends_with(".bsp")) {
    source = language::load_source(what);
  } else {
    auto statements = std::make_shared<language::SourceFile>();
    statements->name = "<bench>";
    statements->text = what;
    source = statements;
  }
  std::vector<double> script, boundary, parts, message;
  std::size_t faces = 0, bytes = 0;
  for (int run = 0; run < runs; ++run) {
    // A script that shows nothing is shown by its last solid (repl/last_solid.hpp): the latest
    // solid statement outside functions or global bound to a solid, whichever came later.
    std::optional<language::Value> statement;
    std::uint64_t serial = 0;
    language::InterpreterOptions options;
    language::Interpreter* running = nullptr;
    options.top_level_value = [&](const language::Value& v) {
      if (v.object<language::SolidValue>()) statement = v, serial = running->assignments();
    };
    language::Interpreter interpreter(options);
    running = &interpreter;
    auto t = Clock::now();
    try {
      interpreter.run(source);
    } catch (const language::ScriptError& e) {  // as the executable reports it: file:line:col: error: ...
      std::fprintf(stderr, "%s", language::format_error(e).c_str());
      return 1;
    }
    script.push_back(since(t));
    std::optional<language::Value> last = statement;
    if (const std::string name = language::latest_solid_global(interpreter);
        !name.empty() && !(statement && serial >= interpreter.assigned_at(name)))
      last = *interpreter.global(name);
    const std::vector<language::ShownPart>& shown = interpreter.shown();
    if (shown.empty() && !last) {
      std::fprintf(stderr, "bench_scene: the statements show nothing and make no solid\n");
      return 1;
    }
    const language::Value& first = shown.empty() ? *last : shown.front().value;
    if (const auto* solid = first.object<language::SolidValue>()) {
      t = Clock::now();
      const PolygonMesh mesh = solid->display_boundary();
      boundary.push_back(since(t));
      faces = mesh.faces.size();
    }
    t = Clock::now();
    const view::Scene scene = view::scene_of(shown, shown.empty() ? last : std::nullopt);
    parts.push_back(since(t));
    t = Clock::now();
    const std::string encoded = view::encode_scene(scene, {});
    message.push_back(since(t));
    bytes = encoded.size();
  }
  const double b = boundary.empty() ? 0.0 : median(boundary);
  std::printf(
      "bench stage=view_scene runs=%d script_ms=%.1f boundary_ms=%.1f parts_ms=%.1f message_ms=%.1f "
      "after_script_ms=%.1f faces=%zu bytes=%zu\n",
      runs, median(script), b, median(parts), median(message), median(parts) + median(message), faces, bytes);
  return 0;
}
