#pragma once
/// \file operators.hpp
/// The meaning of the language's operators on values: arithmetic on numbers, element-wise
/// arithmetic on vectors (lists of numbers), string concatenation and comparison, equality on
/// everything, and whatever library objects define (solid `|`, `&`, `-`).

#include <stdexcept>

#include "language/ast.hpp"
#include "language/value.hpp"

namespace sculpt::language {

/// A value the operator cannot take; the interpreter adds the script position.
class OperatorError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// `a op b` for every binary operator except `and`/`or` (short-circuit, in the interpreter).
/// \throw OperatorError, or a library error from an object's operator.
Value apply_binary(ast::Op op, const Value& a, const Value& b);
/// The same, consuming `a`: when `a` is the only holder of a library object, the object may
/// move its contents into the result (Object::binary_sole; `w = w - x` on a solid reuses w's
/// tree). What any other value sees is unchanged.
Value apply_binary(ast::Op op, Value&& a, const Value& b);

/// `-a`, `+a`, `not a`. \throw OperatorError
Value apply_prefix(ast::Op op, const Value& a);

}  // namespace sculpt::language
