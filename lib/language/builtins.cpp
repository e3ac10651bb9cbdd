#include "language/builtins.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace sculpt::language {

Arguments::Arguments(const Builtin& builtin, SourceRef call, std::vector<const Value*> bound,
                     std::vector<SourceRef> positions, std::vector<Value> rest,
                     std::vector<SourceRef> rest_positions, const RunSettings& settings)
    : builtin_(builtin),
      call_(std::move(call)),
      bound_(std::move(bound)),
      positions_(std::move(positions)),
      rest_(std::move(rest)),
      rest_positions_(std::move(rest_positions)),
      settings_(settings) {}

const Value& Arguments::value(std::size_t i) const {
  static const Value none;
  return bound_[i] ? *bound_[i] : none;
}

void Arguments::fail(std::size_t i, const std::string& message) const {
  throw ScriptError(bound_[i] ? positions_[i] : call_, builtin_.name + ": " + message);
}

void Arguments::fail(const std::string& message) const {
  throw ScriptError(call_, builtin_.name + ": " + message);
}

void Arguments::fail_type(std::size_t i, const char* expected) const {
  fail(i, "argument '" + builtin_.params[i].name + "' must be " + expected + ", got " +
              type_name(value(i)));
}

double Arguments::number(std::size_t i) const {
  if (auto d = value(i).get<double>()) return *d;
  fail_type(i, "a number");
}

long long Arguments::integer(std::size_t i, long long low, long long high) const {
  const double d = number(i);
  if (d != std::floor(d) || d < static_cast<double>(low) || d > static_cast<double>(high)) {
    fail(i, "argument '" + builtin_.params[i].name + "' must be a whole number from " +
                std::to_string(low) + " to " + std::to_string(high) + ", got " + format_number(d));
  }
  return static_cast<long long>(d);
}

bool Arguments::boolean(std::size_t i) const {
  if (auto b = value(i).get<bool>()) return *b;
  fail_type(i, "true or false");
}

const std::string& Arguments::string(std::size_t i) const {
  if (auto s = value(i).get<std::string>()) return *s;
  fail_type(i, "a string");
}

const List& Arguments::list(std::size_t i) const {
  if (const List* l = value(i).list()) return *l;
  fail_type(i, "a list");
}

std::vector<double> Arguments::vector(std::size_t i, std::size_t n) const {
  const std::string expected = "a vector of " + std::to_string(n) + " numbers";
  const List* l = value(i).list();
  if (!l || l->size() != n) fail_type(i, expected.c_str());
  std::vector<double> out;
  for (const Value& v : *l) {
    const double* d = v.get<double>();
    if (!d) fail_type(i, expected.c_str());
    out.push_back(*d);
  }
  return out;
}

const Value& Arguments::function(std::size_t i) const {
  const Value& v = value(i);
  if (!v.is<std::shared_ptr<const UserFunction>>() && !v.is<const Builtin*>()) fail_type(i, "a function");
  return v;
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

std::string Arguments::file_path(std::size_t i) const {
  const std::string& path = string(i);
  if (!settings_.allow_files) fail(i, "file access is disabled in this session");
  if (path.empty()) fail(i, "empty file name");
  std::filesystem::path p(path);
  if (p.is_relative() && call_.source && !call_.source->directory.empty()) {
    p = std::filesystem::path(call_.source->directory) / p;
  }
  return p.string();
}

void BuiltinTable::add(Builtin builtin) {
  builtin.area = area_;
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
