// Built-ins over lists (core area): reverse, map, filter, sum, zip, enumerate. map and filter take
// any function value, a user `fn` or a built-in, and call it through the interpreter.
#include <algorithm>

#include "language/builtins.hpp"
#include "language/operators.hpp"

namespace sculpt::language {

void register_lists(BuiltinTable& table) {
  table.add({.name = "reverse",
             .signature = "reverse(xs)",
             .doc = "A new list: the items of xs in reverse order.",
             .params = {{"xs"}},
             .run = [](const Arguments& args) -> Value {
               List items = args.list(0);
               args.charge(items.size());
               std::reverse(items.begin(), items.end());
               return items;
             }});
  table.add({.name = "map",
             .signature = "map(f, xs)",
             .doc = "A new list: f(x) for each item x of xs. f is any function of one argument: a fn or a "
                    "built-in (map(sqrt, [1, 4]) is [1, 2]).",
             .params = {{"f"}, {"xs"}},
             .run = [](const Arguments& args) -> Value {
               const Value& f = args.function(0);
               const List& items = args.list(1);
               List out;
               out.reserve(items.size());
               for (const Value& x : items) out.push_back(args.call(f, {x}));
               return out;
             }});
  table.add({.name = "filter",
             .signature = "filter(f, xs)",
             .doc = "A new list: the items x of xs for which f(x) is true (f must give true or false).",
             .params = {{"f"}, {"xs"}},
             .run = [](const Arguments& args) -> Value {
               const Value& f = args.function(0);
               const List& items = args.list(1);
               List out;
               for (std::size_t i = 0; i < items.size(); ++i) {
                 const Value keep = args.call(f, {items[i]});
                 const bool* b = keep.get<bool>();
                 if (!b) {
                   args.fail(0, "f must give true or false, got " + type_name(keep) + " for item " + std::to_string(i) +
                                    " (" + to_repr(items[i]) + ")");
                 }
                 if (*b) out.push_back(items[i]);
               }
               return out;
             }});
  table.add({.name = "sum",
             .signature = "sum(xs)",
             .doc = "The items of xs added with + from the first: numbers, vectors of one length (item by "
                    "item) or strings (joined). sum([]) is 0.",
             .params = {{"xs"}},
             .run = [](const Arguments& args) -> Value {
               const List& items = args.list(0);
               if (items.empty()) return 0.0;
               args.charge(items.size());
               Value total = items[0];
               for (std::size_t i = 1; i < items.size(); ++i) {
                 try {
                   total = apply_binary(ast::Op::Add, std::move(total), items[i]);
                 } catch (const OperatorError& e) {
                   args.fail(0, std::string(e.what()) + " (item " + std::to_string(i) + ")");
                 }
               }
               return total;
             }});
  table.add({.name = "zip",
             .signature = "zip(xs, ys)",
             .doc = "A new list of pairs [x, y] of the items of xs and ys at the same index, as long as the "
                    "shorter list.",
             .params = {{"xs"}, {"ys"}},
             .run = [](const Arguments& args) -> Value {
               const List& xs = args.list(0);
               const List& ys = args.list(1);
               const std::size_t n = std::min(xs.size(), ys.size());
               args.charge(n);
               List out;
               out.reserve(n);
               for (std::size_t i = 0; i < n; ++i) out.emplace_back(List{xs[i], ys[i]});
               return out;
             }});
  table.add({.name = "enumerate",
             .signature = "enumerate(xs)",
             .doc = "A new list of pairs [i, x]: each item x of xs with its index i, from 0.",
             .params = {{"xs"}},
             .run = [](const Arguments& args) -> Value {
               const List& xs = args.list(0);
               args.charge(xs.size());
               List out;
               out.reserve(xs.size());
               for (std::size_t i = 0; i < xs.size(); ++i) out.emplace_back(List{static_cast<double>(i), xs[i]});
               return out;
             }});
}

}  // namespace sculpt::language
