// The sculpt executable: runs .bsp scripts or an interactive session.
//   sculpt FILE.bsp ...   sculpt -   sculpt -e 'code'   sculpt -D name=value   -o FILE   --help --version
// Exit code 0 on success, 1 on a script error, 2 on a usage error, 130 when stopped by Ctrl-C.
#include <unistd.h>

#include <csignal>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "base/memory_limit.hpp"
#include "base/memory_policy.hpp"
#include "base/parallel.hpp"
#include "bsp/set_operations.hpp"
#include "interactive.hpp"
#include "language/interpreter.hpp"
#include "language/solid_values.hpp"
#include "last_solid.hpp"
#include "mesh/mesh_io.hpp"
#include "view_mode.hpp"

namespace {

using namespace sculpt;
using namespace sculpt::language;
using sculpt::repl::LastSolid;

constexpr const char* kUsage =
    "usage: sculpt [options] [FILE.bsp ... | -]\n"
    "Runs sculpt scripts in order, in one shared global scope; with no script and a terminal on\n"
    "standard input, starts an interactive session (:help inside it).\n"
    "  FILE.bsp        run a script file\n"
    "  -               run the script read from standard input\n"
    "  -e CODE         run CODE (may be repeated; runs in order with the files)\n"
    "  -D NAME=VALUE   bind NAME before any script runs. VALUE is a number, true, false, a\n"
    "                  sculpt list or string literal ([1, 2, 3], \"text\"); anything else is\n"
    "                  bound as a string. It overrides the scripts' own NAME = ... outside\n"
    "                  functions (as in OpenSCAD); in a session your entries may rebind it\n"
    "  -o FILE         after the scripts, export the union of the solids they show(), else\n"
    "                  their last solid (the last solid expression statement or solid bound\n"
    "                  to a global outside functions, whichever came later) to FILE, format\n"
    "                  by extension (.off .obj .stl .ply .om .3mf .glb); folders are created\n"
    "  --grid STEP     make solids at grid step STEP, a power of two written 2^-13 or 0.0001220703125:\n"
    "                  coordinates up to 2^25 steps (default 2^-15: [-1024, 1024]); see grid()\n"
    "  --memory-limit SIZE  stop work that takes more memory than SIZE (2G, 500M; 'none') with\n"
    "                  an error at its statement instead of being killed by the system; the\n"
    "                  session goes on (default: 90% of the machine's memory)\n"
    "  --threads N     use at most N threads (default: every core, or SCULPT_THREADS); results\n"
    "                  are the same for every count\n"
    "  --view          show the script's parts (show(x), else its last solid) in a browser page\n"
    "                  and run the script again whenever it or a file it includes changes; with\n"
    "                  no script, the interactive session with its view open (docs/viewing.md)\n"
    "  --port N        the view's port on 127.0.0.1 (default 8417, else the next free one of\n"
    "                  8418 to 8426; 0: any free port); :view in a session uses it too\n"
    "  --help          show this help\n"
    "  --version       show the version\n"
    "Environment: SCULPT_THREADS as --threads; SCULPT_HUGE_PAGES=0 keeps the heap on 4 KiB\n"
    "pages (by default it uses transparent huge pages where the system offers them).\n"
    "Exit status: 0 on success, 1 on a script error, 2 on a usage error, 130 when Ctrl-C\n"
    "stopped the scripts (the statement running stops within a fraction of a second; a\n"
    "second Ctrl-C ends the process at once).\n";

/// Exit status of a run stopped by Ctrl-C (128 + SIGINT, as shells report it).
constexpr int kInterruptedStatus = 130;

extern "C" void on_batch_interrupt(int) { sculpt::request_cancel(); }

/// Batch runs: the first Ctrl-C asks the running statement to stop (base/cancel.hpp), which ends
/// the run with status 130; the handler then resets itself, so a second Ctrl-C ends the process.
/// SA_RESTART: a script being read from standard input is read whole, never cut short.
void stop_on_interrupt() {
  struct sigaction action {};
  action.sa_handler = on_batch_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
}

int usage_error(const std::string& message) {
  std::cerr << "sculpt: " << message << "; try 'sculpt --help'\n";
  return 2;
}

struct Job {
  enum Kind { File, Stdin, Code } kind;
  std::string text;
};

SourcePtr code_source(std::string name, std::string text) {
  auto source = std::make_shared<SourceFile>();
  source->name = std::move(name);
  source->text = std::move(text);
  return source;
}

bool is_name(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}

/// The grid of `--grid STEP`: "2^K" (K an integer) or a decimal number, a power of two.
/// \throw InvalidInput (Grid::from_step's message) for anything else.
sculpt::kernel::Grid grid_option(const std::string& text) {
  if (text.rfind("2^", 0) == 0) {
    int k = 0;
    const char* begin = text.data() + 2;
    const char* end = text.data() + text.size();
    const auto [stop, ec] = std::from_chars(begin, end, k);
    if (ec == std::errc() && stop == end && begin != end) return sculpt::kernel::Grid::from_shift(-k);
    throw sculpt::InvalidInput("--grid: '" + text + "' is not 2^K with an integer K");
  }
  double step = 0;
  const auto [stop, ec] = std::from_chars(text.data(), text.data() + text.size(), step);
  if (ec != std::errc() || stop != text.data() + text.size() || text.empty())
    throw sculpt::InvalidInput("--grid: '" + text + "' is not a number or 2^K");
  return sculpt::kernel::Grid::from_step(step);
}

/// The value of `-D name=value` (see kUsage).
Value definition_value(Interpreter& interpreter, const std::string& text) {
  double number = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (ec == std::errc() && end == text.data() + text.size() && !text.empty()) return number;
  if (text == "true") return true;
  if (text == "false") return false;
  if (!text.empty() && (text[0] == '[' || text[0] == '"')) {
    auto value = interpreter.run(code_source("<-D>", text));
    return value ? *value : Value();
  }
  return text;
}

/// sculpt -o FILE: exports what the scripts show (the union of the solids they passed to show(),
/// as the view shows them together), or else their last solid. Returns the exit code.
int export_result(const LastSolid& last, const Interpreter& interpreter, const std::string& path) {
  std::vector<sculpt::Solid> shown;
  for (const sculpt::language::ShownPart& part : interpreter.shown())
    if (const auto* s = part.value.object<SolidValue>()) shown.push_back(s->solid);
  const std::optional<Value> solid = last.get();
  if (shown.empty() && !solid) {
    std::cerr << "sculpt: -o: the scripts made no solid to export\n";
    return 1;
  }
  try {
    std::optional<SolidValue> combined;
    if (!shown.empty()) combined.emplace(sculpt::unite_all(std::move(shown)));
    const SolidValue& result = combined ? *combined : *solid->object<SolidValue>();
    if (const std::string warning = export_solid(result, path); !warning.empty())
      std::cerr << "sculpt: -o: warning: " << warning << "\n";
  } catch (const sculpt::Cancelled&) {
    std::cerr << "sculpt: -o: interrupted (nothing written)\n";
    return kInterruptedStatus;
  } catch (const std::exception& e) {
    std::cerr << "sculpt: -o: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sculpt::use_huge_pages(argv);  // first: it may start the process again (base/memory_policy.hpp)
  sculpt::keep_freed_memory();  // strokes reuse what the previous one freed (base/memory_policy.hpp)
  std::vector<Job> jobs;
  std::vector<std::pair<std::string, std::string>> definitions;
  sculpt::kernel::Grid grid;
  std::optional<int> threads;
  try {
    threads = sculpt::threads_from_environment();
  } catch (const sculpt::InvalidInput& e) {
    return usage_error(e.what());
  }
  std::optional<std::uint64_t> memory_budget = sculpt::default_memory_limit();  // --memory-limit
  bool memory_limit_given = false;
  std::string output;  // -o FILE
  bool view = false;   // --view
  sculpt::repl::ViewPort view_port;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (arg == "--version") {
      std::cout << "sculpt " << SCULPT_VERSION << "\n";
      return 0;
    }
    if (arg == "-e") {
      if (i + 1 >= argc) return usage_error("-e needs code");
      jobs.push_back({Job::Code, argv[++i]});
    } else if (arg == "-D" || (arg.rfind("-D", 0) == 0 && arg.size() > 2)) {
      std::string definition = arg.size() > 2 ? arg.substr(2) : (i + 1 < argc ? argv[++i] : "");
      const auto equals = definition.find('=');
      if (equals == std::string::npos || !is_name(definition.substr(0, equals))) {
        return usage_error("-D needs NAME=VALUE, got '" + definition + "'");
      }
      definitions.emplace_back(definition.substr(0, equals), definition.substr(equals + 1));
    } else if (arg == "--grid" || arg.rfind("--grid=", 0) == 0) {
      std::string text = arg.size() > 6 ? arg.substr(7) : (i + 1 < argc ? argv[++i] : "");
      try {
        grid = grid_option(text);
      } catch (const sculpt::InvalidInput& e) {
        return usage_error(e.what());
      }
    } else if (arg == "--threads" || arg.rfind("--threads=", 0) == 0) {
      const std::string text = arg.size() > 9 ? arg.substr(10) : (i + 1 < argc ? argv[++i] : "");
      int n = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
      if (error != std::errc() || end != text.data() + text.size() || n < 1)
        return usage_error("--threads needs a positive integer, got '" + text + "'");
      threads = n;
    } else if (arg == "--memory-limit" || arg.rfind("--memory-limit=", 0) == 0) {
      const std::string text = arg.size() > 14 ? arg.substr(15) : (i + 1 < argc ? argv[++i] : "");
      try {
        memory_budget = sculpt::parse_memory_size(text);
        memory_limit_given = true;
      } catch (const sculpt::InvalidInput& e) {
        return usage_error(std::string("--memory-limit: ") + e.what());
      }
    } else if (arg == "--view") {
      view = true;
    } else if (arg == "--port" || arg.rfind("--port=", 0) == 0) {
      const std::string text = arg.size() > 6 ? arg.substr(7) : (i + 1 < argc ? argv[++i] : "");
      int n = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
      if (error != std::errc() || end != text.data() + text.size() || n < 0 || n > 65535)
        return usage_error("--port needs a port number in [0, 65535], got '" + text + "'");
      view_port = {.port = n, .given = true};
    } else if (arg == "-o") {
      if (i + 1 >= argc) return usage_error("-o needs a file name");
      output = argv[++i];
      try {
        (void)sculpt::mesh_format_from_path(output);
      } catch (const sculpt::IoError& e) {
        return usage_error(std::string("-o: ") + e.what());
      }
    } else if (arg == "-") {
      jobs.push_back({Job::Stdin, ""});
    } else if (arg.size() > 1 && arg[0] == '-') {
      return usage_error("unknown option '" + arg + "'");
    } else {
      jobs.push_back({Job::File, arg});
    }
  }

  // Work beyond the budget stops with an error at its statement instead of being killed by the
  // system (base/memory_limit.hpp).
  std::optional<sculpt::MemoryWatch> memory_watch;
  if (memory_budget && *memory_budget > 0) {
    memory_watch.emplace(*memory_budget);
    if (!memory_watch->enforced() && memory_limit_given)
      std::cerr << "sculpt: warning: --memory-limit is not enforced here (/proc/self/statm cannot be read)\n";
  }
  std::optional<sculpt::ThreadLimit> thread_limit;
  if (threads) thread_limit.emplace(*threads);

  // In a session the -D bindings are plain globals; scripts run in batch keep them (define_fixed).
  auto define_all = [&](Interpreter& interpreter, bool fixed) {
    interpreter.set_grid(grid);
    for (const auto& [name, text] : definitions) {
      Value value = definition_value(interpreter, text);
      fixed ? interpreter.define_fixed(name, std::move(value)) : interpreter.define(name, std::move(value));
    }
  };
  if (view && !jobs.empty()) {
    if (jobs.size() != 1 || jobs[0].kind != Job::File) return usage_error("--view needs one script file (FILE.bsp)");
    if (!output.empty()) return usage_error("--view and -o do not go together");
    return sculpt::repl::run_script_view({.script = jobs[0].text,
                                          .port = view_port,
                                          .setup = [&](Interpreter& interpreter) { define_all(interpreter, true); }});
  }
  if (jobs.empty() && (isatty(STDIN_FILENO) || view)) {
    if (!output.empty()) return usage_error("-o needs a script (FILE.bsp, - or -e CODE), not a session");
    return sculpt::repl::run_interactive([&](Interpreter& interpreter) { define_all(interpreter, false); },
                                         {.port = view_port, .open = view});
  }
  if (jobs.empty()) jobs.push_back({Job::Stdin, ""});

  stop_on_interrupt();
  LastSolid last;
  InterpreterOptions options;
  options.interrupt = sculpt::cancel_request_flag();
  if (!output.empty()) options.top_level_value = [&last](const Value& value) { last.see(value); };
  Interpreter interpreter(options);
  last.interpreter = &interpreter;
  try {
    define_all(interpreter, true);
    for (const Job& job : jobs) {
      switch (job.kind) {
        case Job::File:
          interpreter.run(load_source(job.text));
          break;
        case Job::Stdin:
          interpreter.run(code_source("<stdin>", std::string(std::istreambuf_iterator<char>(std::cin), {})));
          break;
        case Job::Code:
          interpreter.run(code_source("<command line>", job.text));
          break;
      }
    }
  } catch (const ScriptError& e) {
    std::cout.flush();
    std::cerr << format_error(e);
    return sculpt::cancel_requested() && sculpt::cancel_reason() == sculpt::CancelReason::User ? kInterruptedStatus : 1;
  } catch (const IoError& e) {
    std::cout.flush();
    std::cerr << "sculpt: " << e.what() << "\n";
    return 1;
  }
  return output.empty() ? 0 : export_result(last, interpreter, output);
}
