#include "language/interpreter.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "base/memory_limit.hpp"
#include "language/builtins.hpp"
#include "language/operators.hpp"
#include "language/parser.hpp"
#include "language/record.hpp"
#include "language/suggest.hpp"

namespace sculpt::language {

SourcePtr load_source(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path, "is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path, "cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  auto source = std::make_shared<SourceFile>();
  source->name = path;
  source->text = text.str();
  source->directory = std::filesystem::path(path).parent_path().string();
  return source;
}

namespace {

/// At most this many "in call to" notes per error (deep recursion would print thousands).
constexpr std::size_t kMaxNotes = 8;

/// The result of running a statement: its value (for the REPL echo and a function's implicit
/// result) and whether a `return` is unwinding.
struct Outcome {
  std::optional<Value> value;
  bool returned = false;
};

struct Frame {
  std::unordered_map<std::string, Value> locals;
};

/// Turns errors thrown by library code below the language into script errors at `at`.
/// The library's message without the prefix we add anyway ("box: box: ..." reads badly).
std::string without(const std::string& prefix, const char* message) {
  const std::string text(message);
  return !prefix.empty() && text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
}

/// The error of a statement stopped by a cancellation request: Ctrl-C, or the memory budget
/// (base/memory_limit.hpp), whose limit it names.
std::string stopped_message(const std::string& prefix) {
  if (cancel_reason() != CancelReason::MemoryLimit) return "interrupted";
  const std::optional<std::uint64_t> limit = watched_memory_limit();
  return prefix + "out of memory: the work needed more than the memory limit" +
         (limit ? " of " + format_memory_size(*limit) : std::string()) + " (sculpt --memory-limit)";
}

template <typename F>
auto positioned(const SourceRef& at, const std::string& prefix, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const ScriptError&) {
    throw;
  } catch (const Cancelled&) {  // Ctrl-C or the memory budget, in library code (base/cancel.hpp)
    throw ScriptError(at, stopped_message(prefix));
  } catch (const OperatorError& e) {
    throw ScriptError(at, prefix + e.what());
  } catch (const InvalidInput& e) {
    throw ScriptError(at, prefix + "invalid input: " + without(prefix, e.what()));
  } catch (const GeometryError& e) {
    throw ScriptError(at, prefix + "geometry error: " + without(prefix, e.what()));
  } catch (const RangeError& e) {
    throw ScriptError(at, prefix + "out of range: " + without(prefix, e.what()));
  } catch (const IoError& e) {
    throw ScriptError(at, prefix + e.what());
  } catch (const std::bad_alloc&) {
    throw ScriptError(at, prefix + "out of memory");
  } catch (const std::exception& e) {
    throw ScriptError(at, prefix + without(prefix, e.what()));
  }
}

}  // namespace

struct Interpreter::Impl {
  InterpreterOptions options;
  RunSettings settings;
  std::map<std::string, Value> globals;
  std::set<std::string> fixed;                       // globals bound by define_fixed: top-level assignments skip them
  std::map<std::string, std::uint64_t> assigned_at;  // global name -> serial of its last assignment
  std::uint64_t assignments = 0;                    // global assignments so far
  std::vector<Frame*> frames;  // innermost user-function call last; empty at top level
  SourcePtr source;            // the script whose syntax tree is being walked
  std::shared_ptr<const ast::Program> program;
  std::vector<std::string> includes;  // files being included, to refuse cycles
  std::uintptr_t stack_base = 0;
  std::uint64_t steps = 0;
  kernel::Grid grid;  // the grid new solids are made at (RunSettings::grid points here)
  std::vector<ShownPart> shown;  // what show() collected (RunSettings::shown points here)

  SourceRef at(std::size_t where) const { return {source, where}; }

  // ---- guards ----
  void check_stack(std::size_t where) const {
    char marker = 0;
    const auto here = reinterpret_cast<std::uintptr_t>(&marker);
    if (stack_base > here && stack_base - here > options.stack_budget) {
      throw ScriptError(at(where), "recursion too deep (more than " +
                                       std::to_string(options.stack_budget >> 10) + " KiB of stack)");
    }
  }
  void count_step(std::size_t where) { charge(1, where); }
  void charge(std::uint64_t n, std::size_t where) {
    if (options.interrupt && options.interrupt->load(std::memory_order_relaxed))
      throw ScriptError(at(where), stopped_message(""));
    if (options.max_steps != 0 && (steps += n) > options.max_steps) {
      throw ScriptError(at(where), "step limit of " + std::to_string(options.max_steps) + " exceeded");
    }
  }

