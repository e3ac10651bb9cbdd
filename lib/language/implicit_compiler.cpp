// Compiling script functions into implicit::Expression (Ihm & Naylor 1990, sec. 5: the tracer
// evaluates f, grad f and interval bounds at thousands of points; the interpreter would walk the
// syntax tree at each). One pass over the body: names are bound as the interpreter would bind
// them (locals, then globals, then built-ins), calls of user functions are inlined, and parts
// whose operands are constants are folded with the interpreter's own arithmetic.
#include "language/implicit_compiler.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "language/builtins.hpp"
#include "language/math_functions.hpp"
#include "language/operators.hpp"

namespace sculpt::language {
namespace {

using implicit::ExpressionBuilder;
using implicit::Term;

const char* const kNotCompiled = " cannot be compiled into an implicit function";
/// The built-ins compiled besides the math functions that have a compiled form (math_functions.hpp).
const char* const kOtherCompiledBuiltins = "min, max, pow, dot, norm, cross";

/// "abs, acos, ...": the compiled built-ins, for messages.
std::string compiled_builtins() {
  std::string names;
  for (const MathFunction& f : math_functions())
    if (f.form != CompiledForm::None) names += std::string(f.name) + ", ";
  return names + kOtherCompiledBuiltins;
}
/// Largest |n| of pow(a, n) (repeated squaring: about 2 log2 n nodes' worth of work).
constexpr double kMaxExponent = 1024;

/// A number during compilation: a constant, or a node of the expression being built.
struct Scalar {
  bool is_constant = true;
  double constant = 0.0;
  Term term{};
};

/// What a name or an expression stands for during compilation.
struct Compiled {
  enum class Kind { Scalar, Vector, UserFn, BuiltinFn };
  Kind kind = Kind::Scalar;
  std::vector<Scalar> items;  ///< Scalar: one item; Vector: its items
  std::shared_ptr<const UserFunction> user{};
  const Builtin* builtin = nullptr;

  static Compiled scalar(Scalar s) { return {Kind::Scalar, {s}, nullptr, nullptr}; }
  static Compiled vector(std::vector<Scalar> v) { return {Kind::Vector, std::move(v), nullptr, nullptr}; }
};

Scalar constant(double c) { return {true, c, {}}; }
Scalar node(Term t) { return {false, 0.0, t}; }

std::string describe(const Compiled& c) {
  switch (c.kind) {
    case Compiled::Kind::Scalar: return "a number";
    case Compiled::Kind::Vector: return "a list of " + std::to_string(c.items.size()) + " numbers";
    case Compiled::Kind::UserFn: return "the function '" + c.user->name + "'";
    case Compiled::Kind::BuiltinFn: return "the built-in '" + c.builtin->name + "'";
  }
  return "a value";
}

/// The bindings of one inlined call (the top-level function is the first).
struct InlineFrame {
  const UserFunction* function = nullptr;
  std::map<std::string, Compiled> locals;
};

class Compiler {
 public:
  explicit Compiler(const ImplicitCompileOptions& options) : options_(options) {}

  implicit::Expression run(const UserFunction& f) {
    char marker = 0;
    stack_base_ = reinterpret_cast<std::uintptr_t>(&marker);
    source_ = f.where.source;
    std::vector<Compiled> arguments;
    const Scalar x = counted(builder_.x(), f.where.offset);
    const Scalar y = counted(builder_.y(), f.where.offset);
    const Scalar z = counted(builder_.z(), f.where.offset);
    if (f.parameters.size() == 3) {
      arguments = {Compiled::scalar(x), Compiled::scalar(y), Compiled::scalar(z)};
    } else if (f.parameters.size() == 1) {
      arguments = {Compiled::vector({x, y, z})};
    } else {
      fail(f.where.offset, "'" + f.name + "' takes " + std::to_string(f.parameters.size()) + " parameter" +
                               (f.parameters.size() == 1 ? "" : "s") +
                               "; an implicit function takes three numbers (x, y, z) or one point p");
    }
    const Compiled result = inline_body(f, std::move(arguments));
    if (result.kind != Compiled::Kind::Scalar) {
      fail(f.where.offset, "'" + f.name + "' gives " + describe(result) + "; an implicit function must give a number");
    }
    return builder_.finish(term(result.items[0], f.where.offset));
  }

