#pragma once
/// \file last_solid.hpp
/// The last solid a script made, for sculpt -o and the view: the value of the latest solid
/// expression statement run outside functions, or the global most recently bound to a solid,
/// whichever came later.

#include <cstdint>
#include <optional>

#include "language/interpreter.hpp"
#include "language/solid_values.hpp"

namespace sculpt::repl {

struct LastSolid {
  const language::Interpreter* interpreter = nullptr;
  std::optional<language::Value> value;  ///< the latest solid expression statement's value
  std::uint64_t serial = 0;              ///< the assignment serial when it was made

  /// Give it InterpreterOptions::top_level_value's values.
  void see(const language::Value& v) {
    if (v.object<language::SolidValue>()) value = v, serial = interpreter->assignments();
  }
  [[nodiscard]] std::optional<language::Value> get() const {
    const std::string name = language::latest_solid_global(*interpreter);
    if (value && (name.empty() || serial >= interpreter->assigned_at(name))) return value;
    if (!name.empty()) return *interpreter->global(name);
    return std::nullopt;
  }
};

}  // namespace sculpt::repl
