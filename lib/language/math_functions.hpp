#pragma once
/// \file math_functions.hpp
/// The language's math functions of one or two numbers, declared once: the interpreter's
/// built-ins (builtins_core.cpp) and the implicit-function compiler (implicit_compiler.cpp) both
/// read this table, so a function has one value, one domain check and one message in both.
/// Angles are in radians, as for sin and cos. The table does not depend on the implicit layer
/// (the core built-ins are built without it for fuzzing): it names each function's compiled
/// form, and the compiler builds it.

#include <span>
#include <string>
#include <string_view>

namespace sculpt::language {

/// How the implicit-function compiler builds a function of terms (implicit::ExpressionBuilder).
enum class CompiledForm {
  None,  ///< not compiled: constant arguments are folded, anything else is an error
  Abs,
  Acos,
  Asin,
  Atan,
  Atan2,
  Cos,
  Exp,
  Exp2,
  Hypot,
  Log,
  Sign,
  Sin,
  Sqrt,
  Tan,
};

struct MathFunction {
  const char* name = "";
  const char* signature = "";
  const char* doc = "";
  int arity = 1;                           ///< 1 or 2 numbers
  const char* params[2] = {"x", nullptr};  ///< parameter names
  /// The value for numbers inside the domain (b is 0 for one argument).
  double (*value)(double a, double b) = nullptr;
  /// Empty when (a, b) lies in the domain, else why not ("square root of a negative number").
  std::string (*domain)(double a, double b) = nullptr;
  CompiledForm form = CompiledForm::None;
};

/// Every entry, in alphabetical order.
std::span<const MathFunction> math_functions();
/// The entry named `name`, or null.
const MathFunction* find_math_function(std::string_view name);

/// The value of `f` at (a, b): the domain check, then the value, which must be finite.
/// Returns the message of a failure ("acos: ..." without the name) in `error`, else "".
double evaluate(const MathFunction& f, double a, double b, std::string& error);

}  // namespace sculpt::language