 private:
  const ImplicitCompileOptions& options_;
  ExpressionBuilder builder_;
  std::size_t nodes_ = 0;
  std::size_t work_ = 0;
  SourcePtr source_;             ///< the script of the function being compiled (inlined calls swap it)
  std::vector<InlineFrame*> frames_;  ///< innermost inlined call last
  std::uintptr_t stack_base_ = 0;

  // ---- errors and guards ----
  [[noreturn]] void fail(std::size_t where, const std::string& message) const {
    throw ScriptError(SourceRef{source_, where}, message);
  }
  [[noreturn]] void not_compiled(std::size_t where, const std::string& what, const std::string& why = "") const {
    fail(where, what + kNotCompiled + (why.empty() ? "" : ": " + why));
  }
  void check_stack(std::size_t where) const {
    char marker = 0;
    const auto here = reinterpret_cast<std::uintptr_t>(&marker);
    if (stack_base_ > here && stack_base_ - here > options_.stack_budget) {
      fail(where, "implicit function nested too deeply to compile");
    }
  }
  void count_work(std::size_t where) {
    if (++work_ > options_.max_work) {
      fail(where, "implicit function too large: compiling it takes more than " + std::to_string(options_.max_work) +
                      " steps after inlining its calls");
    }
  }
  Scalar counted(Term t, std::size_t where) {
    if (++nodes_ > options_.max_nodes) {
      fail(where, "implicit function too large: more than " + std::to_string(options_.max_nodes) +
                      " operations after inlining its calls");
    }
    return node(t);
  }
  Term term(const Scalar& s, std::size_t where) {
    return s.is_constant ? counted(builder_.constant(s.constant), where).term : s.term;
  }

  // ---- numbers ----
  /// a op b for + - * / on numbers: folded by the interpreter's arithmetic when both are constants.
  Scalar arithmetic(ast::Op op, const Scalar& a, const Scalar& b, std::size_t where) {
    if (a.is_constant && b.is_constant) {
      try {
        return constant(*apply_binary(op, Value(a.constant), Value(b.constant)).get<double>());
      } catch (const OperatorError& e) {
        fail(where, e.what());
      }
    }
    // Identities that hold exactly in floating point: x + 0, 0 + x, x - 0, x * 1, 1 * x, x / 1.
    const auto is = [](const Scalar& s, double c) { return s.is_constant && s.constant == c; };
    if ((op == ast::Op::Add || op == ast::Op::Sub) && is(b, 0.0)) return a;
    if (op == ast::Op::Add && is(a, 0.0)) return b;
    if ((op == ast::Op::Mul || op == ast::Op::Div) && is(b, 1.0)) return a;
    if (op == ast::Op::Mul && is(a, 1.0)) return b;
    const Term x = term(a, where), y = term(b, where);
    switch (op) {
      case ast::Op::Add: return counted(builder_.add(x, y), where);
      case ast::Op::Sub: return counted(builder_.sub(x, y), where);
      case ast::Op::Mul: return counted(builder_.mul(x, y), where);
      case ast::Op::Div:
        if (b.is_constant && b.constant == 0) fail(where, "division by zero");
        return counted(builder_.div(x, y), where);
      default: break;
    }
    not_compiled(where, std::string("'") + ast::spelling(op) + "'");
  }

  Scalar negate(const Scalar& a, std::size_t where) {
    return a.is_constant ? constant(-a.constant) : counted(builder_.neg(a.term), where);
  }

  Scalar finite(double v, std::size_t where, const std::string& what) const {
    if (!std::isfinite(v)) fail(where, what + ": result is not a finite number");
    return constant(v);
  }

