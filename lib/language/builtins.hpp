#pragma once
/// \file builtins.hpp
/// The table of built-in functions and constants. One table drives the interpreter, `:help`,
/// tab completion and the reference (a test checks that docs/language.md documents every entry).
///
/// Adding a built-in: declare it in the `builtins_<area>.cpp` of its library area, inside that
/// file's `register_<area>(BuiltinTable&)` function: its parameters with their names, kinds,
/// checks and defaults (taken from the library's option structs), and a body that reads its
/// arguments by name. The signature (`sphere(r, segments=32, d=diameter)`), the checks with their
/// errors at the argument, `:help` and the docs test all follow from the declaration:
///
///     table.add({.name = "sphere",
///                .doc = "Sphere of radius r ...",
///                .params = {arg("r").positive(),
///                           arg("segments").integer(3, 100000).defaults(double(CircularOptions{}.segments))},
///                .run = [](const Arguments& args) -> Value {
///                  return solid_value(sphere(args.number("r"), {.segments = int(args.integer("segments"))}));
///                }});
///
/// Then add its test and its entry `### `signature`` in docs/language.md (the docs test names the
/// heading it wants). A new area also adds its register function to the list in builtins.cpp.

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kernel/grid.hpp"
#include "language/shown_part.hpp"
#include "language/value.hpp"

namespace sculpt::language {

/// What a parameter accepts (Param::kind). The interpreter checks a given argument against its
/// parameter's kind and bounds before the built-in runs, in one place (Arguments' constructor),
/// and reports a mismatch at the argument.
enum class Kind {
  Any,       ///< anything: the built-in checks it (several types, a curve or a list of points, ...)
  Number,    ///< a number, within the bounds (Param::at_least, positive, ...)
  Integer,   ///< a whole number in [Param::low, Param::high]
  Bool,      ///< true or false
  String,    ///< a string
  Items,     ///< a list
  Vector,    ///< a list of Param::length numbers
  Function,  ///< a user fn or a built-in
  Object,    ///< a library value Param::accepts takes (Param::of<T>)
};

/// A parameter of a built-in, declared once: its name, what it accepts, its default. The
/// signature (`:help`, the docs test), the checks and the errors all follow from it. Made with
/// arg() and the chained setters, nanobind style:
///
///     arg("r").positive()                                      // required, a finite number > 0
///     arg("segments").integer(3, 100000).defaults(CircularOptions{}.segments)
///     arg("tol").positive().optional("e")                      // may be left out; shown as tol=e
///     arg("s").of<SolidValue>("a solid")
struct Param {
  std::string name{};
  bool required = true;
  Kind kind = Kind::Any;
  /// Number / Integer: the smallest and largest values; `low_open`: low itself is refused.
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool low_open = false;
  bool finite = false;     ///< Number: must be finite
  bool nonzero = false;    ///< Number: must not be 0
  std::size_t length = 0;  ///< Vector: the number of items
  /// Object: whether a value is one this parameter takes, and what it is called in errors.
  bool (*accepts)(const Value&) = nullptr;
  std::string what{};  ///< Any / Object: the accepted values in words ("a solid"), for errors and :help
  /// The value a left-out argument stands for (Arguments::value and the typed readers return it).
  std::optional<Value> fallback{};
  std::string shown{};          ///< in the signature instead of the name (`"file.off"`)
  std::string shown_default{};  ///< in the signature after `=` instead of the fallback (`e`)

