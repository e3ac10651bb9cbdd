// The compiler of script functions into implicit expressions (language/implicit_compiler.hpp),
// checked against independent references: the interpreter's own evaluation of the same `fn`
// at random points (values), derivatives worked out by hand (gradients), sampled values
// (interval bounds); and every construct outside the compiled subset, with its exact position.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "language/implicit_compiler.hpp"
#include "language/interpreter.hpp"
#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::text_source;
using Vec = Eigen::Vector3d;

/// An interpreter that has run `script`, and compiles its functions the way trace does.
class Compiled {
 public:
  explicit Compiled(const std::string& script) : interpreter_({.out = &out_}) {
    interpreter_.run(text_source(script));
  }
  implicit::Expression compile(const std::string& name) const {
    const Value* v = interpreter_.global(name);
    EXPECT_NE(v, nullptr) << name;
    const auto& f = *v->get<std::shared_ptr<const UserFunction>>();
    ImplicitCompileOptions options;
    options.global = [this](const std::string& n) { return interpreter_.global(n); };
    return compile_implicit(*f, options);
  }
  /// The interpreter's value of name(x, y, z), or of name([x, y, z]) when point is true.
  double interpret(const std::string& name, const Vec& p, bool point) {
    const std::string args = format_number(p.x()) + ", " + format_number(p.y()) + ", " + format_number(p.z());
    const auto v = interpreter_.run(text_source(name + (point ? "([" + args + "])" : "(" + args + ")")));
    return *v->get<double>();
  }

 private:
  std::ostringstream out_;
  Interpreter interpreter_;
};

/// The first line of the error that compiling `name` in `script` raises ("" if none).
std::string compile_error(const std::string& script, const std::string& name = "f") {
  try {
    Compiled c(script);
    (void)c.compile(name);
  } catch (const ScriptError& e) {
    const std::string text = format_error(e);
    return text.substr(0, text.find('\n'));
  }
  return "";
}

const char* const kFunctions = R"(
R = 1.5
r = 0.4
center = [0.25, -0.5, 1]
fn quart(x, y, z) { 36 * pow(x, 2) + 81 * pow(y, 2) + 9 * pow(z, 2) - 324 }
fn locals(x, y, z) {
  a = x * y - z / 3
  b = a * a + 1
  return sqrt(b) - abs(a) + min(x, y, z) - max(x, -y)
}
fn trig(x, y, z) { sin(x) * cos(y) + exp(z / 4) - tan(x / 3) + pi }
fn helper(u, v) { pow(u - v, -2) + u / (1 + v * v) }
fn calls(x, y, z) { helper(x, 3) + helper(v = y, u = z) * R }
fn torus(p) {
  q = sqrt(p[0] * p[0] + p[1] * p[1]) - R
  q * q + p[-1] * p[2] - r * r
}
fn vectors(p) {
  d = p - center
  c = cross(d, [0, 0, 1])
  dot(d, d) + norm(c) - 2 * d[1] + max(p) - min(d * 2)
}
fn constants(x, y, z) { k = pow(R, 3) / 2; k * x + sqrt(R) * 0 + y }
fn inverse(x, y, z) { acos(x / 3) + asin(y / 3) * atan(z) + atan2(y, x) + log(1 + x * x) + exp2(z / 2) + sign(y) * hypot(x, z) }
)";

TEST(ImplicitCompiler, ValuesAgreeWithTheInterpreter) {
  Compiled c(kFunctions);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (const char* name : {"quart", "locals", "trig", "calls", "torus", "vectors", "constants", "inverse"}) {
    const bool point = std::string(name) == "torus" || std::string(name) == "vectors";
    const implicit::Expression e = c.compile(name);
    for (int k = 0; k < 200; ++k) {
      const Vec p(u(rng), u(rng), u(rng));
      const double want = c.interpret(name, p, point);
      EXPECT_NEAR(e.value(p), want, 1e-13 * std::max(1.0, std::fabs(want))) << name << " at " << p.transpose();
    }
  }
}

TEST(ImplicitCompiler, ConstantPartsAreFolded) {
  Compiled c(kFunctions);
  // constants: k = R^3 / 2 folds to one number, sqrt(R) * 0 to 0, + 0 drops; what is left is
  // k x + y: x, y, k, *, +.
  const implicit::Expression e = c.compile("constants");
  EXPECT_EQ(e.size(), 5u) << e.str();
  EXPECT_EQ(e.value(Vec(2, 1, 0)), std::pow(1.5, 3) / 2 * 2 + 1);
}

