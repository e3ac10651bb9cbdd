#include "language/session.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>

#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "language/builtins.hpp"
#include "language/parser.hpp"
#include "language/picture_items.hpp"
#include "language/solid_values.hpp"
#include "language/suggest.hpp"
#include "render/camera.hpp"
#include "render/picture.hpp"
#include "render/png_image.hpp"

namespace sculpt::language {
namespace {

constexpr const char* kCommands[] = {":help", ":load", ":quit", ":show", ":vars"};

const std::map<std::string, std::string>& keyword_help() {
  static const std::map<std::string, std::string> help = {
      {"fn", "fn name(a, b) { ... }  defines a function; it returns `return e` or its last expression."},
      {"if", "if c { ... } else if d { ... } else { ... }  runs the first block whose condition is true."},
      {"else", "if c { ... } else { ... }"},
      {"for", "for x in xs { ... }  runs the block once per item of the list xs."},
      {"in", "for x in xs { ... }"},
      {"return", "return e  leaves the current function with the value e."},
      {"include", "include \"file.bsp\"  runs another script here (path relative to this script)."},
      {"and", "a and b  true when both are true (b is not evaluated when a is false)."},
      {"or", "a or b  true when either is true (b is not evaluated when a is true)."},
      {"not", "not a  the opposite of a bool."},
      {"true", "the bool true"},
      {"false", "the bool false"},
  };
  return help;
}

/// The entry stops in the middle of a construct (after an operator, `else`, ...): the parser
/// fails at the very end of the text. The REPL then waits for more; an empty line ends it.
bool ends_early(const std::string& text) {
  auto source = std::make_shared<SourceFile>();
  source->text = text;
  try {
    parse(source);
  } catch (const ScriptError& e) {
    return text.find_first_not_of(" \t\r\n", e.where().offset) == std::string::npos;
  }
  return false;
}

std::string first_word(std::string_view text) {
  const auto begin = text.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return {};
  const auto end = text.find_first_of(" \t", begin);
  return std::string(text.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin));
}

}  // namespace

std::string wrap_text(std::string_view text, std::size_t width, std::size_t indent) {
  const std::string margin(indent, ' ');
  std::string out;
  std::size_t column = 0;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    const std::string_view word = text.substr(at, end - at);
    at = end + 1;
    if (word.empty()) continue;
    if (column == 0) {
      out += margin;
      column = indent;
    } else if (width > 0 && column + 1 + word.size() > width) {
      out += "\n" + margin;
      column = indent;
    } else {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
  }
  return out + "\n";
}

std::string help_text(std::string_view name, std::size_t width) {
  const BuiltinTable& table = builtins();
  if (name.empty()) {
    std::string out =
        "Commands: :help [name], :load file, :vars, :show [name] [view], :quit\n"
        "Keywords: fn if else for in return include and or not true false\n"
        "Operators: + - * / % (numbers, vectors), == != < <= > >=, | & - (solids: union, "
        "intersection, difference)\n";
    std::map<std::string, std::vector<std::string>> by_area;
    for (const auto& [n, b] : table.entries()) by_area[b.area].push_back(n);
    for (const auto& [area, names] : by_area) {
      out += "Built-ins (" + area + "):";
      for (const std::string& n : names) out += " " + n;
      out += "\n";
    }
    out += "Type :help name for details.\n";
    return out;
  }
  const std::string key(name);
  if (const Builtin* b = table.find(key)) {
    // The doc, then what each declared parameter takes (Param::accepted).
    std::string out = b->signature + "\n" + wrap_text(b->doc, width, 2);
    for (const Param& p : b->params) {
      if (const std::string accepted = p.accepted(); !accepted.empty())
        out += wrap_text(p.name + ": " + accepted, width, 4);
    }
    return out;
  }
  if (auto it = keyword_help().find(key); it != keyword_help().end()) return wrap_text(it->second, width, 0);
  std::vector<std::string> candidates;
  for (const auto& [n, _] : table.entries()) candidates.push_back(n);
  for (const auto& [n, _] : keyword_help()) candidates.push_back(n);
  std::string out = "no built-in or keyword named '" + key + "'";
  if (auto guess = closest_name(key, candidates)) out += "; did you mean '" + *guess + "'?";
  return out + "\n";
}

std::filesystem::path show_directory_default() {
  if (const char* dir = std::getenv("SCULPT_SHOW_DIR"); dir && *dir) return dir;
  std::error_code ec;
  std::filesystem::path tmp = std::filesystem::temp_directory_path(ec);
  if (ec) tmp = "/tmp";
  return tmp / ("sculpt-show-" + std::to_string(::getuid()));
}

