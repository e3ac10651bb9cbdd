// Built-ins of the language itself: output, conversion, lists, arithmetic and vectors, time. The
// math functions of one or two numbers come from their table (math_functions.hpp).
#include <chrono>
#include <cmath>
#include <ostream>

#include "base/errors.hpp"
#include "language/builtins.hpp"
#include "language/math_functions.hpp"

namespace sculpt::language {
namespace {

/// Lists made by range() have at most this many items.
constexpr double kMaxRangeItems = 1e7;

Value extreme(const Arguments& args, bool want_max) {
  std::vector<Value> items = args.rest();
  if (items.size() == 1 && items[0].list()) items = *items[0].list();
  if (items.empty()) args.fail("needs at least one number");
  double best = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const double* d = items[i].get<double>();
    if (!d) args.fail("needs numbers, got " + type_name(items[i]));
    if (i == 0 || (want_max ? *d > best : *d < best)) best = *d;
  }
  return best;
}

}  // namespace

void register_core(BuiltinTable& table) {
  table.add({.name = "print",
             .signature = "print(a, b, ...)",
             .doc = "Writes its arguments separated by spaces and a newline to standard output. "
                    "Numbers print with enough digits to read back exactly.",
             .variadic = true,
             .run = [](const Arguments& args) -> Value {
               std::ostream& out = args.out();
               for (std::size_t i = 0; i < args.rest().size(); ++i) out << (i ? " " : "") << to_display(args.rest()[i]);
               out << '\n';
               return {};
             }});
  table.add({.name = "str",
             .signature = "str(x)",
             .doc = "x as text, the way print shows it.",
             .params = {{"x"}},
             .run = [](const Arguments& args) -> Value { return to_display(args.value(0)); }});
  table.add({.name = "type",
             .signature = "type(x)",
             .doc = "The type of x as a string: \"number\", \"string\", \"bool\", \"list\", \"function\", "
                    "\"none\", or a library type such as \"solid\" or \"curve\".",
             .params = {{"x"}},
             .run = [](const Arguments& args) -> Value { return type_name(args.value(0)); }});
  table.add({.name = "len",
             .signature = "len(x)",
             .doc = "Number of items of a list or bytes of a string.",
             .params = {{"x"}},
             .run = [](const Arguments& args) -> Value {
               if (auto s = args.value(0).get<std::string>()) return static_cast<double>(s->size());
               return static_cast<double>(args.list(0).size());
             }});
  table.add({.name = "range",
             .signature = "range(a, b, step=1)",
             .doc = "The list a, a+step, ... up to b excluded (down to b when step < 0). "
                    "At most 10^7 items.",
             .params = {{"a"}, {"b"}, {"step", false}},
             .run = [](const Arguments& args) -> Value {
               const double a = args.number(0);
               const double b = args.number(1);
               const double step = args.has(2) ? args.number(2) : 1.0;
               if (step == 0) args.fail(2, "step must not be 0");
               const double count = std::max(0.0, std::ceil((b - a) / step));
               if (!(count <= kMaxRangeItems)) args.fail("more than 10^7 items");
               args.charge(static_cast<std::uint64_t>(count));
               List items;
               items.reserve(static_cast<std::size_t>(count));
               for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
                 items.emplace_back(a + static_cast<double>(i) * step);
               }
               return items;
             }});
  table.add({.name = "append",
             .signature = "append(xs, x)",
             .doc = "A new list: the items of xs followed by x.",
             .params = {{"xs"}, {"x"}},
             .run = [](const Arguments& args) -> Value {
               args.charge(args.list(0).size());
               List items = args.list(0);
               items.push_back(args.value(1));
               return items;
             }});
  table.add({.name = "concat",
             .signature = "concat(xs, ys)",
             .doc = "A new list: the items of xs followed by the items of ys.",
             .params = {{"xs"}, {"ys"}},
             .run = [](const Arguments& args) -> Value {
               args.charge(args.list(0).size() + args.list(1).size());
               List items = args.list(0);
               const List& more = args.list(1);
               items.insert(items.end(), more.begin(), more.end());
               return items;
             }});
  table.add({.name = "min",
             .signature = "min(a, b, ...)",
             .doc = "The smallest of its numbers (or of the numbers of one list).",
             .variadic = true,
             .run = [](const Arguments& args) { return extreme(args, false); }});
  table.add({.name = "max",
             .signature = "max(a, b, ...)",
             .doc = "The largest of its numbers (or of the numbers of one list).",
             .variadic = true,
             .run = [](const Arguments& args) { return extreme(args, true); }});
  for (const MathFunction& f : math_functions()) {
    std::vector<Param> params{{f.params[0]}};
    if (f.arity == 2) params.push_back({f.params[1]});
    table.add({.name = f.name,
               .signature = f.signature,
               .doc = f.doc,
               .params = std::move(params),
               .run = [&f](const Arguments& args) -> Value {
                 const double a = args.number(0);
                 const double b = f.arity == 2 ? args.number(1) : 0.0;
                 std::string error;
                 const double v = evaluate(f, a, b, error);
                 if (error.empty()) return v;
                 if (f.arity == 1) args.fail(0, error);
                 args.fail(error);
               }});
  }
  table.add({.name = "pow", .signature = "pow(x, y)", .doc = "x to the power y (a finite result or an error).",
             .params = {{"x"}, {"y"}},
             .run = [](const Arguments& args) -> Value {
               const double r = std::pow(args.number(0), args.number(1));
               if (!std::isfinite(r)) args.fail("result is not a finite number");
               return r;
             }});
  table.add({.name = "pi", .signature = "pi", .doc = "The constant 3.141592653589793.",
             .constant = Value(3.14159265358979323846)});
  table.add({.name = "dot", .signature = "dot(u, v)", .doc = "Dot product of two 3-vectors.",
             .params = {{"u"}, {"v"}},
             .run = [](const Arguments& args) -> Value {
               const auto u = args.vector(0, 3);
               const auto v = args.vector(1, 3);
               return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
             }});
  table.add({.name = "cross", .signature = "cross(u, v)", .doc = "Cross product of two 3-vectors.",
             .params = {{"u"}, {"v"}},
             .run = [](const Arguments& args) -> Value {
               const auto u = args.vector(0, 3);
               const auto v = args.vector(1, 3);
               return List{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
             }});
  table.add({.name = "norm", .signature = "norm(v)", .doc = "Euclidean length of a 3-vector.",
             .params = {{"v"}},
             .run = [](const Arguments& args) -> Value {
               const auto v = args.vector(0, 3);
               return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
             }});
  table.add({.name = "clock", .signature = "clock()",
             .doc = "Seconds from a monotonic clock (only differences mean something), for timing inside scripts.",
             .run = [](const Arguments&) -> Value {
               using namespace std::chrono;
               return duration<double>(steady_clock::now().time_since_epoch()).count();
             }});
  table.add({.name = "assert", .signature = "assert(condition, message=\"assertion failed\")",
             .doc = "Stops the script with an error at the call when condition is false.",
             .params = {{"condition"}, {"message", false}},
             .run = [](const Arguments& args) -> Value {
               if (!args.boolean(0)) args.fail(args.has(1) ? args.string(1) : std::string("assertion failed"));
               return {};
             }});
}

}  // namespace sculpt::language