  // Setters (each returns the parameter, for chaining).
  Param&& number() && {
    kind = Kind::Number;
    return std::move(*this);
  }
  Param&& finite_number() && {
    kind = Kind::Number;
    finite = true;
    return std::move(*this);
  }
  /// A finite number > 0.
  Param&& positive() && {
    kind = Kind::Number;
    finite = true;
    low = 0;
    low_open = true;
    return std::move(*this);
  }
  /// A finite number >= x.
  Param&& at_least(double x) && {
    kind = Kind::Number;
    finite = true;
    low = x;
    return std::move(*this);
  }
  /// A finite number in [a, b].
  Param&& between(double a, double b) && {
    kind = Kind::Number;
    finite = true;
    low = a;
    high = b;
    return std::move(*this);
  }
  /// A finite number other than 0.
  Param&& non_zero() && {
    kind = Kind::Number;
    finite = true;
    nonzero = true;
    return std::move(*this);
  }
  /// A whole number in [a, b].
  Param&& integer(double a, double b) && {
    kind = Kind::Integer;
    low = a;
    high = b;
    return std::move(*this);
  }
  Param&& boolean() && {
    kind = Kind::Bool;
    return std::move(*this);
  }
  Param&& string() && {
    kind = Kind::String;
    return std::move(*this);
  }
  Param&& list() && {
    kind = Kind::Items;
    return std::move(*this);
  }
  /// A list of n numbers.
  Param&& vector(std::size_t n) && {
    kind = Kind::Vector;
    length = n;
    return std::move(*this);
  }
  Param&& function() && {
    kind = Kind::Function;
    return std::move(*this);
  }
  /// A library value of type T (an Object), called `name` in errors ("a solid").
  template <typename T>
  Param&& of(std::string description) && {
    kind = Kind::Object;
    accepts = [](const Value& v) { return v.object<T>() != nullptr; };
    what = std::move(description);
    return std::move(*this);
  }
  /// Any value, described in words for :help and errors (the built-in checks it).
  Param&& any(std::string description) && {
    what = std::move(description);
    return std::move(*this);
  }
  /// May be left out; `shown` is how the signature shows its default (`e`, `[min, max]`), or
  /// nothing (`name=name` is not shown: just `name`).
  Param&& optional(std::string text = "") && {
    required = false;
    shown_default = std::move(text);
    return std::move(*this);
  }
  /// May be left out, standing for `value` then (shown in the signature as `name=value`).
  Param&& defaults(Value value) && {
    required = false;
    fallback = std::move(value);
    return std::move(*this);
  }
  /// Shown in the signature as `text` instead of its name (`"file.off"`).
  Param&& shown_as(std::string text) && {
    shown = std::move(text);
    return std::move(*this);
  }

  /// What the parameter accepts in words ("a finite number > 0", "a whole number from 3 to 100"),
  /// or "" for Kind::Any without a description.
  [[nodiscard]] std::string accepted() const;
  /// How the signature shows it: `r`, `segments=32`, `tol=e`, `"file.off"`.
  [[nodiscard]] std::string signature() const;
};

/// A required parameter of any kind named `name` (see Param for the setters).
inline Param arg(std::string name) { return Param{.name = std::move(name)}; }

/// Settings of a run that built-ins may consult.
struct RunSettings {
  std::ostream* out = nullptr;   ///< where print() writes
  /// Where built-ins write their summaries, notes and warnings (trace, implicit, stats, export):
  /// standard error, so that standard output is the script's own prints. Null: `out`.
  std::ostream* err = nullptr;
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
  /// Called with the path of each file a built-in reads (InterpreterOptions::file_read).
  std::function<void(const std::string& path)> file_read{};
};

/// The arguments of one call, bound to the built-in's parameters, with their script positions
/// so that errors point at the right place. The constructor checks each given argument against
/// its parameter's declaration (Param); the readers take the parameter's name and return its
/// default when it was left out.
class Arguments {
 public:
  /// \throw ScriptError at the argument when one does not fit its parameter's declaration.
  Arguments(const Builtin& builtin, SourceRef call, std::vector<const Value*> bound,
            std::vector<SourceRef> positions, std::vector<Value> rest,
            std::vector<SourceRef> rest_positions, const RunSettings& settings);

