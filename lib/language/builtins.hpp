#pragma once
/// \file builtins.hpp
/// The table of built-in functions and constants. One table drives the interpreter, `:help`,
/// tab completion and the reference (a test checks that docs/language.md documents every entry).
///
/// Adding a built-in: write it in the `builtins_<area>.cpp` of its library area, inside that
/// file's `register_<area>(BuiltinTable&)` function:
///
///     table.add({.name = "volume", .signature = "volume(s)", .doc = "Volume of solid s.",
///                .params = {{"s"}},
///                .run = [](const Arguments& args) -> Value { return volume(solid_arg(args, 0)); }});
///
/// A new area also adds its register function to the list in builtins.cpp.

#include <cstdint>
#include <functional>
#include <map>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "kernel/grid.hpp"
#include "language/shown_part.hpp"
#include "language/value.hpp"

namespace sculpt::language {

/// A parameter of a built-in. Optional parameters may be left out or given by name.
struct Param {
  std::string name{};
  bool required = true;
};

/// Settings of a run that built-ins may consult.
struct RunSettings {
  std::ostream* out = nullptr;   ///< where print() writes
  /// What show() collected in this interpreter (the interpreter's list); null: show() only checks
  /// its arguments.
  std::vector<ShownPart>* shown = nullptr;
  bool allow_files = true;       ///< false: built-ins that touch files raise an error (fuzzing)
  std::uint64_t* steps = nullptr;  ///< the run's step counter (see InterpreterOptions::max_steps)
  std::uint64_t max_steps = 0;     ///< 0 = no limit
  /// The global variables of the run, for built-ins that compile user functions (trace), which
  /// see the globals as the function would at a call.
  const std::map<std::string, Value>* globals = nullptr;
  /// The grid new solids are made at (grid(), sculpt --grid; docs/kernel.md, "World range"),
  /// kept across runs by the interpreter; null: the default grid, not settable.
  kernel::Grid* grid = nullptr;
  /// Calls a function value (a user function or a built-in) with positional arguments, as a call
  /// at `at` would (map, filter); set by the interpreter.
  std::function<Value(const Value& f, std::vector<Value> values, const SourceRef& at)> call{};
};

/// The arguments of one call, bound to the built-in's parameters, with their script positions
/// so that errors point at the right place.
class Arguments {
 public:
  Arguments(const Builtin& builtin, SourceRef call, std::vector<const Value*> bound,
            std::vector<SourceRef> positions, std::vector<Value> rest,
            std::vector<SourceRef> rest_positions, const RunSettings& settings);

  /// Parameter i was given.
  [[nodiscard]] bool has(std::size_t i) const { return bound_[i] != nullptr; }
  /// The value of parameter i (none if not given).
  [[nodiscard]] const Value& value(std::size_t i) const;
  [[nodiscard]] double number(std::size_t i) const;
  /// A whole number in [low, high].
  [[nodiscard]] long long integer(std::size_t i, long long low, long long high) const;
  [[nodiscard]] bool boolean(std::size_t i) const;
  [[nodiscard]] const std::string& string(std::size_t i) const;
  [[nodiscard]] const List& list(std::size_t i) const;
  /// A list of exactly n numbers.
  [[nodiscard]] std::vector<double> vector(std::size_t i, std::size_t n) const;
  /// Parameter i, which must be a function (user-defined or built-in).
  [[nodiscard]] const Value& function(std::size_t i) const;
  /// Calls function value `f` with positional `values`; an error inside it gets a note at this call.
  Value call(const Value& f, std::vector<Value> values) const;
  /// The library object of parameter i, which must be of type T (`what` names it in errors).
  template <typename T>
  [[nodiscard]] const T& object(std::size_t i, const char* what) const {
    if (const T* o = value(i).object<T>()) return *o;
    fail_type(i, what);
  }
  /// Copy on write: parameter i's library object, of type T, for the built-in to take its
  /// contents, when the call's argument is its only holder (a temporary, or the variable the
  /// statement assigns to, which the interpreter hands over to built-ins marked
  /// Builtin::takes_arguments); else null, and the built-in must not change it. Check the
  /// arguments first: an error after taking cannot give the contents back.
  template <typename T>
  [[nodiscard]] T* sole_object(std::size_t i) const {
    return has(i) ? dynamic_cast<T*>(value(i).sole_object()) : nullptr;
  }
  /// Values of a variadic built-in beyond its parameters (print).
  [[nodiscard]] const std::vector<Value>& rest() const { return rest_; }

