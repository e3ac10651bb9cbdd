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
  T* data() { return large_.empty() ? small_.data() : large_.data(); }

 private:
  std::array<T, 64> small_;  // not value-initialized: every slot is written before it is read
  std::vector<T> large_;
};

struct Dual {  // trivially constructible, so that Scratch<Dual> costs nothing to set up
  double v;
  Vec d;
};

}  // namespace

// The evaluators below read a node's operands only in the cases that have them (the builder
// gives every unary node an `a` and every binary node an `a` and a `b`), through a plain
// pointer, and write the result in place: the same arithmetic as node-by-node evaluation with
// zero-filled missing operands, in far fewer instructions (they are the inner loop of
// polygonize's edge splits and collapses).
double Expression::value(const Vec& p) const {
  const std::size_t n = nodes_.size();
  if (n == 0) return 0.0;
  Scratch<double> scratch(n);
  double* s = scratch.data();
  for (std::size_t i = 0; i < n; ++i) {
    const ExpressionNode& node = nodes_[i];
    double& r = s[i];
    switch (node.op) {
      case Op::Constant: r = node.constant; break;
      case Op::X: r = p.x(); break;
      case Op::Y: r = p.y(); break;
      case Op::Z: r = p.z(); break;
      case Op::Neg: r = -s[node.a]; break;
      case Op::Sqrt: r = std::sqrt(s[node.a]); break;
      case Op::Sin: r = std::sin(s[node.a]); break;
      case Op::Cos: r = std::cos(s[node.a]); break;
      case Op::Exp: r = std::exp(s[node.a]); break;
      case Op::Abs: r = std::abs(s[node.a]); break;
      case Op::Log:
        r = std::log(s[node.a]);
        break;
      case Op::Asin:
        r = std::asin(s[node.a]);
        break;
      case Op::Acos:
        r = std::acos(s[node.a]);
        break;
      case Op::Atan:
        r = std::atan(s[node.a]);
        break;
      case Op::Sign:
        r = s[node.a] > 0.0 ? 1.0 : s[node.a] < 0.0 ? -1.0 : 0.0;
        break;
      case Op::Atan2:
        r = std::atan2(s[node.a], s[node.b]);
        break;
      case Op::Pow: r = node.exponent == 2 ? s[node.a] * s[node.a] : detail::power_by_squaring(s[node.a], node.exponent); break;
      case Op::Add: r = s[node.a] + s[node.b]; break;
      case Op::Sub: r = s[node.a] - s[node.b]; break;
      case Op::Mul: r = s[node.a] * s[node.b]; break;
      case Op::Div: r = s[node.a] / s[node.b]; break;
      case Op::Min: r = std::min(s[node.a], s[node.b]); break;
      case Op::Max: r = std::max(s[node.a], s[node.b]); break;
    }
  }
  const double v = s[n - 1];
  if (!std::isfinite(v)) throw NonFiniteValue("function value is not finite at " + point_text(p), p);
  return v;
}

