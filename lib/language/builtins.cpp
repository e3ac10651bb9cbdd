#include "language/builtins.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace sculpt::language {
namespace {

/// `name(p1, p2=default, ...)` from the declaration (`name` for a constant; a variadic built-in
/// without parameters: `name(a, b, ...)`).
std::string make_signature(const Builtin& b) {
  if (b.constant) return b.name;
  std::string text = b.name + "(";
  for (std::size_t i = 0; i < b.params.size(); ++i) text += (i ? ", " : "") + b.params[i].signature();
  if (b.variadic) text += b.params.empty() ? "a, b, ..." : ", ...";
  return text + ")";
}

/// Whole numbers in full ("1000000000", not to_chars' shortest "1e+09"), others as format_number.
/// Small ones as scientific without the exponent's zeros: tol=1e-3, not 0.001 or 1e-03.
std::string shown_number(double x) {
  if (x == std::floor(x) && std::abs(x) < 1e18) return std::to_string(static_cast<long long>(x));
  if (std::abs(x) >= 0.01) return format_number(x);
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::scientific).ptr;
  std::string text(buffer, end);
  const std::size_t e = text.find('e');
  std::size_t digits = e + 2;  // after "e-"
  while (digits + 1 < text.size() && text[digits] == '0') text.erase(digits, 1);
  return text;
}

}  // namespace

std::string Param::accepted() const {
  const auto bound = shown_number;
  switch (kind) {
    case Kind::Any:
      return what;
    case Kind::Number: {
      std::string text = finite ? "a finite number" : "a number";
      if (nonzero) text += " other than 0";
      const bool has_low = low > -std::numeric_limits<double>::infinity();
      const bool has_high = high < std::numeric_limits<double>::infinity();
      if (has_low && has_high && low_open) return text + " > " + bound(low) + " and <= " + bound(high);
      if (has_low && has_high) return text + " from " + bound(low) + " to " + bound(high);
      if (has_low) return text + (low_open ? " > " : " >= ") + bound(low);
      if (has_high) return text + " <= " + bound(high);
      return text;
    }
    case Kind::Integer:
      return "a whole number from " + bound(low) + " to " + bound(high);
    case Kind::Bool:
      return "true or false";
    case Kind::String:
      return "a string";
    case Kind::Items:
      return "a list";
    case Kind::Vector:
      return "a vector of " + std::to_string(length) + " numbers";
    case Kind::Function:
      return "a function";
    case Kind::Object:
      return what;
  }
  return what;
}

std::string Param::signature() const {
  std::string text = shown.empty() ? name : shown;
  if (!shown_default.empty()) return text + "=" + shown_default;
  if (const double* d = fallback ? fallback->get<double>() : nullptr) return text + "=" + shown_number(*d);
  if (fallback) return text + "=" + to_repr(*fallback);
  return text;
}

Arguments::Arguments(const Builtin& builtin, SourceRef call, std::vector<const Value*> bound,
                     std::vector<SourceRef> positions, std::vector<Value> rest, std::vector<SourceRef> rest_positions,
                     const RunSettings& settings)
    : builtin_(builtin),
      call_(std::move(call)),
      bound_(std::move(bound)),
      positions_(std::move(positions)),
      rest_(std::move(rest)),
      rest_positions_(std::move(rest_positions)),
      settings_(settings) {
  for (std::size_t i = 0; i < bound_.size(); ++i) {
    if (bound_[i]) check(i);
  }
}

std::size_t Arguments::index(std::string_view name) const {
  for (std::size_t i = 0; i < builtin_.params.size(); ++i) {
    if (builtin_.params[i].name == name) return i;
  }
  throw std::logic_error("built-in '" + builtin_.name + "' has no parameter '" + std::string(name) + "'");
}

const Param& Arguments::param(std::string_view name) const { return builtin_.params[index(name)]; }

