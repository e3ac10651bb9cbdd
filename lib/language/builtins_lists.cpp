// Built-ins over lists (core area): reverse, map, filter, sum, zip, enumerate. map and filter take
// any function value, a user `fn` or a built-in, and call it through the interpreter.
#include <algorithm>

#include "language/builtins.hpp"
#include "language/operators.hpp"

namespace sculpt::language {

void register_lists(BuiltinTable& table) {
  table.add({.name = "reverse",
             .doc = "A new list: the items of xs in reverse order.",
             .params = {arg("xs").list()},
             .run = [](const Arguments& args) -> Value {
               List items = args.list("xs");
               args.charge(items.size());
               std::reverse(items.begin(), items.end());
               return items;
             }});
  table.add({.name = "map",
             .doc = "A new list: f(x) for each item x of xs. f is any function of one argument: a fn or a "
                    "built-in (map(sqrt, [1, 4]) is [1, 2]).",
             .params = {arg("f").function(), arg("xs").list()},
             .run = [](const Arguments& args) -> Value {
               const Value& f = args.function("f");
               const List& items = args.list("xs");
               List out;
               out.reserve(items.size());
               for (const Value& x : items) out.push_back(args.call(f, {x}));
               return out;
             }});
  table.add({.name = "filter",
             .doc = "A new list: the items x of xs for which f(x) is true (f must give true or false).",
             .params = {arg("f").function(), arg("xs").list()},
             .run = [](const Arguments& args) -> Value {
               const Value& f = args.function("f");
               const List& items = args.list("xs");
               List out;
               for (std::size_t i = 0; i < items.size(); ++i) {
                 const Value keep = args.call(f, {items[i]});
                 const bool* b = keep.get<bool>();
                 if (!b) {
                   args.fail("f", "f must give true or false, got " + type_name(keep) + " for item " +
                                      std::to_string(i) + " (" + to_repr(items[i]) + ")");
                 }
                 if (*b) out.push_back(items[i]);
               }
               return out;
             }});
  table.add({.name = "sum",
             .doc = "The items of xs added with + from the first: numbers, vectors of one length (item by "
                    "item) or strings (joined). sum([]) is 0.",
             .params = {arg("xs").list()},
             .run = [](const Arguments& args) -> Value {
               const List& items = args.list("xs");
               if (items.empty()) return 0.0;
               args.charge(items.size());
               Value total = items[0];
               for (std::size_t i = 1; i < items.size(); ++i) {
                 try {
                   total = apply_binary(ast::Op::Add, std::move(total), items[i]);
                 } catch (const OperatorError& e) {
                   args.fail("xs", std::string(e.what()) + " (item " + std::to_string(i) + ")");
                 }
               }
               return total;
             }});
  table.add({.name = "zip",
             .doc = "A new list of pairs [x, y] of the items of xs and ys at the same index, as long as the "
                    "shorter list.",
             .params = {arg("xs").list(), arg("ys").list()},
             .run = [](const Arguments& args) -> Value {
               const List& xs = args.list("xs");
               const List& ys = args.list("ys");
               const std::size_t n = std::min(xs.size(), ys.size());
               args.charge(n);
               List out;
               out.reserve(n);
               for (std::size_t i = 0; i < n; ++i) out.emplace_back(List{xs[i], ys[i]});
               return out;
             }});
  table.add({.name = "enumerate",
             .doc = "A new list of pairs [i, x]: each item x of xs with its index i, from 0.",
             .params = {arg("xs").list()},
             .run = [](const Arguments& args) -> Value {
               const List& xs = args.list("xs");
               args.charge(xs.size());
               List out;
               out.reserve(xs.size());
               for (std::size_t i = 0; i < xs.size(); ++i) out.emplace_back(List{static_cast<double>(i), xs[i]});
               return out;
             }});
}

}  // namespace sculpt::language