  /// Swaps in another script (a user function's or an included file's) for a while.
  struct SourceSwap {
    Impl& impl;
    SourcePtr saved_source;
    std::shared_ptr<const ast::Program> saved_program;
    SourceSwap(Impl& i, SourcePtr s, std::shared_ptr<const ast::Program> p)
        : impl(i), saved_source(std::move(i.source)), saved_program(std::move(i.program)) {
      impl.source = std::move(s);
      impl.program = std::move(p);
    }
    ~SourceSwap() {
      impl.source = std::move(saved_source);
      impl.program = std::move(saved_program);
    }
    SourceSwap(const SourceSwap&) = delete;
    SourceSwap& operator=(const SourceSwap&) = delete;
  };

  // ---- names ----
  const Builtin* find_builtin(const std::string& name) const {
    const Builtin* b = builtins().find(name);
    return b && (!options.core_only || b->area == "core") ? b : nullptr;
  }

  std::vector<std::string> visible_names() const {
    std::vector<std::string> names;
    for (const auto& [name, _] : globals) names.push_back(name);
    if (!frames.empty()) {
      for (const auto& [name, _] : frames.back()->locals) names.push_back(name);
    }
    for (const auto& [name, b] : builtins().entries()) {
      if (find_builtin(name)) names.push_back(name);
    }
    return names;
  }

  Value lookup(const ast::Identifier& id) const {
    if (!frames.empty()) {
      auto it = frames.back()->locals.find(id.name);
      if (it != frames.back()->locals.end()) return it->second;
    }
    if (auto it = globals.find(id.name); it != globals.end()) return it->second;
    if (const Builtin* b = find_builtin(id.name)) return b->constant ? *b->constant : Value(b);
    std::string message = "unknown name '" + id.name + "'";
    if (auto guess = closest_name(id.name, visible_names())) message += "; did you mean '" + *guess + "'?";
    throw ScriptError(at(id.where), message);
  }

  // ---- handing a variable's value over (copy on write) ----
  /// The single operand that `o` only wraps (a bracketed expression, a postfix without calls).
  static const ast::Operand& bare(const ast::Operand& o) {
    const ast::Operand* x = &o;
    while (true) {
      if (const auto* e = boost::get<ast::Expression>(x); e && e->rest.empty()) {
        x = &e->first;
      } else if (const auto* p = boost::get<ast::Postfix>(x); p && p->ops.empty()) {
        x = &p->primary;
      } else {
        return *x;
      }
    }
  }
  /// `e` without the single-operand levels around it (one per precedence level).
  static const ast::Expression& core(const ast::Expression& e) {
    const ast::Expression* x = &e;
    while (x->rest.empty()) {
      const auto* inner = boost::get<ast::Expression>(&bare(x->first));
      if (!inner) break;
      x = inner;
    }
    return *x;
  }
  static bool is_variable(const ast::Expression& e, const std::string& name) {
    const ast::Expression& c = core(e);
    const auto* id = c.rest.empty() ? boost::get<ast::Identifier>(&bare(c.first)) : nullptr;
    return id && id->name == name;
  }
  /// The variable `name` as an assignment in the current scope would overwrite it, or null
  /// (in a function, a global of that name is not overwritten: the assignment makes a local).
  Value* binding(const std::string& name) {
    if (!frames.empty()) {
      auto it = frames.back()->locals.find(name);
      return it == frames.back()->locals.end() ? nullptr : &it->second;
    }
    auto it = globals.find(name);
    return it == globals.end() ? nullptr : &it->second;
  }
  /// Variable `name`, which the running statement overwrites, lets go of `value`'s library
  /// object if it holds that object (it was read into `value` and not reassigned since), so
  /// that `value` may be its only holder. Returns the variable (none until the assignment;
  /// the caller puts `value` back if the statement fails), or null if nothing was released.
  Value* release(const std::string& name, const Value& value) {
    Value* slot = binding(name);
    const auto* held = slot ? slot->get<std::shared_ptr<const Object>>() : nullptr;
    const auto* mine = value.get<std::shared_ptr<const Object>>();
    if (!held || !mine || held->get() != mine->get()) return nullptr;
    *slot = Value();
    return slot;
  }
  /// The value of `x = e`: eval(e), except that where e is `x op ...` or `f(..., x, ...)` with f a
  /// built-in that takes its arguments (Builtin::takes_arguments), x's value is handed over to
  /// the operator or built-in once every operand is evaluated: x is overwritten anyway, so it
  /// need not keep the old value alive, and `w = carve(w, tool, path)` or `w = w - x` reuse w's
  /// tree instead of copying it. Other holders of the old value (`v = w` before) keep it.
  Value eval_assigned(const ast::Assignment& a) {
    const ast::Expression& e = core(a.value);
    const std::string& x = a.target.name;
    if (!e.rest.empty()) {
      const auto* id = boost::get<ast::Identifier>(&bare(e.first));
      if (id && id->name == x) return eval(e, &x);
    } else if (const auto* p = boost::get<ast::Postfix>(&bare(e.first)); p && p->ops.size() == 1) {
      if (const auto* call_args = boost::get<ast::CallArguments>(&p->ops[0])) {
        check_stack(a.value.where);
        const Value callee = eval(p->primary);
        return call(callee, *call_args, p->where, boost::get<ast::Identifier>(&p->primary), &x);
      }
    }
    return eval(a.value);
  }

