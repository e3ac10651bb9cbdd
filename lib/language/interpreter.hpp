#pragma once
/// \file interpreter.hpp
/// Runs parsed scripts: a tree-walking interpreter over the syntax tree of ast.hpp, separate
/// from the parser. Values live in a global scope; a user function call gets its own local
/// scope (functions see their locals and the globals).
///
/// Depth: brackets nest at most kMaxNesting deep (checked by the parser); user recursion and
/// nested includes are bounded by a stack budget (InterpreterOptions::stack_budget): going
/// past it is a clean error "recursion too deep", never a crash.

#include <atomic>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kernel/grid.hpp"
#include "language/shown_part.hpp"
#include "language/source.hpp"
#include "language/value.hpp"

namespace sculpt::language {

struct InterpreterOptions {
  std::ostream* out = nullptr;        ///< print() output; null = std::cout
  /// Built-ins' summaries, notes and warnings (trace, implicit, stats, export); null = std::cerr.
  std::ostream* err = nullptr;
  bool allow_files = true;            ///< false: include/curve/import/export raise errors
  std::uint64_t max_steps = 0;        ///< statements, calls and items made per run(); 0 = no limit
  std::size_t stack_budget = 2u << 20;  ///< bytes of C++ stack the evaluator may use
  bool core_only = false;             ///< hide the built-ins of the library areas (fuzzing)
  /// When set and true, the run stops at its next step (statement, call or item made) with the
  /// error "interrupted"; the REPL points it at a flag its SIGINT handler sets. A built-in that
  /// is working (a set operation, say) stops at its next check of base/cancel.hpp's request
  /// (request_cancel(), which the executable's SIGINT handler also calls) with the same error.
  const std::atomic<bool>* interrupt = nullptr;
  /// The grid solids are made at until a script calls grid(step) (sculpt --grid; docs/kernel.md).
  kernel::Grid grid{};
  /// Called with the value of each expression statement run outside functions (sculpt -o
  /// exports the last solid made; assignments show in assigned_at()).
  std::function<void(const Value&)> top_level_value{};
  /// Called with the path of each file an `include` reads (sculpt --view watches them).
  std::function<void(const std::string& path)> included{};
  /// Called with the path of each file a built-in reads: import, curve(source=), load_spline
  /// (sculpt --view watches them too).
  std::function<void(const std::string& path)> file_read{};
};

class Interpreter {
 public:
  explicit Interpreter(InterpreterOptions options = {});
  ~Interpreter();
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  /// Parses and runs `source` in the global scope. Returns the value of the last statement
  /// when it is an expression (the REPL echoes it), else nullopt. Bindings made before an
  /// error are kept.
  /// \throw ScriptError for syntax and run-time errors, positioned in the script.
  std::optional<Value> run(const SourcePtr& source);

  /// Binds a global. \throw ScriptError if `name` is a built-in.
  void define(const std::string& name, Value value);
  /// Binds a global that assignments outside functions leave alone (sculpt -D name=value
  /// overrides a script's own `name = ...`, OpenSCAD's rule); `for` variables still rebind it.
  /// \throw ScriptError if `name` is a built-in.
  void define_fixed(const std::string& name, Value value);
  [[nodiscard]] const Value* global(const std::string& name) const;
  /// The serial number of the last assignment to global `name` (1 for the session's first
  /// global assignment, 2 for the next, ...), 0 if never assigned: tells which was bound last.
  [[nodiscard]] std::uint64_t assigned_at(const std::string& name) const;
  /// The number of global assignments so far (the latest serial).
  [[nodiscard]] std::uint64_t assignments() const;
  /// The grid new solids are made at (InterpreterOptions::grid, then grid(step) in a script).
  [[nodiscard]] kernel::Grid grid() const;
  void set_grid(const kernel::Grid& grid);
  /// The parts show() put in the view so far, in order (a later show with a name already shown
  /// replaces that part in place).
  [[nodiscard]] const std::vector<ShownPart>& shown() const;
  /// Global names in alphabetical order.
  [[nodiscard]] std::vector<std::string> global_names() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads a whole file into a SourceFile (name = path, directory = its folder).
/// \throw IoError
SourcePtr load_source(const std::string& path);

}  // namespace sculpt::language