void Arguments::check(std::size_t i) const {
  const Param& p = builtin_.params[i];
  const Value& v = *bound_[i];
  const auto refuse = [&] {
    std::string message = "argument '" + p.name + "' must be " + p.accepted() + ", got ";
    const double* d = v.get<double>();
    if (d && (p.kind == Kind::Number || p.kind == Kind::Integer)) {
      message += format_number(*d);
    } else {
      message += type_name(v);
    }
    fail_at(i, message);
  };
  switch (p.kind) {
    case Kind::Any:
      return;
    case Kind::Number: {
      const double* d = v.get<double>();
      if (!d || (p.finite && !std::isfinite(*d)) || (p.nonzero && *d == 0) || *d < p.low || *d > p.high ||
          (p.low_open && *d == p.low))
        refuse();
      return;
    }
    case Kind::Integer: {
      const double* d = v.get<double>();
      if (!d || *d != std::floor(*d) || *d < p.low || *d > p.high) refuse();
      return;
    }
    case Kind::Bool:
      if (!v.is<bool>()) refuse();
      return;
    case Kind::String:
      if (!v.is<std::string>()) refuse();
      return;
    case Kind::Items:
      if (!v.list()) refuse();
      return;
    case Kind::Vector: {
      const List* l = v.list();
      if (!l || l->size() != p.length) refuse();
      for (const Value& x : *l) {
        if (!x.is<double>()) refuse();
      }
      return;
    }
    case Kind::Function:
      if (!v.is<std::shared_ptr<const UserFunction>>() && !v.is<const Builtin*>()) refuse();
      return;
    case Kind::Object:
      if (!p.accepts(v)) refuse();
      return;
  }
}

void Arguments::fail_at(std::size_t i, const std::string& message) const {
  throw ScriptError(bound_[i] ? positions_[i] : call_, builtin_.name + ": " + message);
}

const Value& Arguments::value(std::string_view name) const {
  static const Value none;
  const std::size_t i = index(name);
  if (bound_[i]) return *bound_[i];
  const Param& p = builtin_.params[i];
  return p.fallback ? *p.fallback : none;
}

double Arguments::number(std::string_view name) const {
  if (auto d = value(name).get<double>()) return *d;
  fail_type(name, "a number");
}

long long Arguments::integer(std::string_view name) const {
  const Param& p = param(name);
  const double d = number(name);
  if (d != std::floor(d) || d < p.low || d > p.high) {
    fail(name, "argument '" + p.name + "' must be " + p.accepted() + ", got " + format_number(d));
  }
  return static_cast<long long>(d);
}

long long Arguments::integer(std::string_view name, long long low, long long high) const {
  const double d = number(name);
  if (d != std::floor(d) || d < static_cast<double>(low) || d > static_cast<double>(high)) {
    fail(name, "argument '" + std::string(name) + "' must be a whole number from " + std::to_string(low) + " to " +
                   std::to_string(high) + ", got " + format_number(d));
  }
  return static_cast<long long>(d);
}

bool Arguments::boolean(std::string_view name) const {
  if (auto b = value(name).get<bool>()) return *b;
  fail_type(name, "true or false");
}

const std::string& Arguments::string(std::string_view name) const {
  if (auto s = value(name).get<std::string>()) return *s;
  fail_type(name, "a string");
}

const List& Arguments::list(std::string_view name) const {
  if (const List* l = value(name).list()) return *l;
  fail_type(name, "a list");
}

std::vector<double> Arguments::vector(std::string_view name, std::size_t n) const {
  if (n == 0) n = param(name).length;
  const std::string expected = "a vector of " + std::to_string(n) + " numbers";
  const List* l = value(name).list();
  if (!l || l->size() != n) fail_type(name, expected);
  std::vector<double> out;
  for (const Value& v : *l) {
    const double* d = v.get<double>();
    if (!d) fail_type(name, expected);
    out.push_back(*d);
  }
  return out;
}

std::string format_point(const Eigen::Vector3d& p) {
  std::string s = "(";  // appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on the chained +
  s += format_number(p.x());
  s += ", ";
  s += format_number(p.y());
  s += ", ";
  s += format_number(p.z());
  s += ")";
  return s;
}