  /// Error at parameter i's position / at the call.
  [[noreturn]] void fail(std::size_t i, const std::string& message) const;
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail_type(std::size_t i, const char* expected) const;
  /// Counts `n` steps of work (items made) against the run's step limit.
  void charge(std::uint64_t n) const;
  /// Refuses when files are disabled; else `path` resolved against the calling script's folder.
  [[nodiscard]] std::string file_path(std::size_t i) const;

  /// The global variable `name` of the run, or null.
  [[nodiscard]] const Value* global(const std::string& name) const;
  /// The global variables of the run (empty when the run has none).
  [[nodiscard]] const std::map<std::string, Value>& globals() const;

  /// The grid new solids are made at (RunSettings::grid).
  [[nodiscard]] kernel::Grid grid() const { return settings_.grid ? *settings_.grid : kernel::Grid{}; }
  /// Sets it (the built-in grid()). \throw std::logic_error if the run has no grid setting.
  void set_grid(const kernel::Grid& grid) const;

  [[nodiscard]] std::ostream& out() const { return *settings_.out; }
  /// The run's list of shown parts (RunSettings::shown), or null.
  [[nodiscard]] std::vector<ShownPart>* shown() const { return settings_.shown; }
  [[nodiscard]] const SourceRef& call() const { return call_; }

 private:
  const Builtin& builtin_;
  SourceRef call_;
  std::vector<const Value*> bound_;
  std::vector<SourceRef> positions_;
  std::vector<Value> rest_;
  std::vector<SourceRef> rest_positions_;
  const RunSettings& settings_;
};

struct Builtin {
  std::string name{};
  std::string signature{};   ///< as shown by :help, e.g. "box(min, max)"
  std::string doc{};       ///< one or a few sentences
  std::vector<Param> params{};
  bool variadic = false;   ///< takes any number of extra positional values (print)
  /// The built-in may take the contents of arguments it alone holds (Arguments::sole_object):
  /// in `x = f(x, ...)` the interpreter then hands x's value over instead of keeping a second
  /// holder in x while the call runs. Such a built-in must not read the globals.
  bool takes_arguments = false;
  std::string area{};      ///< "core", "curves", "solids", ... (set by the table)
  /// Empty for constants.
  std::function<Value(const Arguments&)> run{};
  /// For constants (pi): the value the name stands for.
  std::optional<Value> constant{};
};

class BuiltinTable {
 public:
  /// Adds an entry. \throw std::logic_error if the name is already taken.
  void add(Builtin builtin);
  void set_area(std::string area) { area_ = std::move(area); }
  [[nodiscard]] const Builtin* find(const std::string& name) const;
  [[nodiscard]] const std::map<std::string, Builtin>& entries() const { return entries_; }

 private:
  std::map<std::string, Builtin> entries_;
  std::string area_ = "core";
};

/// The table, built once (thread-safe static initialization) from the register functions.
const BuiltinTable& builtins();

// One register function per library area (builtins_<area>.cpp).
void register_core(BuiltinTable& table);
void register_lists(BuiltinTable& table);  ///< in the core area (builtins_lists.cpp)
void register_curves(BuiltinTable& table);
void register_solids(BuiltinTable& table);
void register_bounds(BuiltinTable& table);  ///< bounds(x), in the solids area (builtins_bounds.cpp)
void register_splines(BuiltinTable& table);
void register_surfaces(BuiltinTable& table);
void register_revolution(BuiltinTable& table);
void register_reports(BuiltinTable& table);
void register_implicit(BuiltinTable& table);
void register_render(BuiltinTable& table);
void register_motions(BuiltinTable& table);
void register_view(BuiltinTable& table);  ///< show(x), in the view area (builtins_view.cpp)

/// Names of the language's keywords (for completion and the docs check).
std::span<const char* const> keywords();

}  // namespace sculpt::language
