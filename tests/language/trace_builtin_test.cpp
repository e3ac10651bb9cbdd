// trace and trace_info from scripts (Ihm & Naylor 1990, sec. 5.1 and Appendix B): the curves
// come back as digitized curves whose points satisfy both published equations (residuals
// computed here, independently of the tracer); Fig. 7 gives its two closed loops; singular
// points are reported; bad input is an error at the argument, never a crash or a hang.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <sstream>

#include "language/curve_values.hpp"
#include "language/interpreter.hpp"
#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::first_error_line;
using testing::run_script;
using testing::text_source;
using Vec = Eigen::Vector3d;

struct Surface {
  std::function<double(const Vec&)> f;
  std::function<Vec(const Vec&)> grad;
};

/// |f| / |grad f| at p: the distance to the surface to first order.
double residual(const Surface& s, const Vec& p) { return std::fabs(s.f(p)) / s.grad(p).norm(); }

const Surface kEllipsoid{[](const Vec& p) { return 36 * p.x() * p.x() + 81 * p.y() * p.y() + 9 * p.z() * p.z() - 324; },
                         [](const Vec& p) { return Vec(72 * p.x(), 162 * p.y(), 18 * p.z()); }};
const Surface kCylinderinder{[](const Vec& p) { return p.x() * p.x() + p.y() * p.y() - 3.94; },
                        [](const Vec& p) { return Vec(2 * p.x(), 2 * p.y(), 0); }};

const char* const kFig7 = R"(
fn ellipsoid(x, y, z) { 36 * pow(x, 2) + 81 * pow(y, 2) + 9 * pow(z, 2) - 324 }
fn cyl(p) { p[0] * p[0] + p[1] * p[1] - 3.94 }
)";

/// Runs `script` and returns the curves in the global list `name`.
std::vector<curves::DigitizedCurve> traced(const std::string& script, const std::string& name, std::string* out = nullptr) {
  std::ostringstream text;
  Interpreter interpreter({.out = &text, .err = &text});  // prints and the summary, in order
  interpreter.run(text_source(script));
  if (out) *out = text.str();
  std::vector<curves::DigitizedCurve> result;
  const Value* v = interpreter.global(name);
  EXPECT_NE(v, nullptr);
  for (const Value& item : *v->list()) result.push_back(item.object<CurveValue>()->curve);
  return result;
}

TEST(TraceBuiltin, Fig7QuarticGivesItsTwoClosedLoops) {
  for (const char* tol : {"1e-2", "1e-3", "1e-4"}) {
    std::string out;
    const auto curves = traced(std::string(kFig7) + "cs = trace(ellipsoid, cyl, box=[[-2.5, -2.5, -5], [2.5, "
                                                    "2.5, 5]], tol=" + tol + ")",
                               "cs", &out);
    ASSERT_EQ(curves.size(), 2u) << tol;
    EXPECT_EQ(out.rfind("trace: 2 curves (2 closed), ", 0), 0u) << out;
    double z_sign[2] = {0, 0};
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_TRUE(curves[k].closed);
      EXPECT_EQ(curves[k].dimension, 3);
      EXPECT_GT(curves[k].points.size(), 20u);
      for (const Vec& p : curves[k].points) {
        EXPECT_LE(residual(kEllipsoid, p), 1e-11) << tol;
        EXPECT_LE(residual(kCylinderinder, p), 1e-11) << tol;
        z_sign[k] = p.z();
      }
    }
    // One loop above the xy plane, one below (the ellipsoid's caps cut by the cyl).
    EXPECT_LT(z_sign[0] * z_sign[1], 0.0);
  }
}

TEST(TraceBuiltin, LinearizeTakesTheTracedCurves) {
  const auto r = run_script(std::string(kFig7) + R"(
cs = trace(ellipsoid, cyl, box=[[-2.5, -2.5, -5], [2.5, 2.5, 5]], tol=1e-3, quiet=true)
for c in cs { l = linearize(c, tol=0.05); print(type(c), len(indices(l)) - 1, error(l) <= 0.05) }
)");
  EXPECT_EQ(r.error, "");
  std::istringstream lines(r.out);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) {
    EXPECT_EQ(line.rfind("curve ", 0), 0u) << line;
    EXPECT_NE(line.find(" true"), std::string::npos) << line;
  }
  EXPECT_EQ(count, 2);
}