// Forward-mode automatic differentiation: each node carries its value and its gradient.
ValueGradient Expression::value_gradient(const Vec& p) const {
  const std::size_t n = nodes_.size();
  if (n == 0) return {};
  Scratch<Dual> scratch(n);
  Dual* s = scratch.data();
  for (std::size_t i = 0; i < n; ++i) {
    const ExpressionNode& node = nodes_[i];
    Dual& r = s[i];
    switch (node.op) {
      case Op::Constant: r.v = node.constant; r.d.setZero(); break;
      case Op::X: r.v = p.x(); r.d = Vec::UnitX(); break;
      case Op::Y: r.v = p.y(); r.d = Vec::UnitY(); break;
      case Op::Z: r.v = p.z(); r.d = Vec::UnitZ(); break;
      case Op::Neg: { const Dual& a = s[node.a]; r.v = -a.v; r.d = -a.d; break; }
      case Op::Sqrt: { const Dual& a = s[node.a]; r.v = std::sqrt(a.v); r.d = a.d / (2.0 * r.v); break; }
      case Op::Sin: { const Dual& a = s[node.a]; r.v = std::sin(a.v); r.d = std::cos(a.v) * a.d; break; }
      case Op::Cos: { const Dual& a = s[node.a]; r.v = std::cos(a.v); r.d = -std::sin(a.v) * a.d; break; }
      case Op::Exp: { const Dual& a = s[node.a]; r.v = std::exp(a.v); r.d = r.v * a.d; break; }
      case Op::Abs: {
        const Dual& a = s[node.a];
        r.v = std::abs(a.v);
        r.d = (a.v > 0.0 ? 1.0 : a.v < 0.0 ? -1.0 : 0.0) * a.d;
        break;
      }
      case Op::Log: {
        const Dual& a = s[node.a];
        r.v = std::log(a.v);
        r.d = a.d / a.v;
        break;
      }
      case Op::Asin: {
        const Dual& a = s[node.a];
        r.v = std::asin(a.v);
        r.d = a.d / std::sqrt(1.0 - a.v * a.v);
        break;
      }
      case Op::Acos: {
        const Dual& a = s[node.a];
        r.v = std::acos(a.v);
        r.d = -a.d / std::sqrt(1.0 - a.v * a.v);
        break;
      }
      case Op::Atan: {
        const Dual& a = s[node.a];
        r.v = std::atan(a.v);
        r.d = a.d / (1.0 + a.v * a.v);
        break;
      }
      case Op::Sign: {
        const Dual& a = s[node.a];
        r.v = a.v > 0.0 ? 1.0 : a.v < 0.0 ? -1.0 : 0.0;
        r.d.setZero();
        break;
      }
      case Op::Atan2: {  // d atan2(y, x) = (x dy - y dx) / (x^2 + y^2)
        const Dual &y = s[node.a], &x = s[node.b];
        r.v = std::atan2(y.v, x.v);
        r.d = (x.v * y.d - y.v * x.d) / (x.v * x.v + y.v * y.v);
        break;
      }
      case Op::Pow: {
        const Dual& a = s[node.a];
        if (node.exponent == 2) {  // power_by_squaring's own arithmetic for 2 (x * x) and 1 (x)
          r.v = a.v * a.v;
          r.d = (2 * a.v) * a.d;
        } else {
          r.v = detail::power_by_squaring(a.v, node.exponent);
          r.d = node.exponent == 0 ? Vec::Zero() : Vec(node.exponent * detail::power_by_squaring(a.v, node.exponent - 1) * a.d);
        }
        break;
      }
      case Op::Add: { const Dual &a = s[node.a], &b = s[node.b]; r.v = a.v + b.v; r.d = a.d + b.d; break; }
      case Op::Sub: { const Dual &a = s[node.a], &b = s[node.b]; r.v = a.v - b.v; r.d = a.d - b.d; break; }
      case Op::Mul: { const Dual &a = s[node.a], &b = s[node.b]; r.v = a.v * b.v; r.d = a.v * b.d + b.v * a.d; break; }
      case Op::Div: {
        const Dual &a = s[node.a], &b = s[node.b];
        r.v = a.v / b.v;
        r.d = (a.d - r.v * b.d) / b.v;
        break;
      }
      case Op::Min: { const Dual &a = s[node.a], &b = s[node.b]; r = a.v <= b.v ? a : b; break; }
      case Op::Max: { const Dual &a = s[node.a], &b = s[node.b]; r = a.v >= b.v ? a : b; break; }
    }
  }
  const ValueGradient out{s[n - 1].v, s[n - 1].d};
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
      case Op::Log:
        r = d::log(a, out.domain_error);
        break;
      case Op::Asin:
        r = d::asin(a, out.domain_error);
        break;
      case Op::Acos:
        r = d::acos(a, out.domain_error);
        break;
      case Op::Atan:
        r = d::atan(a);
        break;
      case Op::Sign:
        r = d::sign(a);
        break;
      case Op::Atan2:
        r = d::atan2(a, b);
        break;
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
      case Op::Log:
        t[i] = unary("log", n);
        break;
      case Op::Asin:
        t[i] = unary("asin", n);
        break;
      case Op::Acos:
        t[i] = unary("acos", n);
        break;
      case Op::Atan:
        t[i] = unary("atan", n);
        break;
      case Op::Sign:
        t[i] = unary("sign", n);
        break;
      case Op::Atan2:
        t[i] = "atan2(" + t[n.a] + ", " + t[n.b] + ")";
        break;
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
SCULPT_UNARY(log, Op::Log)
SCULPT_UNARY(asin, Op::Asin)
SCULPT_UNARY(acos, Op::Acos)
SCULPT_UNARY(atan, Op::Atan)
SCULPT_UNARY(sign, Op::Sign)
SCULPT_BINARY(atan2, Op::Atan2)
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