  /// f(a, b) for a math function: folded by the table's own evaluation when the arguments are
  /// constants (as the interpreter computes it), else its compiled form.
  Scalar math(const MathFunction& f, const Scalar& a, const Scalar& b, std::size_t where) {
    if (a.is_constant && (f.arity == 1 || b.is_constant)) {
      std::string error;
      const double v = evaluate(f, a.constant, b.constant, error);
      if (!error.empty()) fail(where, std::string(f.name) + ": " + error);
      return constant(v);
    }
    if (f.form == CompiledForm::None) {
      not_compiled(where, "built-in '" + std::string(f.name) + "'",
                   "it folds constant arguments only; the compiled built-ins are " + compiled_builtins());
    }
    const Term x = term(a, where);
    const Term y = f.arity == 2 ? term(b, where) : Term{};
    ExpressionBuilder& e = builder_;
    const auto one = [&](Term t) { return counted(t, where); };
    switch (f.form) {
      case CompiledForm::Abs:
        return one(e.abs(x));
      case CompiledForm::Acos:
        return one(e.acos(x));
      case CompiledForm::Asin:
        return one(e.asin(x));
      case CompiledForm::Atan:
        return one(e.atan(x));
      case CompiledForm::Atan2:
        return one(e.atan2(x, y));
      case CompiledForm::Cos:
        return one(e.cos(x));
      case CompiledForm::Exp:
        return one(e.exp(x));
      // exp(ln 2 * x): within a few ulps of exp2, with an exact gradient.
      case CompiledForm::Exp2:
        return one(e.exp(one(e.mul(one(e.constant(std::numbers::ln2)).term, x)).term));
      // sqrt(x * x + y * y): may overflow where hypot does not.
      case CompiledForm::Hypot:
        return one(e.sqrt(one(e.add(one(e.mul(x, x)).term, one(e.mul(y, y)).term)).term));
      case CompiledForm::Log:
        return one(e.log(x));
      case CompiledForm::Sign:
        return one(e.sign(x));
      case CompiledForm::Sin:
        return one(e.sin(x));
      case CompiledForm::Sqrt:
        return one(e.sqrt(x));
      // sin / cos: an exact gradient, and interval bounds that widen to the line near a pole.
      case CompiledForm::Tan:
        return one(e.div(one(e.sin(x)).term, one(e.cos(x)).term));
      case CompiledForm::None:
        break;
    }
    not_compiled(where, "built-in '" + std::string(f.name) + "'");
  }

  Scalar extreme(bool want_max, const Scalar& a, const Scalar& b, std::size_t where) {
    if (a.is_constant && b.is_constant) {
      // As the interpreter's min/max: the first of equal values.
      return constant(want_max ? (b.constant > a.constant ? b.constant : a.constant)
                               : (b.constant < a.constant ? b.constant : a.constant));
    }
    const Term x = term(a, where), y = term(b, where);
    return counted(want_max ? builder_.max(x, y) : builder_.min(x, y), where);
  }

  Scalar power(const Scalar& base, const Scalar& exponent, std::size_t where, std::size_t exponent_where) {
    if (!exponent.is_constant) {
      fail(exponent_where, "pow: the exponent of a compiled implicit function must be a constant whole number "
                           "(write sqrt for 1/2)");
    }
    const double n = exponent.constant;
    if (base.is_constant) return finite(std::pow(base.constant, n), where, "pow");
    if (n != std::floor(n) || std::fabs(n) > kMaxExponent) {
      fail(exponent_where, "pow: the exponent of a compiled implicit function must be a whole number from -" +
                               format_number(kMaxExponent) + " to " + format_number(kMaxExponent) + ", got " +
                               format_number(n));
    }
    if (n == 0) return constant(1.0);
    if (n == 1) return base;
    return counted(builder_.pow(base.term, static_cast<int>(n)), where);
  }

  // ---- values ----
  const Scalar& as_scalar(const Compiled& c, std::size_t where, const std::string& context) const {
    if (c.kind != Compiled::Kind::Scalar) fail(where, context + " needs a number, got " + describe(c));
    return c.items[0];
  }
  const std::vector<Scalar>& as_vector(const Compiled& c, std::size_t where, const std::string& context,
                                       std::size_t size) const {
    if (c.kind != Compiled::Kind::Vector || c.items.size() != size) {
      fail(where, context + " needs a vector of " + std::to_string(size) + " numbers, got " + describe(c));
    }
    return c.items;
  }

