// The math functions of the language, declared once (math_functions.hpp).
#include "language/math_functions.hpp"

#include <cmath>

#include "language/value.hpp"

namespace sculpt::language {
namespace {

using F = CompiledForm;

std::string anywhere(double, double) { return {}; }

std::string in_unit_interval(double a, double) {
  return a >= -1.0 && a <= 1.0 ? std::string() : "argument " + format_number(a) + " is outside [-1, 1]";
}

// Alphabetical; one entry per function.
const MathFunction kFunctions[] = {
    {.name = "abs",
     .signature = "abs(x)",
     .doc = "Absolute value.",
     .value = [](double a, double) { return std::fabs(a); },
     .domain = anywhere,
     .form = F::Abs},
    {.name = "acos",
     .signature = "acos(x)",
     .doc = "Arc cosine of x in [-1, 1]: an angle in radians in [0, pi].",
     .value = [](double a, double) { return std::acos(a); },
     .domain = in_unit_interval,
     .form = F::Acos},
    {.name = "asin",
     .signature = "asin(x)",
     .doc = "Arc sine of x in [-1, 1]: an angle in radians in [-pi/2, pi/2].",
     .value = [](double a, double) { return std::asin(a); },
     .domain = in_unit_interval,
     .form = F::Asin},
    {.name = "atan",
     .signature = "atan(x)",
     .doc = "Arc tangent of x: an angle in radians in [-pi/2, pi/2].",
     .value = [](double a, double) { return std::atan(a); },
     .domain = anywhere,
     .form = F::Atan},
    {.name = "atan2",
     .signature = "atan2(y, x)",
     .doc = "Angle of the point (x, y) in radians, in [-pi, pi].",
     .arity = 2,
     .params = {"y", "x"},
     .value = [](double a, double b) { return std::atan2(a, b); },
     .domain = anywhere,
     .form = F::Atan2},
    {.name = "ceil",
     .signature = "ceil(x)",
     .doc = "Smallest whole number >= x.",
     .value = [](double a, double) { return std::ceil(a); },
     .domain = anywhere},
    {.name = "cos",
     .signature = "cos(x)",
     .doc = "Cosine of x radians.",
     .value = [](double a, double) { return std::cos(a); },
     .domain = anywhere,
     .form = F::Cos},
    {.name = "exp",
     .signature = "exp(x)",
     .doc = "e to the power x (a finite result or an error).",
     .value = [](double a, double) { return std::exp(a); },
     .domain = anywhere,
     .form = F::Exp},
    {.name = "exp2",
     .signature = "exp2(x)",
     .doc = "2 to the power x (a finite result or an error).",
     .value = [](double a, double) { return std::exp2(a); },
     .domain = anywhere,
     .form = F::Exp2},
    {.name = "floor",
     .signature = "floor(x)",
     .doc = "Largest whole number <= x.",
     .value = [](double a, double) { return std::floor(a); },
     .domain = anywhere},
    {.name = "hypot",
     .signature = "hypot(x, y)",
     .doc = "sqrt(x^2 + y^2), without overflow or underflow in between (compiled: sqrt(x*x + y*y)).",
     .arity = 2,
     .params = {"x", "y"},
     .value = [](double a, double b) { return std::hypot(a, b); },
     .domain = anywhere,
     .form = F::Hypot},
    {.name = "log",
     .signature = "log(x)",
     .doc = "Natural logarithm of x > 0.",
     .value = [](double a, double) { return std::log(a); },
     .domain =
         [](double a, double) {
           return a > 0.0 ? std::string() : "logarithm of " + format_number(a) + ", which is not > 0";
         },
     .form = F::Log},
    {.name = "round",
     .signature = "round(x)",
     .doc = "Nearest whole number (halves away from 0).",
     .value = [](double a, double) { return std::round(a); },
     .domain = anywhere},
    {.name = "sign",
     .signature = "sign(x)",
     .doc = "The sign of x: -1, 0 or 1.",
     .value = [](double a, double) { return a > 0.0   ? 1.0
                                            : a < 0.0 ? -1.0
                                                      : 0.0; },
     .domain = anywhere,
     .form = F::Sign},
    {.name = "sin",
     .signature = "sin(x)",
     .doc = "Sine of x radians.",
     .value = [](double a, double) { return std::sin(a); },
     .domain = anywhere,
     .form = F::Sin},
    {.name = "sqrt",
     .signature = "sqrt(x)",
     .doc = "Square root of x >= 0.",
     .value = [](double a, double) { return std::sqrt(a); },
     .domain = [](double a,
                  double) { return a >= 0.0 ? std::string() : std::string("square root of a negative number"); },
     .form = F::Sqrt},
    {.name = "tan",
     .signature = "tan(x)",
     .doc = "Tangent of x radians.",
     .value = [](double a, double) { return std::tan(a); },
     .domain = anywhere,
     .form = F::Tan},
};

}  // namespace

std::span<const MathFunction> math_functions() { return kFunctions; }

const MathFunction* find_math_function(std::string_view name) {
  for (const MathFunction& f : kFunctions)
    if (name == f.name) return &f;
  return nullptr;
}

double evaluate(const MathFunction& f, double a, double b, std::string& error) {
  error = f.domain(a, b);
  if (!error.empty()) return 0.0;
  const double v = f.value(a, b);
  if (!std::isfinite(v)) error = "result is not a finite number";
  return v;
}

}  // namespace sculpt::language