Session::Session(std::ostream& out, std::ostream& err, const std::atomic<bool>* interrupt)
    : out_(out),
      err_(err),
      interpreter_(InterpreterOptions{.out = &out, .err = &err, .interrupt = interrupt}),
      show_dir_(show_directory_default()) {}

bool Session::discard_pending() {
  const bool had = !pending_.empty();
  pending_.clear();
  return had;
}

bool Session::feed(const std::string& line) {
  if (pending_.empty()) {
    const std::string word = first_word(line);
    if (word == ":quit" || word == ":q") return false;
    if (!word.empty() && word[0] == ':') {
      try {
        command(line);
      } catch (const Cancelled&) {  // Ctrl-C during a command's work (base/cancel.hpp)
        out_.flush();
        err_ << "error: interrupted\n";
        err_.flush();
      }
      return true;
    }
  }
  const bool ending = !pending_.empty() && line.find_first_not_of(" \t\r") == std::string::npos;
  pending_ += line;
  pending_ += '\n';
  if (is_unfinished(pending_)) return true;
  if (!ending && ends_early(pending_)) return true;
  auto source = std::make_shared<SourceFile>();
  source->name = "<stdin>";
  source->text = std::move(pending_);
  source->first_line = next_line_;
  pending_.clear();
  next_line_ += static_cast<int>(std::count(source->text.begin(), source->text.end(), '\n'));
  run(source);
  return true;
}

void Session::run(const SourcePtr& source) {
  try {
    if (auto value = interpreter_.run(source); value && !value->is_none()) {
      out_ << to_repr(*value) << "\n";
      if (value->object<SolidValue>()) {
        last_value_ = *value;
        last_value_serial_ = interpreter_.assignments();
      }
    }
  } catch (const ScriptError& e) {
    err_ << format_error(e);
  } catch (const Cancelled&) {  // Ctrl-C outside a statement's built-ins (base/cancel.hpp)
    err_ << "error: interrupted\n";
  }
  out_.flush();
  err_.flush();
}

void Session::command(const std::string& line) {
  const auto begin = line.find_first_not_of(" \t");
  const std::string word = first_word(line);
  std::string argument = line.substr(begin + word.size());
  argument.erase(0, argument.find_first_not_of(" \t"));
  argument.erase(argument.find_last_not_of(" \t\r") + 1);
  if (word == ":help" || word == ":h") {
    out_ << help_text(argument, width_);
    if (argument.empty() && !extra_commands_.empty()) {
      out_ << "More commands:";
      for (const auto& [name, _] : extra_commands_) out_ << " " << name;
      out_ << "\n";
    }
  } else if (word == ":vars") {
    for (const std::string& name : interpreter_.global_names()) {
      const Value& v = *interpreter_.global(name);
      std::string shown = to_repr(v);
      if (shown.size() > 70) shown.replace(67, std::string::npos, "...");
      out_ << name << " : " << type_name(v) << " = " << shown << "\n";
    }
  } else if (word == ":show") {
    show(argument);
  } else if (auto extra = extra_commands_.find(word); extra != extra_commands_.end()) {
    extra->second(argument);
  } else if (word == ":load") {
    if (argument.empty()) {
      err_ << "error: :load needs a file name\n";
    } else {
      try {
        run(load_source(argument));
      } catch (const IoError& e) {
        err_ << "error: " << e.what() << "\n";
      }
    }
  } else {
    std::vector<std::string> commands(std::begin(kCommands), std::end(kCommands));
    std::string extras;
    for (const auto& [name, _] : extra_commands_) {
      commands.push_back(name);
      extras += ", " + name;
    }
    err_ << "error: unknown command '" << word << "'";
    if (auto guess = closest_name(word, commands)) err_ << "; did you mean '" << *guess << "'?";
    err_ << " (commands: :help, :load, :vars, :show, :quit" << extras << ")\n";
  }
  out_.flush();
  err_.flush();
}