  /// A global (or built-in) value as the compiler sees it.
  Compiled from_value(const Value& v, const std::string& name, std::size_t where) const {
    if (const double* d = v.get<double>()) return Compiled::scalar(constant(*d));
    if (const List* list = v.list()) {
      std::vector<Scalar> items;
      for (const Value& item : *list) {
        const double* d = item.get<double>();
        if (!d) not_compiled(where, "'" + name + "' (a list of " + type_name(item) + ")",
                             "only lists of numbers can be used");
        items.push_back(constant(*d));
      }
      return Compiled::vector(std::move(items));
    }
    if (const auto* f = v.get<std::shared_ptr<const UserFunction>>()) {
      Compiled c;
      c.kind = Compiled::Kind::UserFn;
      c.user = *f;
      return c;
    }
    if (const auto* b = v.get<const Builtin*>()) {
      Compiled c;
      c.kind = Compiled::Kind::BuiltinFn;
      c.builtin = *b;
      return c;
    }
    not_compiled(where, "'" + name + "' (a " + type_name(v) + ")",
                 "an implicit function can use only numbers, vectors of numbers and functions");
  }

  Compiled lookup(const ast::Identifier& id) const {
    if (!frames_.empty()) {
      auto it = frames_.back()->locals.find(id.name);
      if (it != frames_.back()->locals.end()) return it->second;
    }
    if (options_.global) {
      if (const Value* v = options_.global(id.name)) return from_value(*v, id.name, id.where);
    }
    if (const Builtin* b = builtins().find(id.name)) {
      if (b->constant) return from_value(*b->constant, id.name, id.where);
      Compiled c;
      c.kind = Compiled::Kind::BuiltinFn;
      c.builtin = b;
      return c;
    }
    fail(id.where, "unknown name '" + id.name + "'");
  }

  // ---- expressions ----
  Compiled compile(const ast::Expression& e) {
    check_stack(e.where);
    count_work(e.where);
    Compiled value = compile(e.first);
    for (const ast::Operation& operation : e.rest) {
      const ast::Op op = operation.op;
      if (op == ast::Op::Or || op == ast::Op::And) {
        not_compiled(operation.where, std::string("'") + ast::spelling(op) + "'", "no logic or branches");
      }
      if (op == ast::Op::Eq || op == ast::Op::Ne || op == ast::Op::Lt || op == ast::Op::Le || op == ast::Op::Gt ||
          op == ast::Op::Ge) {
        not_compiled(operation.where, std::string("comparison '") + ast::spelling(op) + "'",
                     "no branches (min, max and abs often replace them)");
      }
      if (op == ast::Op::Union || op == ast::Op::Intersect) {
        not_compiled(operation.where, std::string("'") + ast::spelling(op) + "'", "it combines solids");
      }
      if (op == ast::Op::Mod) not_compiled(operation.where, "'%'");
      const Compiled right = compile(operation.operand);
      value = binary(op, value, right, operation.where);
    }
    return value;
  }

  Compiled binary(ast::Op op, const Compiled& a, const Compiled& b, std::size_t where) {
    using K = Compiled::Kind;
    const auto cannot = [&] {
      fail(where, std::string("cannot apply '") + ast::spelling(op) + "' to " + describe(a) + " and " + describe(b));
    };
    if (a.kind == K::Scalar && b.kind == K::Scalar) return Compiled::scalar(arithmetic(op, a.items[0], b.items[0], where));
    if (a.kind == K::Vector && b.kind == K::Vector && (op == ast::Op::Add || op == ast::Op::Sub)) {
      if (a.items.size() != b.items.size()) {
        fail(where, std::string("cannot apply '") + ast::spelling(op) + "' to vectors of lengths " +
                        std::to_string(a.items.size()) + " and " + std::to_string(b.items.size()));
      }
      std::vector<Scalar> out;
      for (std::size_t i = 0; i < a.items.size(); ++i) out.push_back(arithmetic(op, a.items[i], b.items[i], where));
      return Compiled::vector(std::move(out));
    }
    if (a.kind == K::Vector && b.kind == K::Scalar && (op == ast::Op::Mul || op == ast::Op::Div)) {
      std::vector<Scalar> out;
      for (const Scalar& s : a.items) out.push_back(arithmetic(op, s, b.items[0], where));
      return Compiled::vector(std::move(out));
    }
    if (a.kind == K::Scalar && b.kind == K::Vector && op == ast::Op::Mul) {
      std::vector<Scalar> out;
      for (const Scalar& s : b.items) out.push_back(arithmetic(op, a.items[0], s, where));
      return Compiled::vector(std::move(out));
    }
    cannot();
    return {};
  }

