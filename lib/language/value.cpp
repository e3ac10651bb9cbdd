#include "language/value.hpp"

#include <algorithm>
#include <charconv>

#include "base/errors.hpp"

#include "language/builtins.hpp"

namespace sculpt::language {

Value::Value(List items) {
  int depth = 1;
  for (const Value& item : items) depth = std::max(depth, item.list_depth() + 1);
  if (depth > kMaxListDepth) {
    throw RangeError("lists nested deeper than " + std::to_string(kMaxListDepth) + " levels");
  }
  data_ = std::make_shared<const ListData>(ListData{std::move(items), depth});
}

std::optional<Value> Object::binary_sole(ast::Op op, const Value& other) { return binary(op, other, true); }

std::optional<Value> Object::binary(ast::Op /*op*/, const Value& /*other*/, bool /*self_on_left*/) const {
  return std::nullopt;
}

std::string type_name(const Value& value) {
  struct Visitor {
    std::string operator()(None) const { return "none"; }
    std::string operator()(double) const { return "number"; }
    std::string operator()(bool) const { return "bool"; }
    std::string operator()(const std::string&) const { return "string"; }
    std::string operator()(const std::shared_ptr<const ListData>&) const { return "list"; }
    std::string operator()(const std::shared_ptr<const UserFunction>&) const { return "function"; }
    std::string operator()(const Builtin*) const { return "function"; }
    std::string operator()(const std::shared_ptr<const Object>& o) const { return o->type_name(); }
  };
  return std::visit(Visitor{}, value.data());
}

std::string format_number(double number) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, number);
  return std::string(buffer, result.ptr);
}

namespace {

std::string quote(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\\': out += "\\\\"; break;
      case '"': out += "\\\""; break;
      default: out += c;
    }
  }
  return out + "\"";
}

/// Recursion bounded by kMaxListDepth.
std::string show_value(const Value& value, bool repr, int depth) {
  struct Visitor {
    bool repr;
    int depth;
    std::string operator()(None) const { return "none"; }
    std::string operator()(double d) const { return format_number(d); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& s) const { return repr ? quote(s) : s; }
    std::string operator()(const std::shared_ptr<const ListData>& data) const {
      const List* list = &data->items;
      std::string out = "[";
      for (std::size_t i = 0; i < list->size(); ++i) {
        if (i > 0) out += ", ";
        out += show_value((*list)[i], true, depth + 1);
      }
      return out + "]";
    }
    std::string operator()(const std::shared_ptr<const UserFunction>& f) const {
      std::string out = "<fn " + f->name + "(";
      for (std::size_t i = 0; i < f->parameters.size(); ++i) out += (i ? ", " : "") + f->parameters[i];
      return out + ")>";
    }
    std::string operator()(const Builtin* b) const { return "<built-in " + b->signature + ">"; }
    std::string operator()(const std::shared_ptr<const Object>& o) const { return o->repr(); }
  };
  return std::visit(Visitor{repr, depth}, value.data());
}

}  // namespace

std::string to_display(const Value& value) { return show_value(value, false, 0); }
std::string to_repr(const Value& value) { return show_value(value, true, 0); }

bool equal(const Value& a, const Value& b) {
  if (a.data().index() != b.data().index()) return false;
  if (a.is_none()) return true;
  if (auto x = a.get<double>()) return *x == *b.get<double>();
  if (auto x = a.get<bool>()) return *x == *b.get<bool>();
  if (auto x = a.get<std::string>()) return *x == *b.get<std::string>();
  if (const List* x = a.list()) {
    const List* y = b.list();
    if (x == y) return true;
    if (x->size() != y->size()) return false;
    for (std::size_t i = 0; i < x->size(); ++i) {
      if (!equal((*x)[i], (*y)[i])) return false;
    }
    return true;
  }
  if (auto x = a.get<std::shared_ptr<const UserFunction>>()) return *x == *b.get<std::shared_ptr<const UserFunction>>();
  if (auto x = a.get<const Builtin*>()) return *x == *b.get<const Builtin*>();
  return *a.get<std::shared_ptr<const Object>>() == *b.get<std::shared_ptr<const Object>>();
}

}  // namespace sculpt::language