TEST(TraceBuiltin, VivianiAndTheSexticPassTheirSingularPoints) {
  const auto r = run_script(R"(
fn ball(x, y, z) { x * x + y * y + z * z - 4 }
fn cyl(x, y, z) { pow(x - 1, 2) + y * y - 1 }
v = trace_info(ball, cyl, box=[[-0.5, -1.5, -2.5], [2.5, 1.5, 2.5]], tol=1e-3)
print(len(v[0]), v[0][0], len(v[1]), v[1][0][1], v[1][0][2], v[3])
s = v[1][0][0]
print(abs(s[0] - 2) < 1e-6, abs(s[1]) < 1e-6, abs(s[2]) < 1e-6)
fn f8(x, y, z) { y * y - x * x - pow(x, 3) }
fn g8(x, y, z) { z - x * x + x - 2 }
w = trace_info(f8, g8, box=[[-1.3, -1.5, 1], [0.7, 1.5, 5]], tol=1e-3)
t = w[1][0][0]
print(len(w[0]), len(w[1]), w[1][0][1], abs(t[0]) < 1e-6, abs(t[1]) < 1e-6, abs(t[2] - 2) < 1e-6)
)");
  EXPECT_EQ(r.error, "");
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line.substr(0, 2), "1 ") << line;
  EXPECT_NE(line.find("closed>"), std::string::npos) << line;
  EXPECT_NE(line.find(" 1 2 true false"), std::string::npos) << line;  // one crossing, passed twice, resolved
  std::getline(lines, line);
  EXPECT_EQ(line, "true true true");
  std::getline(lines, line);
  EXPECT_EQ(line, "1 1 2 true true true");
}

TEST(TraceBuiltin, TracedPointsSatisfyVivianisEquations) {
  const auto curves = traced(R"(
fn ball(p) { dot(p, p) - 4 }
fn cyl(x, y, z) { pow(x - 1, 2) + y * y - 1 }
cs = trace(ball, cyl, box=[[-0.5, -1.5, -2.5], [2.5, 1.5, 2.5]], tol=1e-4, quiet=true)
)", "cs");
  ASSERT_EQ(curves.size(), 1u);
  const Surface sphere{[](const Vec& p) { return p.squaredNorm() - 4; }, [](const Vec& p) { return Vec(2 * p); }};
  const Surface cyl{[](const Vec& p) { return (p.x() - 1) * (p.x() - 1) + p.y() * p.y() - 1; },
                    [](const Vec& p) { return Vec(2 * (p.x() - 1), 2 * p.y(), 0); }};
  for (const Vec& p : curves[0].points) {
    if ((p - Vec(2, 0, 0)).norm() < 1e-3) continue;  // both gradients are parallel at the crossing
    EXPECT_LE(residual(sphere, p), 1e-11);
    EXPECT_LE(residual(cyl, p), 1e-11);
  }
}

TEST(TraceBuiltin, ABoxWithoutTheCurveGivesAnEmptyList) {
  const auto r = run_script(std::string(kFig7) + "print(trace(ellipsoid, cyl, box=[[-1, -1, -1], [1, 1, 1]]))");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.err, "trace: 0 curves, 0 points, 0 singular points, 0 steps\n");  // the summary on standard error
  EXPECT_EQ(r.out, "[]\n");
}

TEST(TraceBuiltin, DegeneratePairsGiveDocumentedResults) {
  // g = f, g = 2f, g = 0: the tangent grad f x grad g vanishes everywhere, no curve. A sphere
  // and its tangent plane touch in one point: no curve, one singular point passed 0 times.
  const auto r = run_script(R"(
fn f(x, y, z) { x * x + y * y + z * z - 1 }
fn twice(x, y, z) { 2 * f(x, y, z) }
fn zero(x, y, z) { 0 }
fn top(x, y, z) { z - 1 }
b = [[-2, -2, -2], [2, 2, 2]]
print(len(trace(f, f, box=b, quiet=true)), len(trace(f, twice, box=b, quiet=true)), len(trace(f, zero, box=b, quiet=true)))
i = trace_info(f, top, box=b)
print(len(i[0]), len(i[1]), i[1][0][1], norm(i[1][0][0] - [0, 0, 1]) < 1e-3)
)");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "0 0 0\n0 1 0 true\n");
}

