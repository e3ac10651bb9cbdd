#pragma once
/// \file source.hpp
/// A script's text with its name, and errors that point into it. Every error the language
/// reports reads `file:line:col: error: message`, then the source line and a caret.

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sculpt::language {

/// The text of one script (a file, `-e` code, or one REPL entry).
struct SourceFile {
  std::string name;       ///< shown in messages: a path, "<stdin>" or "<command line>"
  std::string text;
  std::string directory;  ///< folder that relative paths in the script refer to ("" = current)
  int first_line = 1;     ///< line number of the first line (the REPL numbers entries on)

  /// 1-based line and column (in bytes) of a byte offset.
  [[nodiscard]] std::pair<int, int> line_column(std::size_t offset) const;
  /// The whole line containing `offset`, without its newline.
  [[nodiscard]] std::string_view line_text(std::size_t offset) const;
};

using SourcePtr = std::shared_ptr<const SourceFile>;

/// A position in a script.
struct SourceRef {
  SourcePtr source;
  std::size_t offset = 0;
};

/// A note attached to an error, such as "in call to 'f'" with the call's position.
struct ErrorNote {
  SourceRef where;
  std::string message;
};

/// An error in a script: syntax, type, name, argument or a library error raised by a call.
class ScriptError : public std::runtime_error {
 public:
  ScriptError(SourceRef where, const std::string& message)
      : std::runtime_error(message), where_(std::move(where)) {}
  [[nodiscard]] const SourceRef& where() const { return where_; }
  [[nodiscard]] const std::vector<ErrorNote>& notes() const { return notes_; }
  void add_note(ErrorNote note) { notes_.push_back(std::move(note)); }

 private:
  SourceRef where_;
  std::vector<ErrorNote> notes_;
};

/// "file:line:col: error: message\n<source line>\n<caret>\n" plus one
/// "file:line:col: note: ..." line per note.
std::string format_error(const ScriptError& error);

/// Formats one position: "file:line:col: <kind>: message", the line, and a caret under the column.
std::string format_diagnostic(const SourceRef& where, std::string_view kind, std::string_view message);

}  // namespace sculpt::language
