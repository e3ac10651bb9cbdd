#include "implicit/expression.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "implicit/detail/interval_arithmetic.hpp"

namespace sculpt::implicit {
namespace {

using Vec = Eigen::Vector3d;

std::string point_text(const Vec& p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Scratch storage for one evaluation: on the stack for small expressions.
template <typename T>
class Scratch {
 public:
  explicit Scratch(std::size_t n) {
    if (n > small_.size()) large_.resize(n);
  }
  T& operator[](std::size_t i) { return large_.empty() ? small_[i] : large_[i]; }

 private:
  std::array<T, 64> small_;  // not value-initialized: every slot is written before it is read
  std::vector<T> large_;
};

struct Dual {  // trivially constructible, so that Scratch<Dual> costs nothing to set up
  double v;
  Vec d;
};

}  // namespace

double Expression::value(const Vec& p) const {
  Scratch<double> s(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const ExpressionNode& n = nodes_[i];
    const double a = n.a >= 0 ? s[n.a] : 0.0, b = n.b >= 0 ? s[n.b] : 0.0;
    double r = 0.0;
    switch (n.op) {
      case Op::Constant: r = n.constant; break;
      case Op::X: r = p.x(); break;
      case Op::Y: r = p.y(); break;
      case Op::Z: r = p.z(); break;
      case Op::Neg: r = -a; break;
      case Op::Sqrt: r = std::sqrt(a); break;
      case Op::Sin: r = std::sin(a); break;
      case Op::Cos: r = std::cos(a); break;
      case Op::Exp: r = std::exp(a); break;
      case Op::Abs: r = std::abs(a); break;
      case Op::Pow: r = detail::power_by_squaring(a, n.exponent); break;
      case Op::Add: r = a + b; break;
      case Op::Sub: r = a - b; break;
      case Op::Mul: r = a * b; break;
      case Op::Div: r = a / b; break;
      case Op::Min: r = std::min(a, b); break;
      case Op::Max: r = std::max(a, b); break;
    }
    s[i] = r;
  }
  const double v = nodes_.empty() ? 0.0 : s[nodes_.size() - 1];
  if (!std::isfinite(v)) throw NonFiniteValue("function value is not finite at " + point_text(p), p);
  return v;
}

// Forward-mode automatic differentiation: each node carries its value and its gradient.
ValueGradient Expression::value_gradient(const Vec& p) const {
  static const Dual kZero{0.0, Vec::Zero()};
  Scratch<Dual> s(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const ExpressionNode& n = nodes_[i];
    const Dual& a = n.a >= 0 ? s[n.a] : kZero;
    const Dual& b = n.b >= 0 ? s[n.b] : kZero;
    Dual r = kZero;
    switch (n.op) {
      case Op::Constant: r.v = n.constant; break;
      case Op::X: r = {p.x(), Vec::UnitX()}; break;
      case Op::Y: r = {p.y(), Vec::UnitY()}; break;
      case Op::Z: r = {p.z(), Vec::UnitZ()}; break;
      case Op::Neg: r = {-a.v, -a.d}; break;
      case Op::Sqrt: r.v = std::sqrt(a.v); r.d = a.d / (2.0 * r.v); break;
      case Op::Sin: r = {std::sin(a.v), std::cos(a.v) * a.d}; break;
      case Op::Cos: r = {std::cos(a.v), -std::sin(a.v) * a.d}; break;
      case Op::Exp: r.v = std::exp(a.v); r.d = r.v * a.d; break;
      case Op::Abs: r = {std::abs(a.v), (a.v > 0.0 ? 1.0 : a.v < 0.0 ? -1.0 : 0.0) * a.d}; break;
      case Op::Pow:
        r.v = detail::power_by_squaring(a.v, n.exponent);
        r.d = n.exponent == 0 ? Vec::Zero() : Vec(n.exponent * detail::power_by_squaring(a.v, n.exponent - 1) * a.d);
        break;
      case Op::Add: r = {a.v + b.v, a.d + b.d}; break;
      case Op::Sub: r = {a.v - b.v, a.d - b.d}; break;
      case Op::Mul: r = {a.v * b.v, a.v * b.d + b.v * a.d}; break;
      case Op::Div: r.v = a.v / b.v; r.d = (a.d - r.v * b.d) / b.v; break;
      case Op::Min: r = a.v <= b.v ? a : b; break;
      case Op::Max: r = a.v >= b.v ? a : b; break;
    }
    s[i] = r;
  }
  ValueGradient out;
  if (!nodes_.empty()) out = {s[nodes_.size() - 1].v, s[nodes_.size() - 1].d};
  if (!std::isfinite(out.value)) throw NonFiniteValue("function value is not finite at " + point_text(p), p);
  if (!out.gradient.allFinite()) throw NonFiniteValue("function gradient is not finite at " + point_text(p), p);
  return out;
}

IntervalBounds Expression::bounds(const Box& box) const {
  if (!box.lo.allFinite() || !box.hi.allFinite() || (box.lo.array() > box.hi.array()).any())
    throw InvalidInput("interval bounds need a box with finite lo <= hi");
  namespace d = detail;
  IntervalBounds out;
  Scratch<Interval> s(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const ExpressionNode& n = nodes_[i];
    const Interval a = n.a >= 0 ? s[n.a] : Interval{}, b = n.b >= 0 ? s[n.b] : Interval{};
    Interval r;
    switch (n.op) {
      case Op::Constant: r = d::point_interval(n.constant); break;
      case Op::X: r = {box.lo.x(), box.hi.x()}; break;
      case Op::Y: r = {box.lo.y(), box.hi.y()}; break;
      case Op::Z: r = {box.lo.z(), box.hi.z()}; break;
      case Op::Neg: r = d::neg(a); break;
      case Op::Sqrt: r = d::sqrt(a, out.domain_error); break;
      case Op::Sin: r = d::sin(a); break;
      case Op::Cos: r = d::cos(a); break;
      case Op::Exp: r = d::exp(a); break;
      case Op::Abs: r = d::abs(a); break;
      case Op::Pow: r = d::pow(a, n.exponent); break;
      case Op::Add: r = d::add(a, b); break;
      case Op::Sub: r = d::sub(a, b); break;
      case Op::Mul: r = d::mul(a, b); break;
      case Op::Div: r = d::div(a, b); break;
      case Op::Min: r = d::min(a, b); break;
      case Op::Max: r = d::max(a, b); break;
    }
    if (std::isnan(r.lo) || std::isnan(r.hi)) r = d::whole_line();
    s[i] = r;
  }
  if (!nodes_.empty()) out.range = s[nodes_.size() - 1];
  return out;
}

std::string Expression::str() const {
  std::vector<std::string> t(nodes_.size());
  auto unary = [&](const char* name, const ExpressionNode& n) { return std::string(name) + "(" + t[n.a] + ")"; };
  auto binary = [&](const char* op, const ExpressionNode& n) { return "(" + t[n.a] + " " + op + " " + t[n.b] + ")"; };
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const ExpressionNode& n = nodes_[i];
    switch (n.op) {
      case Op::Constant: {
        std::ostringstream s;
        s.precision(17);
        s << n.constant;
        t[i] = s.str();
        break;
      }
      case Op::X: t[i] = std::string(1, 'x'); break;  // not = "x": GCC 12 -Wrestrict false positive
      case Op::Y: t[i] = std::string(1, 'y'); break;
      case Op::Z: t[i] = std::string(1, 'z'); break;
      case Op::Neg: t[i] = "-" + t[n.a]; break;
      case Op::Sqrt: t[i] = unary("sqrt", n); break;
      case Op::Sin: t[i] = unary("sin", n); break;
      case Op::Cos: t[i] = unary("cos", n); break;
      case Op::Exp: t[i] = unary("exp", n); break;
      case Op::Abs: t[i] = unary("abs", n); break;
      case Op::Pow: t[i] = t[n.a] + "^" + std::to_string(n.exponent); break;
      case Op::Add: t[i] = binary("+", n); break;
      case Op::Sub: t[i] = binary("-", n); break;
      case Op::Mul: t[i] = binary("*", n); break;
      case Op::Div: t[i] = binary("/", n); break;
      case Op::Min: t[i] = "min(" + t[n.a] + ", " + t[n.b] + ")"; break;
      case Op::Max: t[i] = "max(" + t[n.a] + ", " + t[n.b] + ")"; break;
    }
  }
  return t.empty() ? "" : t.back();
}

// --- builder ---------------------------------------------------------------------------------

void ExpressionBuilder::check(Term t) const {
  if (t.index < 0 || t.index >= static_cast<std::int32_t>(nodes_.size()))
    throw InvalidInput("expression term does not belong to this builder");
}

Term ExpressionBuilder::push(ExpressionNode node) {
  nodes_.push_back(node);
  return {static_cast<std::int32_t>(nodes_.size() - 1)};
}

Term ExpressionBuilder::constant(double c) {
  if (!std::isfinite(c)) throw InvalidInput("expression constant must be finite");
  return push({.op = Op::Constant, .constant = c});
}
Term ExpressionBuilder::x() {
  if (x_ < 0) x_ = push({.op = Op::X}).index;
  return {x_};
}
Term ExpressionBuilder::y() {
  if (y_ < 0) y_ = push({.op = Op::Y}).index;
  return {y_};
}
Term ExpressionBuilder::z() {
  if (z_ < 0) z_ = push({.op = Op::Z}).index;
  return {z_};
}

#define SCULPT_UNARY(name, opcode)            \
  Term ExpressionBuilder::name(Term a) {      \
    check(a);                                 \
    return push({.op = opcode, .a = a.index}); \
  }
#define SCULPT_BINARY(name, opcode)                         \
  Term ExpressionBuilder::name(Term a, Term b) {            \
    check(a);                                               \
    check(b);                                               \
    return push({.op = opcode, .a = a.index, .b = b.index}); \
  }
SCULPT_UNARY(neg, Op::Neg)
SCULPT_UNARY(sqrt, Op::Sqrt)
SCULPT_UNARY(sin, Op::Sin)
SCULPT_UNARY(cos, Op::Cos)
SCULPT_UNARY(exp, Op::Exp)
SCULPT_UNARY(abs, Op::Abs)
SCULPT_BINARY(add, Op::Add)
SCULPT_BINARY(sub, Op::Sub)
SCULPT_BINARY(mul, Op::Mul)
SCULPT_BINARY(div, Op::Div)
SCULPT_BINARY(min, Op::Min)
SCULPT_BINARY(max, Op::Max)
#undef SCULPT_UNARY
#undef SCULPT_BINARY

Term ExpressionBuilder::pow(Term a, int exponent) {
  check(a);
  return push({.op = Op::Pow, .a = a.index, .exponent = exponent});
}

Expression ExpressionBuilder::finish(Term root) const {
  if (nodes_.empty()) throw InvalidInput("cannot finish an empty expression");
  check(root);
  // Keep the nodes root uses, in their order (still topological), and renumber the operands.
  std::vector<char> used(nodes_.size(), 0);
  used[root.index] = 1;
  for (std::int32_t i = root.index; i >= 0; --i) {
    if (!used[i]) continue;
    if (nodes_[i].a >= 0) used[nodes_[i].a] = 1;
    if (nodes_[i].b >= 0) used[nodes_[i].b] = 1;
  }
  std::vector<std::int32_t> renumber(nodes_.size(), -1);
  Expression e;
  for (std::int32_t i = 0; i <= root.index; ++i) {
    if (!used[i]) continue;
    ExpressionNode n = nodes_[i];
    if (n.a >= 0) n.a = renumber[n.a];
    if (n.b >= 0) n.b = renumber[n.b];
    renumber[i] = static_cast<std::int32_t>(e.nodes_.size());
    e.nodes_.push_back(n);
  }
  return e;
}

}  // namespace sculpt::implicit