  void assign(const ast::Identifier& id, Value value) {
    if (find_builtin(id.name)) {
      throw ScriptError(at(id.where), "cannot assign to '" + id.name + "': it is a built-in");
    }
    if (frames.empty()) {
      globals[id.name] = std::move(value);
      assigned_at[id.name] = ++assignments;
    } else {
      frames.back()->locals[id.name] = std::move(value);
    }
  }

  // ---- expressions ----
  /// `handover`: the variable the statement assigns the result to, when `e` is `handover op ...`
  /// (eval_assigned): the variable lets go of its value before the first operator, so that
  /// the operator may reuse the operand's contents (copy on write, Value::sole_object).
  Value eval(const ast::Expression& e, const std::string* handover = nullptr) {
    check_stack(e.where);
    Value value = eval(e.first);
    for (std::size_t k = 0; k < e.rest.size(); ++k) {
      const ast::Operation& operation = e.rest[k];
      if (operation.op == ast::Op::And || operation.op == ast::Op::Or) {
        const bool left = truth(value, operation.where, operation.op);
        if (left == (operation.op == ast::Op::Or)) continue;  // decided: skip the right side
        value = truth(eval(operation.operand), operation.where, operation.op);
        continue;
      }
      Value right = eval(operation.operand);
      // The left operand is a temporary (or, handed over, the variable's value): an operator
      // may reuse its contents when nothing else holds it.
      Value* released = k == 0 && handover ? release(*handover, value) : nullptr;
      try {
        value = positioned(at(operation.where), "", [&] { return apply_binary(operation.op, std::move(value), right); });
      } catch (...) {
        if (released) *released = value;  // the statement failed: the variable keeps its value
        throw;
      }
      if (const std::string* text = value.get<std::string>()) charge(text->size(), operation.where);
      if (const List* list = value.list()) charge(list->size(), operation.where);
    }
    return value;
  }

  bool truth(const Value& v, std::size_t where, ast::Op op) const {
    if (const bool* b = v.get<bool>()) return *b;
    throw ScriptError(at(where), std::string("'") + ast::spelling(op) + "' needs true or false, got " + type_name(v));
  }

  Value eval(const ast::Operand& operand) {
    struct Visitor {
      Impl& self;
      Value operator()(const ast::Nil&) const { return {}; }
      Value operator()(const ast::NumberLiteral& n) const {
        if (!std::isfinite(n.value)) throw ScriptError(self.at(n.where), "number too large for a double");
        return n.value;
      }
      Value operator()(const ast::StringLiteral& s) const { return s.value; }
      Value operator()(const ast::BoolLiteral& b) const { return b.value; }
      Value operator()(const ast::Identifier& id) const { return self.lookup(id); }
      Value operator()(const ast::ListLiteral& l) const {
        List items;
        items.reserve(l.items.size());
        for (const ast::Expression& item : l.items) items.push_back(self.eval(item));
        return positioned(self.at(l.where), "", [&] { return Value(std::move(items)); });
      }
      Value operator()(const ast::Expression& e) const { return self.eval(e); }
      Value operator()(const ast::Prefixed& p) const {
        Value value = self.eval(p.operand);
        for (auto op = p.ops.rbegin(); op != p.ops.rend(); ++op) {
          value = positioned(self.at(p.where), "", [&] { return apply_prefix(*op, value); });
        }
        return value;
      }
      Value operator()(const ast::Postfix& p) const { return self.eval(p); }
    };
    return boost::apply_visitor(Visitor{*this}, operand);
  }

