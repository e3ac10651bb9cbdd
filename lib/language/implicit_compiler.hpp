#pragma once
/// \file implicit_compiler.hpp
/// Compiles a script function `fn f(x, y, z) { ... }` (or `fn f(p)` taking a point [x, y, z])
/// into an implicit::Expression, so that the tracer of implicit curves (Ihm & Naylor 1990,
/// sec. 5.1) evaluates values, exact gradients and interval bounds without running the
/// interpreter point by point.
///
/// The subset (docs/language.md, "Implicit functions"): numbers; + - * / and prefix -;
/// `pow(a, n)` with a whole-number constant n; sqrt, sin, cos, tan, exp, abs, min, max (two or
/// more arguments, or one vector); vectors of numbers with constant indices, `dot`, `norm`,
/// `cross`; local bindings `name = e`; `return e` or a final expression; calls of other such
/// functions (inlined; recursion is an error); global numbers, vectors of numbers and functions
/// (their values when the function is compiled), and `pi`. Parts whose operands are all
/// constants are folded as the interpreter computes them. Everything else (if, for, comparisons,
/// and/or/not, strings, booleans, solids, `%`, other built-ins, include, nested fn) is a
/// ScriptError at the construct, naming it.

#include <cstddef>
#include <functional>
#include <string>

#include "implicit/expression.hpp"
#include "language/source.hpp"
#include "language/value.hpp"

namespace sculpt::language {

struct ImplicitCompileOptions {
  /// The value of a global name, or null when there is none (the interpreter's globals at the
  /// call; built-in names are looked up by the compiler itself).
  std::function<const Value*(const std::string&)> global{};
  /// Largest expression (nodes, before unused ones are dropped); inlining can multiply sizes.
  /// The tracer evaluates an expression tens of thousands of times, so a larger one would be
  /// traced for minutes.
  std::size_t max_nodes = 100'000;
  /// Most syntax-tree expressions and calls compiled, inlined ones counted each time: a chain of
  /// calls on constants doubles the work per level without making any node.
  std::size_t max_work = 250'000;
  /// Calls of user functions may nest this deep (each is inlined).
  int max_call_depth = 64;
  /// Bytes of C++ stack the compiler may use (it recurses over the syntax tree, whose depth the
  /// parser bounds, and into inlined calls, bounded by max_call_depth: about 20 KiB per call
  /// under AddressSanitizer, so max_call_depth is reached first). At most a quarter of the
  /// process's stack limit is used.
  std::size_t stack_budget = 2u << 20;
};

/// The function `f` as an expression of x, y, z. `f` takes three numbers (x, y, z) or one point.
/// \throw ScriptError at the construct that is not in the subset, with "in call to" notes for
///        inlined calls; or at the definition of `f` for a wrong parameter count or no result.
[[nodiscard]] implicit::Expression compile_implicit(const UserFunction& f, const ImplicitCompileOptions& options);

}  // namespace sculpt::language