  Compiled compile(const ast::Operand& operand) {
    struct Visitor {
      Compiler& self;
      Compiled operator()(const ast::Nil& n) const { self.fail(n.where, "an empty value" + std::string(kNotCompiled)); }
      Compiled operator()(const ast::NumberLiteral& n) const {
        if (!std::isfinite(n.value)) self.fail(n.where, "number too large for a double");
        return Compiled::scalar(constant(n.value));
      }
      Compiled operator()(const ast::StringLiteral& s) const { self.not_compiled(s.where, "a string"); }
      Compiled operator()(const ast::BoolLiteral& b) const {
        self.not_compiled(b.where, b.value ? "'true'" : "'false'", "no logic or branches");
      }
      Compiled operator()(const ast::Identifier& id) const { return self.lookup(id); }
      Compiled operator()(const ast::ListLiteral& l) const {
        std::vector<Scalar> items;
        for (const ast::Expression& item : l.items) {
          const Compiled c = self.compile(item);
          if (c.kind != Compiled::Kind::Scalar) {
            self.not_compiled(item.where, "a list holding " + describe(c), "only vectors of numbers");
          }
          items.push_back(c.items[0]);
        }
        return Compiled::vector(std::move(items));
      }
      Compiled operator()(const ast::Expression& e) const { return self.compile(e); }
      Compiled operator()(const ast::Prefixed& p) const {
        Compiled value = self.compile(p.operand);
        for (auto op = p.ops.rbegin(); op != p.ops.rend(); ++op) {
          if (*op == ast::Op::Not) self.not_compiled(p.where, "'not'", "no logic or branches");
          if (value.kind != Compiled::Kind::Scalar && value.kind != Compiled::Kind::Vector) {
            self.fail(p.where, std::string("cannot apply prefix '") + ast::spelling(*op) + "' to " + describe(value));
          }
          if (*op == ast::Op::Neg) {
            for (Scalar& s : value.items) s = self.negate(s, p.where);
          }
        }
        return value;
      }
      Compiled operator()(const ast::Postfix& p) const { return self.compile(p); }
    };
    return boost::apply_visitor(Visitor{*this}, operand);
  }

  Compiled compile(const ast::Postfix& p) {
    Compiled value = compile(p.primary);
    const ast::Identifier* callee_name = boost::get<ast::Identifier>(&p.primary);
    for (const ast::PostfixOp& op : p.ops) {
      if (const auto* call_args = boost::get<ast::CallArguments>(&op)) {
        value = call(value, *call_args, p.where, callee_name);
      } else {
        value = subscript(value, boost::get<ast::Subscript>(op));
      }
      callee_name = nullptr;
    }
    return value;
  }

  Compiled subscript(const Compiled& value, const ast::Subscript& s) {
    if (s.slice) not_compiled(s.where, "a slice", "index the items one by one");
    const Compiled index = compile(s.index);
    if (value.kind != Compiled::Kind::Vector) {
      fail(s.where, "cannot index " + describe(value) + ": only lists have items");
    }
    if (index.kind != Compiled::Kind::Scalar || !index.items[0].is_constant) {
      fail(s.index.where, "an index in a compiled implicit function must be a constant whole number");
    }
    const double d = index.items[0].constant;
    if (d != std::floor(d)) fail(s.index.where, "a list index must be a whole number, got " + format_number(d));
    const double n = static_cast<double>(value.items.size());
    const double i = d < 0 ? d + n : d;
    if (i < 0 || i >= n) {
      fail(s.index.where, "index " + format_number(d) + " is out of range for a list of " +
                              std::to_string(value.items.size()) + " items");
    }
    return Compiled::scalar(value.items[static_cast<std::size_t>(i)]);
  }

  // ---- calls ----
  Compiled call(const Compiled& callee, const ast::CallArguments& call_args, std::size_t where,
                const ast::Identifier* callee_name) {
    check_stack(where);
    if (callee.kind == Compiled::Kind::UserFn) return call_user(*callee.user, call_args, where);
    if (callee.kind == Compiled::Kind::BuiltinFn) return call_builtin(*callee.builtin, call_args, where);
    fail(where, (callee_name ? "'" + callee_name->name + "' is " : std::string()) + describe(callee) + ", not a function");
  }