void Session::show(const std::string& argument) {
  const std::string name = first_word(argument);
  const std::string view = first_word(argument.substr(argument.find(name) + name.size()));
  std::string file = name;
  std::optional<Value> value;
  if (!name.empty()) {
    const Value* v = interpreter_.global(name);
    if (!v) {
      err_ << "error: :show: no variable named '" << name << "'\n";
      return;
    }
    value = *v;
  } else {
    // The most recently bound global solid, unless an entry's solid value came later.
    file = latest_solid_global(interpreter_);
    const std::uint64_t best = file.empty() ? 0 : interpreter_.assigned_at(file);
    value = last_solid();
    if (!value) {
      err_ << "error: :show: no solid made yet (:show name shows the solid bound to name)\n";
      return;
    }
    if (last_value_ && last_value_serial_ >= best) file = "last";
  }
  // What render draws (solids, meshes, surfaces, curves of every kind, lists of them).
  auto items = picture_items(*value, "'" + file + "'");
  if (const std::string* error = std::get_if<std::string>(&items)) {
    err_ << "error: :show: " << *error << "\n";
    return;
  }
  try {
    render::PictureOptions options{.antialias = kPictureAntialias};
    if (!view.empty()) options.view = render::view_direction(view);
    std::filesystem::create_directories(show_dir_);
    const std::filesystem::path path = show_dir_ / (file + ".png");
    render::write_png(render::render_items(std::get<std::vector<render::PictureItem>>(items), options), path,
                      {.fast = true});
    out_ << path.string() << "\n";
  } catch (const std::exception& e) {
    err_ << "error: :show: " << e.what() << "\n";
  }
}

std::optional<Value> Session::last_solid() const {
  const std::string name = latest_solid_global(interpreter_);
  const std::uint64_t best = name.empty() ? 0 : interpreter_.assigned_at(name);
  if (last_value_ && last_value_serial_ >= best) return last_value_;
  if (best > 0) return *interpreter_.global(name);
  return std::nullopt;
}

void Session::add_command(std::string name, std::function<void(const std::string& argument)> run) {
  extra_commands_[std::move(name)] = std::move(run);
}

namespace {

/// The name of the call whose argument list `before` ends inside (`sphere(1, ` gives "sphere"),
/// or "" when it ends outside every call. Brackets and strings are skipped.
std::string open_call(std::string_view before) {
  std::vector<std::size_t> opened;  // positions of the '(' and '[' not yet closed
  bool in_string = false;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const char c = before[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '(' || c == '[') {
      opened.push_back(i);
    } else if ((c == ')' || c == ']') && !opened.empty()) {
      opened.pop_back();
    }
  }
  if (opened.empty() || before[opened.back()] != '(') return "";
  std::size_t end = opened.back();
  while (end > 0 && before[end - 1] == ' ') --end;
  std::size_t start = end;
  auto is_name = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  while (start > 0 && is_name(before[start - 1])) --start;
  return std::string(before.substr(start, end - start));
}

/// `name=` for each parameter of the function `call` (a built-in or a script's fn) whose name
/// starts with `text` and that the call does not name yet.
std::vector<std::string> parameter_names(const Interpreter& interpreter, const std::string& call,
                                         std::string_view before, std::string_view text) {
  std::vector<std::string> parameters;
  if (const Value* v = interpreter.global(call)) {
    if (const auto* f = v->get<std::shared_ptr<const UserFunction>>()) parameters = (*f)->parameters;
  } else if (const Builtin* b = builtins().find(call)) {
    for (const Param& p : b->params) parameters.push_back(p.name);
  }
  const std::string_view arguments = before.substr(before.rfind('('));
  std::vector<std::string> out;
  for (const std::string& p : parameters) {
    if (p.compare(0, text.size(), text) != 0) continue;
    const std::size_t named = arguments.find(p + "=");
    const bool given = named != std::string_view::npos &&
                       (named == 0 || !std::isalnum(static_cast<unsigned char>(arguments[named - 1])));
    if (!given) out.push_back(p + "=");
  }
  return out;
}

}  // namespace

std::vector<std::string> Session::complete(std::string_view text, std::string_view before) const {
  std::vector<std::string> names;
  auto consider = [&](const std::string& name) {
    if (name.compare(0, text.size(), text) == 0) names.push_back(name);
  };
  if (const std::string call = open_call(before); !call.empty()) {
    names = parameter_names(interpreter_, call, before, text);
  }
  if (!text.empty() && text[0] == ':') {
    for (const char* c : kCommands) consider(c);
    for (const auto& [name, _] : extra_commands_) consider(name);
  } else {
    for (const char* k : keywords()) consider(k);
    for (const auto& [name, _] : builtins().entries()) consider(name);
    for (const std::string& name : interpreter_.global_names()) consider(name);
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

}  // namespace sculpt::language
