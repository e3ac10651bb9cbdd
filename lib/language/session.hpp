#pragma once
/// \file session.hpp
/// An interactive session without the terminal: lines in, output out. The REPL (repl/) puts
/// libedit in front of it; tests drive it directly. Entries that leave brackets open, or stop
/// right after an operator, continue on the next line (an empty line ends the latter); `:help [name]`, `:load file`, `:vars`, `:quit` are commands. An error is
/// printed and the session goes on with every binding intact.

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
  /// start with `text`, sorted.
  [[nodiscard]] std::vector<std::string> complete(std::string_view text) const;
  [[nodiscard]] Interpreter& interpreter() { return interpreter_; }

 private:
  void command(const std::string& line);
  void run(const SourcePtr& source);

  std::ostream& out_;
  std::ostream& err_;
  Interpreter interpreter_;
  std::string pending_;
  int next_line_ = 1;
};

/// `:help` text: an overview of commands, keywords and built-ins when `name` is empty, else
/// the signature and description of one built-in or keyword.
std::string help_text(std::string_view name);

}  // namespace sculpt::language