TEST(ImplicitCompiler, GradientsMatchAnalyticDerivatives) {
  Compiled c(kFunctions + std::string(R"(
fn g(x, y, z) { x * x * y + sin(z) * exp(x) - 1 / (1 + y * y) }
)"));
  const implicit::Expression g = c.compile("g");
  const implicit::Expression torus = c.compile("torus");
  const implicit::Expression quartic = c.compile("quart");
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int k = 0; k < 200; ++k) {
    const Vec p(u(rng), u(rng), u(rng));
    const double x = p.x(), y = p.y(), z = p.z();
    const Vec dg(2 * x * y + std::sin(z) * std::exp(x), x * x + 2 * y / std::pow(1 + y * y, 2),
                 std::cos(z) * std::exp(x));
    EXPECT_LE((g.value_gradient(p).gradient - dg).norm(), 1e-12 * std::max(1.0, dg.norm()));
    const double rho = std::hypot(x, y);
    const double q = rho - 1.5;
    const Vec dt(2 * q * x / rho, 2 * q * y / rho, 2 * z);
    EXPECT_LE((torus.value_gradient(p).gradient - dt).norm(), 1e-12 * std::max(1.0, dt.norm()));
    const Vec dq(72 * x, 162 * y, 18 * z);
    EXPECT_LE((quartic.value_gradient(p).gradient - dq).norm(), 1e-12 * dq.norm());
  }
}

TEST(ImplicitCompiler, IntervalBoundsContainSampledValues) {
  Compiled c(kFunctions);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0), w(0.01, 1.0), t(0.0, 1.0);
  for (const char* name : {"quart", "locals", "trig", "torus", "vectors", "inverse"}) {
    const implicit::Expression e = c.compile(name);
    for (int b = 0; b < 40; ++b) {
      const Vec lo(u(rng), u(rng), u(rng));
      const implicit::Box box{.lo = lo, .hi = lo + Vec(w(rng), w(rng), w(rng))};
      const implicit::IntervalBounds bounds = e.bounds(box);
      for (int k = 0; k < 50; ++k) {
        const Vec p = box.lo + (box.hi - box.lo).cwiseProduct(Vec(t(rng), t(rng), t(rng)));
        double v = 0;
        try {
          v = e.value(p);
        } catch (const implicit::NonFiniteValue&) {
          continue;  // torus on the z axis: sqrt(0) has no gradient, but value is fine; others finite
        }
        EXPECT_TRUE(bounds.range.contains(v)) << name << " " << v << " not in [" << bounds.range.lo << ", "
                                              << bounds.range.hi << "]";
      }
    }
  }
}

// The inverse functions, log, exp2, sign and hypot (math_functions.hpp), differentiated by hand.
TEST(ImplicitCompiler, InverseFunctionGradientsMatchAnalyticDerivatives) {
  Compiled c(kFunctions);
  const implicit::Expression e = c.compile("inverse");
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int k = 0; k < 200; ++k) {
    const Vec p(u(rng), u(rng), u(rng));
    const double x = p.x(), y = p.y(), z = p.z();
    const double s = y > 0 ? 1.0 : -1.0, h = std::hypot(x, z), r2 = x * x + y * y;
    const Vec want(-1 / (3 * std::sqrt(1 - x * x / 9)) - y / r2 + 2 * x / (1 + x * x) + s * x / h,
                   std::atan(z) / (3 * std::sqrt(1 - y * y / 9)) + x / r2,
                   std::asin(y / 3) / (1 + z * z) + std::pow(2.0, z / 2) * std::log(2.0) / 2 + s * z / h);
    EXPECT_LE((e.value_gradient(p).gradient - want).norm(), 1e-12 * std::max(1.0, want.norm())) << p.transpose();
  }
}

