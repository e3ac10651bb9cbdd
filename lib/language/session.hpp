#pragma once
/// \file session.hpp
/// An interactive session without the terminal: lines in, output out. The REPL (repl/) puts
/// libedit in front of it; tests drive it directly. Entries that leave brackets open, or stop
/// right after an operator, continue on the next line (an empty line ends the latter); `:help [name]`,
/// `:load file`, `:vars`, `:show [name] [view]`, `:quit` are commands. An error is printed and the
/// session goes on with every binding intact.
///
/// `:show name` renders the solid (or list of solids) bound to `name` to `<show dir>/name.png` and
/// prints the path, so an image viewer kept open on the file follows the sculpting; `:show` alone
/// shows the last solid made: the value of the latest entry that was a solid expression, or the
/// global most recently bound to a solid, whichever came later (`last.png` for the former).

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "language/interpreter.hpp"

namespace sculpt::language {

class Session {
 public:
  /// `out` receives printed values and command output, `err` the error messages.
  /// `interrupt` (optional) stops a running entry with an "interrupted" error when it turns true
  /// (see InterpreterOptions::interrupt); the session goes on.
  Session(std::ostream& out, std::ostream& err, const std::atomic<bool>* interrupt = nullptr);

  /// Feeds one typed line. Returns false when the session is over (:quit).
  bool feed(const std::string& line);
  /// True while an unfinished entry waits for more lines (show the continuation prompt).
  [[nodiscard]] bool continuing() const { return !pending_.empty(); }
  /// Drops the unfinished entry, if any (Ctrl-C at a prompt). Returns whether there was one.
  bool discard_pending();
  /// Names (keywords, built-ins, globals, and commands when `text` starts with ':') that
  /// start with `text`, sorted. `before` is the line before `text`: when it ends inside a call's
  /// parentheses, the function's parameter names not yet given are offered too, as `name=`.
  [[nodiscard]] std::vector<std::string> complete(std::string_view text, std::string_view before = {}) const;
  [[nodiscard]] Interpreter& interpreter() { return interpreter_; }
  /// Adds a command such as `:view` that the session itself does not know (the sculpt executable
  /// adds it: the view is a layer above the language). `run` gets the rest of the line.
  void add_command(std::string name, std::function<void(const std::string& argument)> run);
  /// The last solid made: the value of the latest entry that was a solid, or the global most
  /// recently bound to a solid, whichever came later (what `:show` alone shows); nullopt if none.
  [[nodiscard]] std::optional<Value> last_solid() const;
  /// Where `:show` writes its pictures (created when needed). Default: show_directory_default().
  void set_show_directory(std::filesystem::path dir) { show_dir_ = std::move(dir); }
  [[nodiscard]] const std::filesystem::path& show_directory() const { return show_dir_; }
  /// The terminal's width, to which `:help` wraps its lines (0: not wrapped; the REPL sets it).
  void set_width(std::size_t columns) { width_ = columns; }

 private:
  void command(const std::string& line);
  void run(const SourcePtr& source);
  void show(const std::string& argument);

  std::ostream& out_;
  std::ostream& err_;
  Interpreter interpreter_;
  std::string pending_;
  int next_line_ = 1;
  std::filesystem::path show_dir_;
  std::size_t width_ = 0;
  /// The latest entry value that was a solid, with the assignment serial at that time.
  std::optional<Value> last_value_;
  std::uint64_t last_value_serial_ = 0;
  std::map<std::string, std::function<void(const std::string&)>> extra_commands_;
};

/// `$SCULPT_SHOW_DIR` if set, else `<temporary directory>/sculpt-show-<uid>` (one per user).
std::filesystem::path show_directory_default();

/// `:help` text: an overview of commands, keywords and built-ins when `name` is empty, else
/// the signature and description of one built-in (and what each parameter takes) or keyword.
/// Lines are wrapped to `width` columns (0: not wrapped).
std::string help_text(std::string_view name, std::size_t width = 0);

/// `text` in lines of at most `width` columns (0: one line), broken between words, each
/// line indented by `indent` spaces; a word longer than a line stands alone. Ends in a newline.
std::string wrap_text(std::string_view text, std::size_t width, std::size_t indent);

}  // namespace sculpt::language
