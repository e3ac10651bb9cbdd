// Built-ins of the language itself: output, conversion, lists, arithmetic and vectors, time. The
// math functions of one or two numbers come from their table (math_functions.hpp).
#include <chrono>
#include <cmath>
#include <ostream>

#include "base/errors.hpp"
#include "language/builtins.hpp"
#include "language/math_functions.hpp"
#include "language/record.hpp"

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
             .doc = "x as text, the way print shows it.",
             .params = {arg("x")},
             .run = [](const Arguments& args) -> Value { return to_display(args.value("x")); }});
  table.add({.name = "type",
             .doc = "The type of x as a string: \"number\", \"string\", \"bool\", \"list\", \"function\", "
                    "\"none\", or a library type such as \"solid\" or \"curve\".",
             .params = {arg("x")},
             .run = [](const Arguments& args) -> Value { return type_name(args.value("x")); }});
  table.add({.name = "len",
             .doc = "Number of items of a list or bytes of a string.",
             .params = {arg("x").any("a list or a string")},
             .run = [](const Arguments& args) -> Value {
               if (auto s = args.value("x").get<std::string>()) return static_cast<double>(s->size());
               return static_cast<double>(args.list("x").size());
             }});
  table.add({.name = "keys",
             .doc = "The names of a record's fields, in order (read a field with r[\"name\"]).",
             .params = {arg("r").of<Record>("a record")},
             .run = [](const Arguments& args) -> Value {
               List names;
               for (const auto& [name, _] : args.object<Record>("r").fields()) names.emplace_back(name);
               return names;
             }});
  table.add({.name = "range",
             .doc = "The list a, a+step, ... up to b excluded (down to b when step < 0). "
                    "At most 10^7 items.",
             .params = {arg("a").number(), arg("b").number(), arg("step").number().defaults(1.0)},
             .run = [](const Arguments& args) -> Value {
               const double a = args.number("a");
               const double b = args.number("b");
               const double step = args.number("step");
               if (step == 0) args.fail("step", "step must not be 0");
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
             .doc = "A new list: the items of xs followed by x.",
             .params = {arg("xs").list(), arg("x")},
             .run = [](const Arguments& args) -> Value {
               args.charge(args.list("xs").size());
               List items = args.list("xs");
               items.push_back(args.value("x"));
               return items;
             }});
  table.add({.name = "concat",
             .doc = "A new list: the items of xs followed by the items of ys.",
             .params = {arg("xs").list(), arg("ys").list()},
             .run = [](const Arguments& args) -> Value {
               args.charge(args.list("xs").size() + args.list("ys").size());
               List items = args.list("xs");
               const List& more = args.list("ys");
               items.insert(items.end(), more.begin(), more.end());
               return items;
             }});
  table.add({.name = "min",
             .doc = "The smallest of its numbers (or of the numbers of one list).",
             .variadic = true,
             .run = [](const Arguments& args) { return extreme(args, false); }});
  table.add({.name = "max",
             .doc = "The largest of its numbers (or of the numbers of one list).",
             .variadic = true,
             .run = [](const Arguments& args) { return extreme(args, true); }});
  for (const MathFunction& f : math_functions()) {
    std::vector<Param> params{arg(f.params[0]).number()};
    if (f.arity == 2) params.push_back(arg(f.params[1]).number());
    table.add({.name = f.name, .doc = f.doc, .params = std::move(params), .run = [&f](const Arguments& args) -> Value {
                 const double a = args.number(f.params[0]);
                 const double b = f.arity == 2 ? args.number(f.params[1]) : 0.0;
                 std::string error;
                 const double v = evaluate(f, a, b, error);
                 if (error.empty()) return v;
                 if (f.arity == 1) args.fail(f.params[0], error);
                 args.fail(error);
               }});
  }
  table.add({.name = "pow",
             .doc = "x to the power y (a finite result or an error).",
             .params = {arg("x").number(), arg("y").number()},
             .run = [](const Arguments& args) -> Value {
               const double r = std::pow(args.number("x"), args.number("y"));
               if (!std::isfinite(r)) args.fail("result is not a finite number");
               return r;
             }});
  table.add({.name = "pi", .doc = "The constant 3.141592653589793.", .constant = Value(3.14159265358979323846)});
  table.add({.name = "dot",
             .doc = "Dot product of two 3-vectors.",
             .params = {arg("u").vector(3), arg("v").vector(3)},
             .run = [](const Arguments& args) -> Value {
               const auto u = args.vector("u");
               const auto v = args.vector("v");
               return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
             }});
  table.add({.name = "cross",
             .doc = "Cross product of two 3-vectors.",
             .params = {arg("u").vector(3), arg("v").vector(3)},
             .run = [](const Arguments& args) -> Value {
               const auto u = args.vector("u");
               const auto v = args.vector("v");
               return List{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
             }});
  table.add({.name = "norm",
             .doc = "Euclidean length of a 3-vector.",
             .params = {arg("v").vector(3)},
             .run = [](const Arguments& args) -> Value {
               const auto v = args.vector("v");
               return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
             }});
  table.add({.name = "clock",
             .doc = "Seconds from a monotonic clock (only differences mean something), for timing inside scripts.",
             .run = [](const Arguments&) -> Value {
               using namespace std::chrono;
               return duration<double>(steady_clock::now().time_since_epoch()).count();
             }});
  table.add({.name = "assert",
             .doc = "Stops the script with an error at the call when condition is false.",
             .params = {arg("condition").boolean(), arg("message").string().defaults("assertion failed")},
             .run = [](const Arguments& args) -> Value {
               if (!args.boolean("condition")) args.fail(args.string("message"));
               return {};
             }});
}

}  // namespace sculpt::language