  /// The argument of parameter `name` was given. (Naming a parameter the built-in does not
  /// declare is a programming error: std::logic_error.)
  [[nodiscard]] bool has(std::string_view name) const { return bound_[index(name)] != nullptr; }
  /// Its value: the argument, else the parameter's default, else none.
  [[nodiscard]] const Value& value(std::string_view name) const;
  /// The typed readers: the value, checked (the declared kind was checked already; these check
  /// it again for Kind::Any parameters).
  [[nodiscard]] double number(std::string_view name) const;
  /// A whole number within the parameter's declared range (Param::integer).
  [[nodiscard]] long long integer(std::string_view name) const;
  /// A whole number in [low, high] (for a parameter that is not always one, circle(n) or circle(r, n)).
  [[nodiscard]] long long integer(std::string_view name, long long low, long long high) const;
  [[nodiscard]] bool boolean(std::string_view name) const;
  [[nodiscard]] const std::string& string(std::string_view name) const;
  [[nodiscard]] const List& list(std::string_view name) const;
  /// A list of the declared number of numbers (Param::vector), or of n when n > 0.
  [[nodiscard]] std::vector<double> vector(std::string_view name, std::size_t n = 0) const;
  /// A list of three numbers as a point or direction.
  [[nodiscard]] Eigen::Vector3d point(std::string_view name) const;
  /// A function (user-defined or built-in).
  [[nodiscard]] const Value& function(std::string_view name) const;
  /// Calls function value `f` with positional `values`; an error inside it gets a note at this call.
  Value call(const Value& f, std::vector<Value> values) const;
  /// The library object of parameter `name`, which must be of type T (`what` names it in errors;
  /// by default the parameter's description, Param::of).
  template <typename T>
  [[nodiscard]] const T& object(std::string_view name, const char* what = nullptr) const {
    if (const T* o = value(name).object<T>()) return *o;
    fail_type(name, what ? what : param(name).what.c_str());
  }
  /// Copy on write: the argument's library object, of type T, for the built-in to take its
  /// contents, when the call's argument is its only holder (a temporary, or the variable the
  /// statement assigns to, which the interpreter hands over to built-ins marked
  /// Builtin::takes_arguments); else null, and the built-in must not change it. Check the
  /// arguments first: an error after taking cannot give the contents back.
  template <typename T>
  [[nodiscard]] T* sole_object(std::string_view name) const {
    const std::size_t i = index(name);
    return bound_[i] ? dynamic_cast<T*>(bound_[i]->sole_object()) : nullptr;
  }
  /// Values of a variadic built-in beyond its parameters (print).
  [[nodiscard]] const std::vector<Value>& rest() const { return rest_; }

  /// Error at the argument's position (at the call when it was left out) / at the call.
  [[noreturn]] void fail(std::string_view name, const std::string& message) const;
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail(const char* message) const { fail(std::string(message)); }
  /// "argument 'name' must be <expected>, got <type>".
  [[noreturn]] void fail_type(std::string_view name, const std::string& expected) const;
  /// Counts `n` steps of work (items made) against the run's step limit.
  void charge(std::uint64_t n) const;
  /// Refuses when files are disabled; else the path argument resolved against the calling
  /// script's folder.
  [[nodiscard]] std::string file_path(std::string_view name) const;
  /// file_path for a file the built-in reads: also reported to RunSettings::file_read (the live
  /// view runs the script again when it changes).
  [[nodiscard]] std::string input_path(std::string_view name) const;

  /// The global variable `name` of the run, or null.
  [[nodiscard]] const Value* global(const std::string& name) const;
  /// The global variables of the run (empty when the run has none).
  [[nodiscard]] const std::map<std::string, Value>& globals() const;

  /// The grid new solids are made at (RunSettings::grid).
  [[nodiscard]] kernel::Grid grid() const { return settings_.grid ? *settings_.grid : kernel::Grid{}; }
  /// Sets it (the built-in grid()). \throw std::logic_error if the run has no grid setting.
  void set_grid(const kernel::Grid& grid) const;

  /// print()'s stream (standard output).
  [[nodiscard]] std::ostream& out() const { return *settings_.out; }
  /// The stream of summaries, notes and warnings (RunSettings::err).
  [[nodiscard]] std::ostream& err() const { return settings_.err ? *settings_.err : *settings_.out; }
  /// The run's list of shown parts (RunSettings::shown), or null.
  [[nodiscard]] std::vector<ShownPart>* shown() const { return settings_.shown; }
  [[nodiscard]] const SourceRef& call() const { return call_; }

 private:
  /// The position of parameter `name` in the declaration. \throw std::logic_error if none.
  [[nodiscard]] std::size_t index(std::string_view name) const;
  [[nodiscard]] const Param& param(std::string_view name) const;
  /// Checks argument i against its declaration (the constructor).
  void check(std::size_t i) const;
  [[noreturn]] void fail_at(std::size_t i, const std::string& message) const;

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
  /// As shown by :help, e.g. "box(min, max)": made by BuiltinTable::add from the parameters
  /// (Param::signature) unless given.
  std::string signature{};
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
  /// Adds an entry, making its signature from its parameters.
  /// \throw std::logic_error if the name is already taken.
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

/// "(x, y, z)" with each coordinate as format_number writes it.
std::string format_point(const Eigen::Vector3d& p);

}  // namespace sculpt::language