// Interval bounds at the edges: a box partly outside the domain of acos or log proves nothing
// (domain_error), atan2 is bounded by [-pi, pi] across its branch cut and by its corners elsewhere.
TEST(ImplicitCompiler, InverseFunctionBoundsAtDomainEdgesAndTheBranchCut) {
  Compiled c("fn a(x, y, z) { acos(x) }\nfn t(x, y, z) { atan2(y, x) }\nfn l(x, y, z) { log(x) + sign(y) }");
  const double pi = std::numbers::pi;
  const implicit::Expression a = c.compile("a");
  implicit::IntervalBounds b = a.bounds({.lo = Vec(-0.5, 0, 0), .hi = Vec(0.5, 1, 1)});
  EXPECT_FALSE(b.domain_error);
  EXPECT_TRUE(b.range.contains(2 * pi / 3) && b.range.contains(pi / 3));
  EXPECT_NEAR(b.range.hi, 2 * pi / 3, 1e-12);
  EXPECT_TRUE(a.bounds({.lo = Vec(0.5, 0, 0), .hi = Vec(2, 1, 1)}).domain_error);
  const implicit::Expression t = c.compile("t");
  b = t.bounds({.lo = Vec(-2, -0.1, 0), .hi = Vec(-1, 0.1, 1)});  // across the negative x axis
  EXPECT_TRUE(b.range.contains(std::atan2(-0.1, -1.0)) && b.range.contains(std::atan2(0.1, -1.0)));
  b = t.bounds({.lo = Vec(1, 1, 0), .hi = Vec(2, 2, 1)});
  EXPECT_NEAR(b.range.lo, std::atan2(1.0, 2.0), 1e-12);
  EXPECT_NEAR(b.range.hi, std::atan2(2.0, 1.0), 1e-12);
  EXPECT_TRUE(b.range.contains(pi / 4));
  const implicit::Expression l = c.compile("l");
  EXPECT_TRUE(l.bounds({.lo = Vec(-1, 0, 0), .hi = Vec(1, 1, 1)}).domain_error);
  b = l.bounds({.lo = Vec(1, 1, 0), .hi = Vec(std::exp(1.0), 2, 1)});  // log in [0, 1], sign(y) = 1
  EXPECT_FALSE(b.domain_error);
  EXPECT_NEAR(b.range.lo, 1.0, 1e-12);
  EXPECT_NEAR(b.range.hi, 2.0, 1e-12);
}

TEST(ImplicitCompiler, GlobalsAreReadWhenCompiled) {
  Compiled c("k = 2\nfn f(x, y, z) { k * x }\nk = 3");
  EXPECT_EQ(c.compile("f").value(Vec(1, 0, 0)), 3.0);
}

TEST(ImplicitCompiler, ZeroAndFirstPowersAndWholeConstants) {
  Compiled c("fn f(x, y, z) { pow(x, 0) + pow(y, 1) + pow(2, 3) }\nfn g(x, y, z) { 5 }");
  EXPECT_EQ(c.compile("f").value(Vec(7, 2, 0)), 11.0);
  EXPECT_EQ(c.compile("g").value(Vec(7, 2, 0)), 5.0);
}