  Compiled call_builtin(const Builtin& b, const ast::CallArguments& call_args, std::size_t where) {
    const std::string& name = b.name;
    const MathFunction* math_function = find_math_function(name);
    const bool known = math_function || name == "min" || name == "max" || name == "pow" || name == "dot" ||
                       name == "norm" || name == "cross";
    if (!known) not_compiled(where, "built-in '" + name + "'", "the compiled built-ins are " + compiled_builtins());
    std::vector<Compiled> args;
    std::vector<std::size_t> positions;
    for (const ast::Argument& a : call_args.arguments) {
      if (a.name) fail(a.where, name + ": named arguments" + kNotCompiled + " in calls of built-ins");
      args.push_back(compile(a.value));
      positions.push_back(a.where);
    }
    const auto expect = [&](std::size_t n) {
      if (args.size() != n) {
        fail(where, b.signature + " takes " + std::to_string(n) + " argument" + (n == 1 ? "" : "s") + ", got " +
                        std::to_string(args.size()));
      }
    };
    if (math_function) {
      const auto arity = static_cast<std::size_t>(math_function->arity);
      expect(arity);
      const Scalar first = as_scalar(args[0], positions[0], name);
      const Scalar second = arity == 2 ? as_scalar(args[1], positions[1], name) : constant(0.0);
      return Compiled::scalar(math(*math_function, first, second, where));
    }
    if (name == "pow") {
      expect(2);
      return Compiled::scalar(power(as_scalar(args[0], positions[0], "pow"), as_scalar(args[1], positions[1], "pow"),
                                    where, positions[1]));
    }
    if (name == "min" || name == "max") {
      std::vector<Scalar> items;
      if (args.size() == 1 && args[0].kind == Compiled::Kind::Vector) {
        items = args[0].items;
      } else {
        for (std::size_t i = 0; i < args.size(); ++i) items.push_back(as_scalar(args[i], positions[i], name));
      }
      if (items.empty()) fail(where, name + ": needs at least one number");
      Scalar best = items[0];
      for (std::size_t i = 1; i < items.size(); ++i) best = extreme(name == "max", best, items[i], where);
      return Compiled::scalar(best);
    }
    if (name == "norm") {
      expect(1);
      const auto& v = as_vector(args[0], positions[0], "norm", 3);
      return Compiled::scalar(math(*find_math_function("sqrt"), dot(v, v, where), constant(0.0), where));
    }
    expect(2);
    const auto& u = as_vector(args[0], positions[0], name, 3);
    const auto& v = as_vector(args[1], positions[1], name, 3);
    if (name == "dot") return Compiled::scalar(dot(u, v, where));
    const auto minor = [&](int i, int j) {
      return arithmetic(ast::Op::Sub, arithmetic(ast::Op::Mul, u[i], v[j], where),
                        arithmetic(ast::Op::Mul, u[j], v[i], where), where);
    };
    return Compiled::vector({minor(1, 2), minor(2, 0), minor(0, 1)});
  }

  Scalar dot(const std::vector<Scalar>& u, const std::vector<Scalar>& v, std::size_t where) {
    Scalar sum = arithmetic(ast::Op::Mul, u[0], v[0], where);
    for (std::size_t i = 1; i < u.size(); ++i) {
      sum = arithmetic(ast::Op::Add, sum, arithmetic(ast::Op::Mul, u[i], v[i], where), where);
    }
    return sum;
  }

