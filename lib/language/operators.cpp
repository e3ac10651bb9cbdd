#include "language/operators.hpp"

#include <cmath>
#include <utility>

namespace sculpt::language {
namespace {

using ast::Op;

/// For `+` and `*` on two solids (OpenSCAD users write union and intersection so): the operator.
std::string solid_hint(Op op, const Value& a, const Value& b) {
  if (type_name(a) != "solid" || type_name(b) != "solid") return "";
  if (op == Op::Add) return "; the union of solids is 'a | b'";
  if (op == Op::Mul) return "; the intersection of solids is 'a & b'";
  return "";
}

[[noreturn]] void unsupported(Op op, const Value& a, const Value& b) {
  throw OperatorError(std::string("cannot apply '") + ast::spelling(op) + "' to " + type_name(a) + " and " +
                      type_name(b) + solid_hint(op, a, b));
}

double finite(double x, Op op) {
  if (!std::isfinite(x)) {
    throw OperatorError(std::string("'") + ast::spelling(op) + "' gives a result that is not a finite number");
  }
  return x;
}

double arithmetic(Op op, double x, double y) {
  switch (op) {
    case Op::Add: return finite(x + y, op);
    case Op::Sub: return finite(x - y, op);
    case Op::Mul: return finite(x * y, op);
    case Op::Div:
      if (y == 0) throw OperatorError("division by zero");
      return finite(x / y, op);
    case Op::Mod:
      if (y == 0) throw OperatorError("modulo by zero");
      return finite(x - y * std::floor(x / y), op);  // sign of the divisor, like Python
    default: break;
  }
  throw OperatorError("internal: not an arithmetic operator");
}

/// The numbers of a list, or nullopt if some item is not a number.
std::optional<std::vector<double>> numbers(const Value& v) {
  const List* list = v.list();
  if (!list) return std::nullopt;
  std::vector<double> out;
  out.reserve(list->size());
  for (const Value& item : *list) {
    const double* d = item.get<double>();
    if (!d) return std::nullopt;
    out.push_back(*d);
  }
  return out;
}

Value to_list(const std::vector<double>& xs) {
  List out(xs.begin(), xs.end());
  return Value(std::move(out));
}

template <typename Compare>
Value compare(Op op, const Value& a, const Value& b, Compare less) {
  switch (op) {
    case Op::Lt: return less(a, b);
    case Op::Gt: return less(b, a);
    case Op::Le: return !less(b, a);
    case Op::Ge: return !less(a, b);
    default: break;
  }
  unsupported(op, a, b);
}

bool is_comparison(Op op) { return op == Op::Lt || op == Op::Le || op == Op::Gt || op == Op::Ge; }
bool is_arithmetic(Op op) {
  return op == Op::Add || op == Op::Sub || op == Op::Mul || op == Op::Div || op == Op::Mod;
}

}  // namespace

Value apply_binary(Op op, const Value& a, const Value& b) {
  if (op == Op::Eq) return equal(a, b);
  if (op == Op::Ne) return !equal(a, b);

  // Library objects first: they define what operators mean for them.
  if (auto o = a.get<std::shared_ptr<const Object>>()) {
    if (auto r = (*o)->binary(op, b, true)) return *r;
    unsupported(op, a, b);
  }
  if (auto o = b.get<std::shared_ptr<const Object>>()) {
    if (auto r = (*o)->binary(op, a, false)) return *r;
    unsupported(op, a, b);
  }

  const double* x = a.get<double>();
  const double* y = b.get<double>();
  if (x && y) {
    if (is_arithmetic(op)) return arithmetic(op, *x, *y);
    if (is_comparison(op)) {
      return compare(op, a, b, [](const Value& p, const Value& q) { return *p.get<double>() < *q.get<double>(); });
    }
    unsupported(op, a, b);
  }

  const std::string* s = a.get<std::string>();
  const std::string* t = b.get<std::string>();
  if (s && t) {
    if (op == Op::Add) return *s + *t;
    if (is_comparison(op)) {
      return compare(op, a, b, [](const Value& p, const Value& q) { return *p.get<std::string>() < *q.get<std::string>(); });
    }
    unsupported(op, a, b);
  }

  // Vectors: element-wise + and -, scaling by a number.
  if (!is_arithmetic(op)) unsupported(op, a, b);
  const auto u = numbers(a);
  const auto v = numbers(b);
  if (u && v && (op == Op::Add || op == Op::Sub)) {
    if (u->size() != v->size()) {
      throw OperatorError(std::string("cannot apply '") + ast::spelling(op) + "' to vectors of lengths " +
                          std::to_string(u->size()) + " and " + std::to_string(v->size()));
    }
    std::vector<double> out(u->size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = arithmetic(op, (*u)[i], (*v)[i]);
    return to_list(out);
  }
  if (u && y && (op == Op::Mul || op == Op::Div)) {
    std::vector<double> out(u->size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = arithmetic(op, (*u)[i], *y);
    return to_list(out);
  }
  if (x && v && op == Op::Mul) {
    std::vector<double> out(v->size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = arithmetic(op, *x, (*v)[i]);
    return to_list(out);
  }
  if ((a.list() && !u) || (b.list() && !v)) {
    throw OperatorError(std::string("cannot apply '") + ast::spelling(op) +
                        "' to a list that holds something other than numbers");
  }
  unsupported(op, a, b);
}

Value apply_binary(Op op, Value&& a, const Value& b) {
  if (op != Op::Eq && op != Op::Ne) {
    if (Object* o = a.sole_object()) {
      if (auto r = o->binary_sole(op, b)) return std::move(*r);
      unsupported(op, a, b);
    }
  }
  return apply_binary(op, std::as_const(a), b);
}

Value apply_prefix(Op op, const Value& a) {
  if (op == Op::Not) {
    if (const bool* b = a.get<bool>()) return !*b;
    throw OperatorError("'not' needs true or false, got " + type_name(a));
  }
  if (const double* x = a.get<double>()) return op == Op::Neg ? -*x : *x;
  if (auto u = numbers(a)) {
    if (op == Op::Neg) {
      for (double& d : *u) d = -d;
    }
    return to_list(*u);
  }
  throw OperatorError(std::string("cannot apply prefix '") + ast::spelling(op) + "' to " + type_name(a));
}

}  // namespace sculpt::language