  Value eval(const ast::Postfix& p) {
    Value value = eval(p.primary);
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

  /// A slice bound: a whole number, counted from the end when negative, clamped to [0, n] (as
  /// in Python); `otherwise` when left out.
  std::size_t slice_bound(const boost::optional<ast::Expression>& bound, std::size_t n, std::size_t otherwise) {
    if (!bound) return otherwise;
    const Value v = eval(*bound);
    const double* d = v.get<double>();
    if (!d || *d != std::floor(*d)) {
      throw ScriptError(at(bound->where),
                        "a slice bound must be a whole number, got " + (d ? format_number(*d) : type_name(v)));
    }
    const double size = static_cast<double>(n);
    return static_cast<std::size_t>(std::clamp(*d < 0 ? *d + size : *d, 0.0, size));
  }

  /// xs[a:b]: the items a, ..., b - 1 as a new list (empty when b <= a).
  Value slice(const Value& value, const ast::Subscript& s) {
    const List* list = value.list();
    if (!list) throw ScriptError(at(s.where), "cannot slice " + type_name(value) + ": only lists have items");
    const std::size_t start = slice_bound(s.start, list->size(), 0);
    const std::size_t stop = slice_bound(s.stop, list->size(), list->size());
    if (stop <= start) return List{};
    charge(stop - start, s.where);
    return List(list->begin() + static_cast<std::ptrdiff_t>(start), list->begin() + static_cast<std::ptrdiff_t>(stop));
  }

  Value subscript(const Value& value, const ast::Subscript& s) {
    if (s.slice) return slice(value, s);
    const Value index = eval(s.index);
    if (const auto* record = value.object<Record>()) return field(*record, index, s);
    const List* list = value.list();
    if (!list) {
      throw ScriptError(at(s.where),
                        "cannot index " + type_name(value) + ": only lists have items and records have fields");
    }
    const double* d = index.get<double>();
    if (!d || *d != std::floor(*d)) {
      throw ScriptError(at(s.index.where), "a list index must be a whole number, got " +
                                               (d ? format_number(*d) : type_name(index)));
    }
    const double n = static_cast<double>(list->size());
    const double i = *d < 0 ? *d + n : *d;
    if (i < 0 || i >= n) {
      throw ScriptError(at(s.index.where), "index " + format_number(*d) + " is out of range for a list of " +
                                               std::to_string(list->size()) + " items");
    }
    return (*list)[static_cast<std::size_t>(i)];
  }

  /// `record["name"]`: the field, or an error listing the fields (and the closest name).
  Value field(const Record& record, const Value& index, const ast::Subscript& s) const {
    const std::string* name = index.get<std::string>();
    if (!name) throw ScriptError(at(s.index.where), "a record's field is named by a string, got " + type_name(index));
    if (const Value* v = record.field(*name)) return *v;
    std::vector<std::string> names;
    std::string listed;
    for (const auto& [key, _] : record.fields()) {
      names.push_back(key);
      listed += (listed.empty() ? "" : ", ") + key;
    }
    const auto near = closest_name(*name, names);
    throw ScriptError(at(s.index.where), "the record has no field \"" + *name + "\"" +
                                             (near ? " (did you mean \"" + *near + "\"?)" : "") +
                                             "; its fields: " + listed);
  }

  // ---- calls ----
  struct Evaluated {
    std::vector<Value> values;
    std::vector<const ast::Argument*> syntax;
  };

  /// Binds arguments to parameters: positional in order, then by name.
  /// Returns for each parameter the index into `args.values` (or -1).
  std::vector<long> bind(const std::string& signature, const std::vector<std::string>& names,
                         const std::vector<bool>& required, bool variadic, const Evaluated& args,
                         std::size_t call_where, std::vector<std::size_t>* rest) const {
    std::vector<long> slot(names.size(), -1);
    std::size_t position = 0;
    for (std::size_t a = 0; a < args.values.size(); ++a) {
      const ast::Argument& syntax = *args.syntax[a];
      if (!syntax.name) {
        if (position < names.size()) {
          slot[position++] = static_cast<long>(a);
        } else if (variadic) {
          rest->push_back(a);
        } else {
          throw ScriptError(at(syntax.where), signature + " takes at most " + std::to_string(names.size()) +
                                                  " argument" + (names.size() == 1 ? "" : "s") + ", got " +
                                                  std::to_string(args.values.size()));
        }
        continue;
      }
      const std::string& name = syntax.name->name;
      std::size_t p = 0;
      while (p < names.size() && names[p] != name) ++p;
      if (p == names.size()) {
        std::string message = signature + " has no parameter '" + name + "'";
        if (auto guess = closest_name(name, names)) message += "; did you mean '" + *guess + "'?";
        throw ScriptError(at(syntax.where), message);
      }
      if (slot[p] >= 0) throw ScriptError(at(syntax.where), signature + ": argument '" + name + "' given twice");
      slot[p] = static_cast<long>(a);
    }
    for (std::size_t p = 0; p < names.size(); ++p) {
      if (slot[p] < 0 && required[p]) {
        throw ScriptError(at(call_where), signature + ": missing argument '" + names[p] + "'");
      }
    }
    return slot;
  }

  /// `handover`: see eval_assigned.
  Value call(const Value& callee, const ast::CallArguments& call_args, std::size_t where,
             const ast::Identifier* callee_name, const std::string* handover = nullptr) {
    check_stack(where);
    count_step(where);
    Evaluated args;
    for (const ast::Argument& a : call_args.arguments) {
      args.values.push_back(eval(a.value));
      args.syntax.push_back(&a);
    }
    if (const auto* builtin = callee.get<const Builtin*>())
      return call_builtin(**builtin, args, where, (*builtin)->takes_arguments ? handover : nullptr);
    if (const auto* f = callee.get<std::shared_ptr<const UserFunction>>()) return call_user(**f, args, where);
    const std::string what = callee_name ? "'" + callee_name->name + "' is a " + type_name(callee)
                                         : "a " + type_name(callee) + " value";
    throw ScriptError(at(where), what + ", not a function");
  }

  /// Calls function value `callee` with positional `values` at `where` (Arguments::call: map, filter).
  Value apply(const Value& callee, std::vector<Value> values, std::size_t where) {
    check_stack(where);
    count_step(where);
    std::vector<ast::Argument> syntax(values.size());
    Evaluated args{std::move(values), {}};
    for (ast::Argument& a : syntax) {
      a.where = where;
      args.syntax.push_back(&a);
    }
    if (const auto* builtin = callee.get<const Builtin*>()) return call_builtin(**builtin, args, where);
    if (const auto* f = callee.get<std::shared_ptr<const UserFunction>>()) return call_user(**f, args, where);
    throw ScriptError(at(where), "a " + type_name(callee) + " value, not a function");
  }

  Value call_builtin(const Builtin& b, const Evaluated& args, std::size_t where, const std::string* handover = nullptr) {
    std::vector<std::string> names;
    std::vector<bool> required;
    for (const Param& p : b.params) {
      names.push_back(p.name);
      required.push_back(p.required);
    }
    std::vector<std::size_t> rest_index;
    const auto slot = bind(b.signature, names, required, b.variadic, args, where, &rest_index);
    std::vector<const Value*> bound;
    std::vector<SourceRef> positions;
    for (long s : slot) {
      bound.push_back(s < 0 ? nullptr : &args.values[static_cast<std::size_t>(s)]);
      positions.push_back(s < 0 ? at(where) : at(args.syntax[static_cast<std::size_t>(s)]->where));
    }
    std::vector<Value> rest;
    std::vector<SourceRef> rest_positions;
    for (std::size_t i : rest_index) {
      rest.push_back(args.values[i]);
      rest_positions.push_back(at(args.syntax[i]->where));
    }
    const Arguments arguments(b, at(where), std::move(bound), std::move(positions), std::move(rest),
                              std::move(rest_positions), settings);
    // The variable the statement overwrites lets go of its value if it is an argument (once all
    // are evaluated): the built-in may then take it (Arguments::sole_object).
    Value* released = nullptr;
    std::size_t released_arg = 0;
    if (handover) {
      for (long s : slot) {
        if (s < 0 || !is_variable(args.syntax[std::size_t(s)]->value, *handover)) continue;
        released_arg = std::size_t(s);
        released = release(*handover, args.values[released_arg]);
        break;
      }
    }
    try {
      return positioned(at(where), b.name + ": ", [&] { return b.run(arguments); });
    } catch (...) {
      if (released) *released = args.values[released_arg];  // the statement failed: keep the value
      throw;
    }
  }

  Value call_user(const UserFunction& f, const Evaluated& args, std::size_t where) {
    const std::string signature = f.name + "()";
    const std::vector<bool> required(f.parameters.size(), true);
    const auto slot = bind(f.name, f.parameters, required, false, args, where, nullptr);
    Frame frame;
    for (std::size_t p = 0; p < slot.size(); ++p) {
      frame.locals[f.parameters[p]] = args.values[static_cast<std::size_t>(slot[p])];
    }
    const SourceRef call_site = at(where);
    frames.push_back(&frame);
    struct PopFrame {
      std::vector<Frame*>& frames;
      ~PopFrame() { frames.pop_back(); }
    } pop{frames};
    try {
      SourceSwap swap(*this, f.where.source, f.program);
      Outcome outcome = exec(f.body->statements);
      return outcome.value ? std::move(*outcome.value) : Value();
    } catch (ScriptError& e) {
      // Recursion repeats the same call site: note each site once.
      const bool repeated = !e.notes().empty() && e.notes().back().where.offset == call_site.offset &&
                            e.notes().back().where.source == call_site.source;
      if (!repeated && e.notes().size() < kMaxNotes) e.add_note({call_site, "in call to '" + f.name + "'"});
      throw;
    }
  }

  // ---- statements ----
  Outcome exec(const std::vector<ast::Statement>& statements) {
    Outcome last;
    for (const ast::Statement& statement : statements) {
      last = exec(statement);
      if (last.returned) return last;
    }
    return last;
  }

  Outcome exec(const ast::Statement& statement) {
    struct Visitor {
      Impl& self;
      Outcome operator()(const ast::Expression& e) const {
        Value value = self.eval(e);
        self.report_top_level(value);
        return {std::move(value)};
      }
      Outcome operator()(const ast::Assignment& a) const {
        if (self.frames.empty() && self.fixed.contains(a.target.name)) return {};  // sculpt -D wins
        self.assign(a.target, self.eval_assigned(a));
        return {};
      }
      Outcome operator()(const ast::Return& r) const {
        if (self.frames.empty()) throw ScriptError(self.at(r.where), "'return' outside a function");
        return {r.value ? self.eval(*r.value) : Value(), true};
      }
      Outcome operator()(const ast::Include& i) const { return self.include(i); }
      Outcome operator()(const ast::If& i) const {
        for (const ast::ConditionalBlock& branch : i.branches) {
          const Value condition = self.eval(branch.condition);
          const bool* b = condition.get<bool>();
          if (!b) {
            throw ScriptError(self.at(branch.condition.where),
                              "an 'if' condition must be true or false, got " + type_name(condition));
          }
          if (*b) return self.exec(branch.body.statements);
        }
        if (i.otherwise) return self.exec(i.otherwise->statements);
        return {};
      }
      Outcome operator()(const ast::For& f) const {
        const Value sequence = self.eval(f.sequence);
        const List* list = sequence.list();
        if (!list) {
          throw ScriptError(self.at(f.sequence.where), "'for' needs a list, got " + type_name(sequence));
        }
        // `sequence` holds the list alive even if the body rebinds the name it came from.
        for (const Value& item : *list) {
          self.assign(f.variable, item);
          Outcome outcome = self.exec(f.body.statements);
          if (outcome.returned) return outcome;
        }
        return {};
      }
      Outcome operator()(const ast::FunctionDefinition& d) const {
        auto f = std::make_shared<UserFunction>();
        f->name = d.name.name;
        for (const ast::Identifier& p : d.parameters) {
          for (const std::string& earlier : f->parameters) {
            if (earlier == p.name) throw ScriptError(self.at(p.where), "parameter '" + p.name + "' appears twice");
          }
          f->parameters.push_back(p.name);
        }
        f->body = &d.body;
        f->program = self.program;
        f->where = self.at(d.where);
        self.assign(d.name, Value(std::shared_ptr<const UserFunction>(std::move(f))));
        return {};
      }
    };
    const std::size_t where = boost::apply_visitor([](const auto& s) { return s.where; }, statement);
    check_stack(where);
    count_step(where);
    return boost::apply_visitor(Visitor{*this}, statement);
  }

  void report_top_level(const Value& value) const {
    if (frames.empty() && options.top_level_value) options.top_level_value(value);
  }

  Outcome include(const ast::Include& i) {
    if (!settings.allow_files) throw ScriptError(at(i.where), "include: file access is disabled in this session");
    std::filesystem::path path(i.path.value);
    if (path.is_relative() && source && !source->directory.empty()) path = std::filesystem::path(source->directory) / path;
    std::error_code ec;
    const std::string key = std::filesystem::weakly_canonical(path, ec).string();
    for (const std::string& open : includes) {
      if (open == key) throw ScriptError(at(i.path.where), "include: '" + path.string() + "' includes itself");
    }
    const SourcePtr included = positioned(at(i.path.where), "include: ", [&] { return load_source(path.string()); });
    if (options.included) options.included(path.string());
    auto parsed = std::make_shared<const ast::Program>(parse(included));
    includes.push_back(key);
    struct PopInclude {
      std::vector<std::string>& includes;
      ~PopInclude() { includes.pop_back(); }
    } pop{includes};
    const SourceRef site = at(i.where);
    try {
      SourceSwap swap(*this, included, parsed);
      exec(parsed->statements);
    } catch (ScriptError& e) {
      if (e.notes().size() < kMaxNotes) e.add_note({site, "included from here"});
      throw;
    }
    return {};
  }
};

Interpreter::Interpreter(InterpreterOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->settings.out = options.out ? options.out : &std::cout;
  impl_->settings.err = options.err ? options.err : &std::cerr;
  impl_->settings.allow_files = options.allow_files;
  impl_->settings.file_read = options.file_read;
  impl_->settings.steps = &impl_->steps;
  impl_->settings.max_steps = options.max_steps;
  impl_->settings.globals = &impl_->globals;
  impl_->grid = options.grid;
  impl_->settings.grid = &impl_->grid;
  impl_->settings.shown = &impl_->shown;
  impl_->settings.call = [impl = impl_.get()](const Value& f, std::vector<Value> values, const SourceRef& at) {
    return impl->apply(f, std::move(values), at.offset);
  };
  // Keep the budget well inside the real stack limit.
  rlimit limit{};
  if (getrlimit(RLIMIT_STACK, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    impl_->options.stack_budget = std::min<std::size_t>(impl_->options.stack_budget, limit.rlim_cur / 2);
  }
}

Interpreter::~Interpreter() = default;

kernel::Grid Interpreter::grid() const { return impl_->grid; }
const std::vector<ShownPart>& Interpreter::shown() const { return impl_->shown; }
void Interpreter::set_grid(const kernel::Grid& grid) { impl_->grid = grid; }

std::optional<Value> Interpreter::run(const SourcePtr& source) {
  Impl& impl = *impl_;
  char marker = 0;
  const bool outermost = impl.stack_base == 0;
  if (outermost) {
    impl.stack_base = reinterpret_cast<std::uintptr_t>(&marker);
    impl.steps = 0;
  }
  struct ResetBase {
    Impl& impl;
    bool outermost;
    ~ResetBase() {
      if (outermost) impl.stack_base = 0;
    }
  } reset{impl, outermost};

  auto program = std::make_shared<const ast::Program>(parse(source));
  Impl::SourceSwap swap(impl, source, program);
  const Outcome outcome = impl.exec(program->statements);
  if (program->statements.empty()) return std::nullopt;
  const ast::Statement& last = program->statements.back();
  if (boost::get<ast::Expression>(&last) || boost::get<ast::If>(&last)) {
    return outcome.value;
  }
  return std::nullopt;
}

void Interpreter::define(const std::string& name, Value value) {
  ast::Identifier id;
  id.name = name;
  impl_->assign(id, std::move(value));
}

void Interpreter::define_fixed(const std::string& name, Value value) {
  define(name, std::move(value));
  impl_->fixed.insert(name);
}

const Value* Interpreter::global(const std::string& name) const {
  auto it = impl_->globals.find(name);
  return it == impl_->globals.end() ? nullptr : &it->second;
}

std::uint64_t Interpreter::assigned_at(const std::string& name) const {
  auto it = impl_->assigned_at.find(name);
  return it == impl_->assigned_at.end() ? 0 : it->second;
}

std::uint64_t Interpreter::assignments() const { return impl_->assignments; }

std::vector<std::string> Interpreter::global_names() const {
  std::vector<std::string> names;
  for (const auto& [name, _] : impl_->globals) names.push_back(name);
  return names;
}

}  // namespace sculpt::language