// Every construct outside the subset: the error names it and points at it (file:line:col).
TEST(ImplicitCompiler, UnsupportedConstructsAreErrorsAtTheirPosition) {
  const std::string f = "fn f(x, y, z) {\n  ";
  const auto error = [&](const std::string& body) { return compile_error(f + body + "\n}\n"); };
  EXPECT_EQ(error("if x > 0 { x } else { y }"),
            "t.bsp:2:3: error: 'if' cannot be compiled into an implicit function: no branches (min, max and abs "
            "often replace them)");
  EXPECT_EQ(error("for i in [1, 2] { x }\n  x"),
            "t.bsp:2:3: error: 'for' cannot be compiled into an implicit function: no loops");
  EXPECT_EQ(error("x + (y < 1)"),
            "t.bsp:2:10: error: comparison '<' cannot be compiled into an implicit function: no branches (min, "
            "max and abs often replace them)");
  EXPECT_EQ(error("x and y"), "t.bsp:2:5: error: 'and' cannot be compiled into an implicit function: no logic or branches");
  EXPECT_EQ(error("not x"), "t.bsp:2:7: error: 'not' cannot be compiled into an implicit function: no logic or branches");
  EXPECT_EQ(error("x + true"), "t.bsp:2:7: error: 'true' cannot be compiled into an implicit function: no logic or branches");
  EXPECT_EQ(error("s = \"a\"\n  x"), "t.bsp:2:7: error: a string cannot be compiled into an implicit function");
  EXPECT_EQ(error("x % 2"), "t.bsp:2:5: error: '%' cannot be compiled into an implicit function");
  EXPECT_EQ(error("x | y"), "t.bsp:2:5: error: '|' cannot be compiled into an implicit function: it combines solids");
  EXPECT_EQ(error("floor(x)"),
            "t.bsp:2:3: error: built-in 'floor' cannot be compiled into an implicit function: it folds constant "
            "arguments only; the compiled built-ins are abs, acos, asin, atan, atan2, cos, exp, exp2, hypot, log, "
            "sign, sin, sqrt, tan, min, max, pow, dot, norm, cross");
  EXPECT_EQ(error("x + floor(2.5)"), "");  // constant arguments fold as in the interpreter
  EXPECT_EQ(error("x + acos(2)"), "t.bsp:2:7: error: acos: argument 2 is outside [-1, 1]");
  EXPECT_EQ(error("x + log(0)"), "t.bsp:2:7: error: log: logarithm of 0, which is not > 0");
  EXPECT_EQ(error("pow(x, y)"),
            "t.bsp:2:10: error: pow: the exponent of a compiled implicit function must be a constant whole "
            "number (write sqrt for 1/2)");
  EXPECT_EQ(error("pow(x, 0.5)"),
            "t.bsp:2:10: error: pow: the exponent of a compiled implicit function must be a whole number from "
            "-1024 to 1024, got 0.5");
  EXPECT_EQ(error("[x, y][0] + [x, y][y]"),
            "t.bsp:2:22: error: an index in a compiled implicit function must be a constant whole number");
  EXPECT_EQ(error("[x, y][2]"), "t.bsp:2:10: error: index 2 is out of range for a list of 2 items");
  EXPECT_EQ(error("[[x], y]\n  x"),
            "t.bsp:2:4: error: a list holding a list of 1 numbers cannot be compiled into an implicit function: "
            "only vectors of numbers");
  EXPECT_EQ(error("include \"x.bsp\"\n  x"), "t.bsp:2:3: error: 'include' cannot be compiled into an implicit function");
  EXPECT_EQ(error("fn h(a) { a }\n  x"), "t.bsp:2:3: error: a nested 'fn' cannot be compiled into an implicit function");
  EXPECT_EQ(error("q + x"), "t.bsp:2:3: error: unknown name 'q'");
  EXPECT_EQ(error("x / 0"), "t.bsp:2:5: error: division by zero");
  EXPECT_EQ(error("sqrt(-1) + x"), "t.bsp:2:3: error: sqrt: square root of a negative number");
  EXPECT_EQ(error("y = 1"),
            "t.bsp:1:1: error: 'f' gives no value cannot be compiled into an implicit function: end its body with an "
            "expression or 'return e'");
  EXPECT_EQ(error("[x, y, z]"),
            "t.bsp:1:1: error: 'f' gives a list of 3 numbers; an implicit function must give a number");
  EXPECT_EQ(error("return"), "t.bsp:2:3: error: 'return' without a value cannot be compiled into an implicit function");
  EXPECT_EQ(error("sin(x, y)"), "t.bsp:2:3: error: sin(x) takes 1 argument, got 2");
  EXPECT_EQ(error("sqrt(x = 1)"),
            "t.bsp:2:8: error: sqrt: named arguments cannot be compiled into an implicit function in calls of built-ins");
  EXPECT_EQ(error("x(1)"), "t.bsp:2:3: error: 'x' is a number, not a function");
  EXPECT_EQ(error("[x, y] + [z]"), "t.bsp:2:10: error: cannot apply '+' to vectors of lengths 2 and 1");
  EXPECT_EQ(error("sin + x"), "t.bsp:2:7: error: cannot apply '+' to the built-in 'sin' and a number");
  EXPECT_EQ(error("sin = 1\n  x"), "t.bsp:2:3: error: cannot assign to 'sin': it is a built-in");
}