Eigen::Vector3d Arguments::point(std::string_view name) const {
  const auto v = vector(name, 3);
  return {v[0], v[1], v[2]};
}

const Value& Arguments::function(std::string_view name) const {
  const Value& v = value(name);
  if (!v.is<std::shared_ptr<const UserFunction>>() && !v.is<const Builtin*>()) fail_type(name, "a function");
  return v;
}

void Arguments::fail(std::string_view name, const std::string& message) const { fail_at(index(name), message); }

void Arguments::fail(const std::string& message) const { throw ScriptError(call_, builtin_.name + ": " + message); }

void Arguments::fail_type(std::string_view name, const std::string& expected) const {
  fail(name, "argument '" + std::string(name) + "' must be " + expected + ", got " + type_name(value(name)));
}

Value Arguments::call(const Value& f, std::vector<Value> values) const {
  if (!settings_.call) throw std::logic_error("Arguments::call: the run cannot call functions");
  return settings_.call(f, std::move(values), call_);
}

void Arguments::charge(std::uint64_t n) const {
  if (settings_.steps == nullptr || settings_.max_steps == 0) return;
  *settings_.steps += n;
  if (*settings_.steps > settings_.max_steps) fail("step limit of " + std::to_string(settings_.max_steps) + " exceeded");
}

const Value* Arguments::global(const std::string& name) const {
  if (settings_.globals == nullptr) return nullptr;
  auto it = settings_.globals->find(name);
  return it == settings_.globals->end() ? nullptr : &it->second;
}

const std::map<std::string, Value>& Arguments::globals() const {
  static const std::map<std::string, Value> none;
  return settings_.globals ? *settings_.globals : none;
}

void Arguments::set_grid(const kernel::Grid& grid) const {
  if (!settings_.grid) throw std::logic_error("Arguments::set_grid: the run has no grid setting");
  *settings_.grid = grid;
}

std::string Arguments::file_path(std::string_view name) const {
  const std::string& path = string(name);
  if (!settings_.allow_files) fail(name, "file access is disabled in this session");
  if (path.empty()) fail(name, "empty file name");
  std::filesystem::path p(path);
  if (p.is_relative() && call_.source && !call_.source->directory.empty()) {
    p = std::filesystem::path(call_.source->directory) / p;
  }
  return p.string();
}

std::string Arguments::input_path(std::string_view name) const {
  std::string path = file_path(name);
  if (settings_.file_read) settings_.file_read(path);
  return path;
}

void BuiltinTable::add(Builtin builtin) {
  builtin.area = area_;
  if (builtin.signature.empty()) builtin.signature = make_signature(builtin);
  const std::string name = builtin.name;
  if (!entries_.emplace(name, std::move(builtin)).second) {
    throw std::logic_error("built-in '" + name + "' registered twice");
  }
}

const Builtin* BuiltinTable::find(const std::string& name) const {
  auto it = entries_.find(name);
  return it == entries_.end() ? nullptr : &it->second;
}

const BuiltinTable& builtins() {
  static const BuiltinTable table = [] {
    BuiltinTable t;
    t.set_area("core");
    register_core(t);
    register_lists(t);
#ifndef SCULPT_LANGUAGE_CORE_ONLY  // the fuzz target builds the language without the geometry areas
    t.set_area("curves");
    register_curves(t);
    t.set_area("solids");
    register_solids(t);
    register_bounds(t);
    t.set_area("splines");
    register_splines(t);
    t.set_area("surfaces");
    register_surfaces(t);
    t.set_area("revolution");
    register_revolution(t);
    t.set_area("reports");
    register_reports(t);
    t.set_area("implicit");
    register_implicit(t);
    t.set_area("render");
    register_render(t);
    t.set_area("motions");
    register_motions(t);
    t.set_area("view");
    register_view(t);
#endif
    return t;
  }();
  return table;
}

std::span<const char* const> keywords() {
  static constexpr const char* words[] = {"fn",  "if",  "else", "for",  "in",   "return",
                                          "include", "and", "or", "not", "true", "false"};
  return words;
}

}  // namespace sculpt::language
