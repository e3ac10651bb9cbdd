#pragma once
/// \file value.hpp
/// Run-time values of the sculpt language: none, number, bool, string, list (a list of three
/// numbers is a vector), user function, built-in function, and opaque library objects
/// (curves, linearizations, solids) that each built-in area defines as an `Object` subclass.

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "language/ast.hpp"
#include "language/source.hpp"

namespace sculpt::language {

class Value;
struct Builtin;
using List = std::vector<Value>;

/// Lists may contain lists at most this deep (keeps printing, comparing and destroying values
/// free of deep recursion); building a deeper one raises RangeError.
inline constexpr int kMaxListDepth = 200;

struct ListData {
  List items;
  int depth = 1;  ///< 1 + the deepest list among the items
};

/// A function defined in a script with `fn`. It sees its parameters, its own local variables
/// and the global variables (no closures over an enclosing function's locals).
struct UserFunction {
  std::string name;
  std::vector<std::string> parameters;
  const ast::Block* body = nullptr;
  std::shared_ptr<const ast::Program> program;  ///< keeps `body` alive
  SourceRef where;                              ///< the definition
};

/// A value owned by a library area (curve, solid, ...). Immutable once built.
class Object {
 public:
  virtual ~Object() = default;
  /// Name used in messages and by type(): "curve", "solid", ...
  [[nodiscard]] virtual std::string type_name() const = 0;
  /// Short printable description, such as "<solid: 12 faces>".
  [[nodiscard]] virtual std::string repr() const = 0;
  /// Binary operators involving this object (`a | b` on solids, ...). `self_on_left` tells which
  /// side this object is on. nullopt = not supported (the interpreter reports a type error).
  [[nodiscard]] virtual std::optional<Value> binary(ast::Op op, const Value& other,
                                                    bool self_on_left) const;
  /// binary() when this object is the left operand and nothing but that operand holds it (a
  /// temporary, or a variable the statement overwrites: Value::sole_object): the object may move
  /// its contents into the result instead of copying them (a solid's tree). The default calls
  /// binary().
  [[nodiscard]] virtual std::optional<Value> binary_sole(ast::Op op, const Value& other);
};

struct None {};

class Value {
 public:
  using Storage = std::variant<None, double, bool, std::string, std::shared_ptr<const ListData>,
                               std::shared_ptr<const UserFunction>, const Builtin*,
                               std::shared_ptr<const Object>>;
  Value() = default;
  Value(double number) : data_(number) {}                       // NOLINT: implicit on purpose
  Value(bool flag) : data_(flag) {}                             // NOLINT
  Value(std::string text) : data_(std::move(text)) {}           // NOLINT
  Value(const char* text) : data_(std::string(text)) {}         // NOLINT
  /// \throw RangeError when the list would nest deeper than kMaxListDepth.
  Value(List items);  // NOLINT
  Value(std::shared_ptr<const UserFunction> f) : data_(std::move(f)) {}         // NOLINT
  Value(const Builtin* b) : data_(b) {}                                         // NOLINT
  Value(std::shared_ptr<const Object> o) : data_(std::move(o)) {}               // NOLINT

  [[nodiscard]] const Storage& data() const { return data_; }
  template <typename T>
  [[nodiscard]] bool is() const { return std::holds_alternative<T>(data_); }
  template <typename T>
  [[nodiscard]] const T* get() const { return std::get_if<T>(&data_); }
  [[nodiscard]] bool is_none() const { return is<None>(); }
  [[nodiscard]] const List* list() const {
    auto p = get<std::shared_ptr<const ListData>>();
    return p ? &(*p)->items : nullptr;
  }
  [[nodiscard]] int list_depth() const {
    auto p = get<std::shared_ptr<const ListData>>();
    return p ? (*p)->depth : 0;
  }
  /// The library object if it is of type T, else null.
  template <typename T>
  [[nodiscard]] const T* object() const {
    auto p = get<std::shared_ptr<const Object>>();
    return p ? dynamic_cast<const T*>(p->get()) : nullptr;
  }
  /// Copy on write: the library object when this value is its only holder (no variable, list
  /// or other value can see it), else null. Only the value's owner may use it, to take the
  /// object's contents (a built-in its call's arguments, the interpreter an operand it is about
  /// to drop); every other holder keeps seeing an unchanged object, so values stay values.
  [[nodiscard]] Object* sole_object() const {
    auto p = get<std::shared_ptr<const Object>>();
    // Objects are made non-const (std::make_shared<T>) and shared as const: casting back is sound.
    return p && p->use_count() == 1 ? const_cast<Object*>(p->get()) : nullptr;
  }

 private:
  Storage data_;
};

/// "number", "string", "list", "function", "solid", ...
std::string type_name(const Value& value);
/// The shortest decimal that reads back as exactly `number` (std::to_chars).
std::string format_number(double number);
/// How print() shows a value: strings without quotes.
std::string to_display(const Value& value);
/// How the REPL and lists show a value: strings quoted and escaped.
std::string to_repr(const Value& value);
/// Structural equality for none, numbers, bools, strings and lists; identity otherwise.
bool equal(const Value& a, const Value& b);

}  // namespace sculpt::language