  Compiled call_user(const UserFunction& f, const ast::CallArguments& call_args, std::size_t where) {
    for (const InlineFrame* frame : frames_) {
      if (frame->function == &f) {
        not_compiled(where, "recursive call of '" + f.name + "'", "inlining it would never end");
      }
    }
    if (static_cast<int>(frames_.size()) >= options_.max_call_depth) {
      fail(where, "calls nested more than " + std::to_string(options_.max_call_depth) + " deep" + kNotCompiled);
    }
    // Bind as the interpreter does: positional arguments in order, then by name.
    std::vector<std::optional<Compiled>> slot(f.parameters.size());
    std::size_t position = 0;
    for (const ast::Argument& a : call_args.arguments) {
      Compiled value = compile(a.value);
      if (!a.name) {
        if (position >= f.parameters.size()) {
          fail(a.where, f.name + " takes at most " + std::to_string(f.parameters.size()) + " argument" +
                            (f.parameters.size() == 1 ? "" : "s") + ", got " +
                            std::to_string(call_args.arguments.size()));
        }
        slot[position++] = std::move(value);
        continue;
      }
      std::size_t p = 0;
      while (p < f.parameters.size() && f.parameters[p] != a.name->name) ++p;
      if (p == f.parameters.size()) fail(a.where, f.name + " has no parameter '" + a.name->name + "'");
      if (slot[p]) fail(a.where, f.name + ": argument '" + a.name->name + "' given twice");
      slot[p] = std::move(value);
    }
    std::vector<Compiled> arguments;
    for (std::size_t p = 0; p < slot.size(); ++p) {
      if (!slot[p]) fail(where, f.name + ": missing argument '" + f.parameters[p] + "'");
      arguments.push_back(std::move(*slot[p]));
    }
    const SourceRef call_site{source_, where};
    try {
      return inline_body(f, std::move(arguments));
    } catch (ScriptError& e) {
      if (e.notes().size() < 8) e.add_note({call_site, "in call to '" + f.name + "'"});
      throw;
    }
  }

  // ---- statements ----
  /// The value of f's body with its parameters bound to `arguments`.
  Compiled inline_body(const UserFunction& f, std::vector<Compiled> arguments) {
    check_stack(f.where.offset);
    InlineFrame frame;
    frame.function = &f;
    for (std::size_t p = 0; p < arguments.size(); ++p) frame.locals[f.parameters[p]] = std::move(arguments[p]);
    struct Restore {
      Compiler& self;
      SourcePtr source;
      ~Restore() {
        self.frames_.pop_back();
        self.source_ = std::move(source);
      }
    };
    frames_.push_back(&frame);
    Restore restore{*this, source_};
    source_ = f.where.source;

    std::optional<Compiled> result;
    for (const ast::Statement& statement : f.body->statements) {
      result.reset();
      if (const auto* e = boost::get<ast::Expression>(&statement)) {
        result = compile(*e);
      } else if (const auto* a = boost::get<ast::Assignment>(&statement)) {
        if (builtins().find(a->target.name)) {
          fail(a->target.where, "cannot assign to '" + a->target.name + "': it is a built-in");
        }
        frame.locals[a->target.name] = compile(a->value);
      } else if (const auto* r = boost::get<ast::Return>(&statement)) {
        if (!r->value) fail(r->where, "'return' without a value" + std::string(kNotCompiled));
        return compile(*r->value);
      } else if (const auto* i = boost::get<ast::If>(&statement)) {
        not_compiled(i->where, "'if'", "no branches (min, max and abs often replace them)");
      } else if (const auto* l = boost::get<ast::For>(&statement)) {
        not_compiled(l->where, "'for'", "no loops");
      } else if (const auto* inc = boost::get<ast::Include>(&statement)) {
        not_compiled(inc->where, "'include'");
      } else if (const auto* d = boost::get<ast::FunctionDefinition>(&statement)) {
        not_compiled(d->where, "a nested 'fn'");
      }
    }
    if (!result) {
      fail(f.where.offset, "'" + f.name + "' gives no value" + kNotCompiled +
                               ": end its body with an expression or 'return e'");
    }
    if (result->kind == Compiled::Kind::UserFn || result->kind == Compiled::Kind::BuiltinFn) {
      fail(f.where.offset, "'" + f.name + "' gives " + describe(*result) + kNotCompiled);
    }
    return std::move(*result);
  }
};

}  // namespace

implicit::Expression compile_implicit(const UserFunction& f, const ImplicitCompileOptions& options) {
  if (f.body == nullptr) throw ScriptError(f.where, "'" + f.name + "' has no body");
  ImplicitCompileOptions bounded = options;
  // The interpreter that calls us may itself use its budget: keep well inside the real limit.
  rlimit limit{};
  if (getrlimit(RLIMIT_STACK, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    bounded.stack_budget = std::min<std::size_t>(bounded.stack_budget, limit.rlim_cur / 4);
  }
  return Compiler(bounded).run(f);
}

}  // namespace sculpt::language