TEST(TraceBuiltin, StepBudgetRunsOutWithAWarning) {
  const auto r = run_script(std::string(kFig7) + R"(
cs = trace(ellipsoid, cyl, box=[[-2.5, -2.5, -5], [2.5, 2.5, 5]], tol=1e-4, steps=50)
i = trace_info(ellipsoid, cyl, box=[[-2.5, -2.5, -5], [2.5, 2.5, 5]], tol=1e-4, steps=50)
print(i[2] <= 51, i[3])
)");
  EXPECT_EQ(r.error, "");
  EXPECT_NE(r.err.find("trace: warning: the step budget of 50 ran out; the curves may be incomplete"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("true true\n"), std::string::npos) << r.out;
}

TEST(TraceBuiltin, BadInputIsAnErrorAtTheArgument) {
  const std::string fns = std::string(kFig7) + "fn two(x, y) { x }\nfn root(x, y, z) { sqrt(x) + z - 0.5 }\nfn flat(x, y, z) { y }\n";  // lines 1-6
  const auto call = [&](const std::string& args) { return first_error_line(fns + "trace(" + args + ")"); };
  EXPECT_EQ(call("ellipsoid, cyl, box=[[1, 0, 0], [1, 1, 1]]"),
            "t.bsp:7:23: error: trace: the box is empty: its first corner must be below its second in x, y and z "
            "(x: 1 >= 1)");
  EXPECT_EQ(call("ellipsoid, cyl"),
            "t.bsp:7:1: error: trace: give box=[[xmin, ymin, zmin], [xmax, ymax, zmax]], the region to trace in");
  EXPECT_EQ(call("ellipsoid, cyl, box=[0, 1]"),
            "t.bsp:7:23: error: trace: box must be [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
  EXPECT_EQ(call("ellipsoid, cyl, box=[[0, 0, 0], [1, 1, 1]], tol=1e-12"),
            "t.bsp:7:51: error: trace: tol=1e-12 is below the floor of 1e-9 times the box diagonal "
            "(1.7320508075688772e-09 here)");
  EXPECT_EQ(call("ellipsoid, cyl, box=[[0, 0, 0], [1, 1, 1]], tol=-1"),
            "t.bsp:7:51: error: trace: argument 'tol' must be a finite number > 0, got -1");
  EXPECT_EQ(call("ellipsoid, cyl, box=[[0, 0, 0], [1, 1, 1]], tol=5"),
            "t.bsp:7:51: error: trace: tol=5 is larger than the box diagonal");
  EXPECT_EQ(call("ellipsoid, cyl, box=[[0, 0, 0], [1, 1, 1]], steps=0"),
            "t.bsp:7:51: error: trace: argument 'steps' must be a whole number from 1 to 10000000, got 0");
  EXPECT_EQ(call("ellipsoid, 3, box=[[0, 0, 0], [1, 1, 1]]"),
            "t.bsp:7:18: error: trace: argument 'g' must be a function fn f(x, y, z) or fn f(p), got number");
  EXPECT_EQ(call("two, cyl, box=[[0, 0, 0], [1, 1, 1]]"),
            "t.bsp:4:1: error: 'two' takes 2 parameters; an implicit function takes three numbers (x, y, z) or one "
            "point p");
  EXPECT_EQ(call("sin, cyl, box=[[0, 0, 0], [1, 1, 1]]"),
            "t.bsp:7:7: error: trace: argument 'f' must be a function fn f(x, y, z) or fn f(p), got function");
  // The curve z = 0.5 - sqrt(x), y = 0 ends at x = 0, where sqrt has no gradient; the tracer
  // steps past it into x < 0.
  const std::string root = call("root, flat, box=[[-1, -1, -1], [1, 1, 1]]");
  EXPECT_EQ(root.rfind("t.bsp:7:7: error: trace: 'root' (or its gradient) is not finite at (", 0), 0u) << root;
}

TEST(TraceBuiltin, CompileErrorsPointIntoTheFunctionWithANoteAtTheCall) {
  const auto r = run_script("fn f(x, y, z) {\n  if x > 0 { x } else { y }\n}\nfn g(x, y, z) { z }\n"
                            "trace(f, g, box=[[0, 0, 0], [1, 1, 1]])\n");
  EXPECT_EQ(r.error.substr(0, r.error.find('\n')),
            "t.bsp:2:3: error: 'if' cannot be compiled into an implicit function: no branches (min, max and abs "
            "often replace them)");
  EXPECT_NE(r.error.find("t.bsp:5:1: note: in compiling 'f' for this call"), std::string::npos) << r.error;
}

TEST(TraceBuiltin, StepsCountAgainstTheRunsStepLimit) {
  // Appended, not kFig7 + "...": GCC 12 warns falsely about the temporary's memcpy (-Warray-bounds).
  std::string script = kFig7;
  script += "trace(ellipsoid, cyl, box=[[-2.5, -2.5, -5], [2.5, 2.5, 5]], tol=1e-4, quiet=true)";
  const auto r = run_script(script, {.max_steps = 200});
  EXPECT_NE(r.error.find("step limit of 200 exceeded"), std::string::npos) << r.error;
}

}  // namespace
}  // namespace sculpt::language
