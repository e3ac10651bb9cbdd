#pragma once
/// \file expression.hpp
/// A compact form of a function R^3 -> R for implicit curves and surfaces (Ihm & Naylor 1990,
/// sec. 5: curves f = g = 0 and surface patches f = 0). The function is a flat array of nodes in
/// topological order (every operand before its user), so evaluation is one loop without
/// recursion. A shared node (a local binding in the language) is evaluated once.
///
/// Three evaluations: the value; the value with its exact gradient (forward-mode automatic
/// differentiation); and outward-rounded interval bounds over a box, which the tracer uses to
/// discard boxes that cannot hold the curve.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "base/errors.hpp"

namespace sculpt::implicit {

/// An axis-aligned box [lo, hi]; valid when lo <= hi in every coordinate and all are finite.
struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
};

/// A closed interval [lo, hi]; lo may be -inf and hi +inf (the whole line).
struct Interval {
  double lo = 0.0;
  double hi = 0.0;
  [[nodiscard]] bool contains(double v) const { return lo <= v && v <= hi; }
};

/// Interval bounds of an expression over a box.
struct IntervalBounds {
  Interval range;             ///< every finite value the function takes on the box lies in range
  bool domain_error = false;  ///< some operation saw arguments outside its domain (sqrt of a negative)
};

/// A value with its exact gradient.
struct ValueGradient {
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
};

/// The function (or its gradient) is not finite at a point: division by zero, sqrt of a
/// negative number, overflow. Carries the point, so the caller can say where.
class NonFiniteValue : public InvalidInput {
 public:
  NonFiniteValue(const std::string& message, const Eigen::Vector3d& point)
      : InvalidInput(message), point_(point) {}
  [[nodiscard]] const Eigen::Vector3d& point() const { return point_; }

 private:
  Eigen::Vector3d point_;
};

/// The operations of an expression node.
enum class Op : std::uint8_t {
  Constant,
  X,
  Y,
  Z,  // leaves
  Neg,
  Sqrt,
  Sin,
  Cos,
  Exp,
  Abs,
  Pow,  // unary (Pow: integer exponent)
  Log,
  Asin,
  Acos,
  Atan,
  Sign,  // unary
  Add,
  Sub,
  Mul,
  Div,
  Min,
  Max,    // binary
  Atan2,  // binary: atan2(a, b), the angle of the point (b, a)
};

/// One node: operands a, b are indices of earlier nodes (-1 when unused).
struct ExpressionNode {
  Op op = Op::Constant;
  std::int32_t a = -1;
  std::int32_t b = -1;
  double constant = 0.0;  ///< Op::Constant
  int exponent = 0;       ///< Op::Pow
};

/// A handle to a node under construction in an ExpressionBuilder.
struct Term {
  std::int32_t index = -1;
};

/// A finished function R^3 -> R. A value type; cheap to copy for small functions.
class Expression {
 public:
  /// The value at p. \throw NonFiniteValue if it is not finite.
  [[nodiscard]] double value(const Eigen::Vector3d& p) const;
  /// Value and exact gradient at p (forward-mode AD). \throw NonFiniteValue if either is not finite.
  [[nodiscard]] ValueGradient value_gradient(const Eigen::Vector3d& p) const;
  /// Bounds over a box, outward rounded: every value of the function on the box lies in the range.
  /// Division by an interval containing 0 gives the whole line; sqrt, log, asin or acos of an
  /// interval partly outside their domain sets domain_error. \throw InvalidInput for an invalid box.
  [[nodiscard]] IntervalBounds bounds(const Box& box) const;

  [[nodiscard]] const std::vector<ExpressionNode>& nodes() const { return nodes_; }
  [[nodiscard]] std::size_t size() const { return nodes_.size(); }
  /// A readable infix form, for messages and tests.
  [[nodiscard]] std::string str() const;

 private:
  friend class ExpressionBuilder;
  std::vector<ExpressionNode> nodes_;  ///< topological order; the last node is the root
};

/// Builds an Expression node by node:
/// `ExpressionBuilder b; auto x = b.x(); Expression e = b.finish(b.sub(b.mul(x, x), b.constant(1)));`
/// Reusing a Term shares its node. \throw InvalidInput for a Term not from this builder,
/// a non-finite constant, or finish() on an empty builder.
class ExpressionBuilder {
 public:
  Term constant(double c);
  Term x();
  Term y();
  Term z();
  Term neg(Term a);
  Term add(Term a, Term b);
  Term sub(Term a, Term b);
  Term mul(Term a, Term b);
  Term div(Term a, Term b);
  Term pow(Term a, int exponent);  ///< integer power, negative allowed (1 / a^-n)
  Term sqrt(Term a);
  Term sin(Term a);
  Term cos(Term a);
  Term exp(Term a);
  Term abs(Term a);
  Term log(Term a);  ///< natural logarithm
  Term asin(Term a);
  Term acos(Term a);
  Term atan(Term a);
  Term sign(Term a);           ///< -1, 0 or 1 (gradient 0)
  Term atan2(Term a, Term b);  ///< the angle of the point (b, a) in [-pi, pi]
  Term min(Term a, Term b);
  Term max(Term a, Term b);
  /// The expression whose value is `root`; nodes root does not use are dropped.
  [[nodiscard]] Expression finish(Term root) const;

 private:
  Term push(ExpressionNode node);
  void check(Term t) const;
  std::vector<ExpressionNode> nodes_;
  std::int32_t x_ = -1, y_ = -1, z_ = -1;
};

}  // namespace sculpt::implicit