TEST(ImplicitCompiler, GlobalsOfOtherTypesAreNamed) {
  EXPECT_EQ(compile_error("s = box([0, 0, 0], [1, 1, 1])\nfn f(x, y, z) { x + s }"),
            "t.bsp:2:21: error: 's' (a solid) cannot be compiled into an implicit function: an implicit function "
            "can use only numbers, vectors of numbers and functions");
  EXPECT_EQ(compile_error("s = \"text\"\nfn f(x, y, z) { x + s }"),
            "t.bsp:2:21: error: 's' (a string) cannot be compiled into an implicit function: an implicit function "
            "can use only numbers, vectors of numbers and functions");
  EXPECT_EQ(compile_error("s = [1, \"a\"]\nfn f(x, y, z) { x + s[0] }"),
            "t.bsp:2:21: error: 's' (a list of string) cannot be compiled into an implicit function: only lists of "
            "numbers can be used");
}

TEST(ImplicitCompiler, RecursionIsAnErrorWithTheCallChain) {
  const std::string script = "fn f(x, y, z) { g(x) + y }\nfn g(a) { h(a) }\nfn h(a) { g(a * 2) }\n";
  try {
    Compiled c(script);
    (void)c.compile("f");
    FAIL() << "no error";
  } catch (const ScriptError& e) {
    const std::string text = format_error(e);
    EXPECT_EQ(text.substr(0, text.find('\n')),
              "t.bsp:3:11: error: recursive call of 'g' cannot be compiled into an implicit function: inlining it "
              "would never end");
    EXPECT_NE(text.find("t.bsp:2:11: note: in call to 'h'"), std::string::npos) << text;
    EXPECT_NE(text.find("t.bsp:1:17: note: in call to 'g'"), std::string::npos) << text;
  }
  EXPECT_EQ(compile_error("fn f(x, y, z) { f(x, y, z) }"),
            "t.bsp:1:17: error: recursive call of 'f' cannot be compiled into an implicit function: inlining it "
            "would never end");
}

TEST(ImplicitCompiler, ParameterCountsAndCallBinding) {
  EXPECT_EQ(compile_error("fn f(x, y) { x }"),
            "t.bsp:1:1: error: 'f' takes 2 parameters; an implicit function takes three numbers (x, y, z) or one "
            "point p");
  EXPECT_EQ(compile_error("fn h(a, b) { a }\nfn f(x, y, z) { h(x) }"), "t.bsp:2:17: error: h: missing argument 'b'");
  EXPECT_EQ(compile_error("fn h(a) { a }\nfn f(x, y, z) { h(x, y) }"),
            "t.bsp:2:22: error: h takes at most 1 argument, got 2");
  EXPECT_EQ(compile_error("fn h(a) { a }\nfn f(x, y, z) { h(b = x) }"), "t.bsp:2:19: error: h has no parameter 'b'");
  EXPECT_EQ(compile_error("fn f(p) { p[3] }"), "t.bsp:1:13: error: index 3 is out of range for a list of 3 items");
}

TEST(ImplicitCompiler, SizeAndDepthLimitsAreErrors) {
  // Each level doubles the expression: 100 * 2^30 nodes would be built without the limit.
  std::string script = "fn f0(x) { x";
  for (int i = 0; i < 100; ++i) script += " * x";
  script += " }\n";
  for (int i = 1; i <= 30; ++i) {
    script += "fn f" + std::to_string(i) + "(x) { f" + std::to_string(i - 1) + "(x) + f" + std::to_string(i - 1) +
              "(x) }\n";
  }
  script += "fn f(x, y, z) { f30(x) }\n";
  EXPECT_NE(compile_error(script).find("error: implicit function too large: more than 100000 operations"),
            std::string::npos);
  // The same chain on a constant makes no node, but the work doubles all the same.
  std::string constants = script;
  constants.replace(constants.find("fn f(x, y, z) { f30(x) }"), 24, "fn f(x, y, z) { f30(2) + x }");
  EXPECT_NE(compile_error(constants).find("error: implicit function too large: compiling it takes more than 250000 "
                                          "steps"),
            std::string::npos)
      << compile_error(constants);
  std::string chain = "fn c0(x) { x }\n";
  for (int i = 1; i <= 100; ++i) {
    chain += "fn c" + std::to_string(i) + "(x) { c" + std::to_string(i - 1) + "(x) }\n";
  }
  chain += "fn f(x, y, z) { c100(x) }\n";
  EXPECT_NE(compile_error(chain).find("error: calls nested more than 64 deep cannot be compiled"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::language
