#include "language/source.hpp"

#include <algorithm>

namespace sculpt::language {

std::pair<int, int> SourceFile::line_column(std::size_t offset) const {
  offset = std::min(offset, text.size());
  int line = first_line;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return {line, static_cast<int>(offset - line_start) + 1};
}

std::string_view SourceFile::line_text(std::size_t offset) const {
  offset = std::min(offset, text.size());
  std::size_t begin = offset == 0 ? std::string::npos : text.rfind('\n', offset - 1);
  begin = begin == std::string::npos ? 0 : begin + 1;
  std::size_t end = text.find('\n', offset);
  if (end == std::string::npos) end = text.size();
  std::string_view line(text.data() + begin, end - begin);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

std::string format_diagnostic(const SourceRef& where, std::string_view kind, std::string_view message) {
  std::string out;
  if (!where.source) {
    out.append(kind).append(": ").append(message).append("\n");
    return out;
  }
  const auto [line, column] = where.source->line_column(where.offset);
  out += where.source->name + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
  out.append(kind).append(": ").append(message).append("\n");
  std::string_view text = where.source->line_text(where.offset);
  int caret = column;
  // Very long lines show a window around the column.
  constexpr int kWindow = 70;
  if (static_cast<int>(text.size()) > 2 * kWindow + 10) {
    const int begin = std::max(0, column - 1 - kWindow);
    const std::string_view shown = text.substr(static_cast<std::size_t>(begin), 2 * kWindow);
    const bool cut_left = begin > 0;
    const bool cut_right = begin + static_cast<int>(shown.size()) < static_cast<int>(text.size());
    out.append(cut_left ? "..." : "").append(shown).append(cut_right ? "..." : "").append("\n");
    caret = column - begin + (cut_left ? 3 : 0);
    text = shown;
    for (int i = 0; i + 1 < caret; ++i) out += ' ';
    out += "^\n";
    return out;
  }
  out.append(text).append("\n");
  // The caret keeps the line's tabs so that it lines up in a terminal.
  for (int i = 0; i + 1 < caret && i < static_cast<int>(text.size()); ++i) out += text[i] == '\t' ? '\t' : ' ';
  out += "^\n";
  return out;
}

std::string format_error(const ScriptError& error) {
  std::string out = format_diagnostic(error.where(), "error", error.what());
  for (const ErrorNote& note : error.notes()) {
    if (!note.where.source) {
      out += "note: " + note.message + "\n";
      continue;
    }
    const auto [line, column] = note.where.source->line_column(note.where.offset);
    out += note.where.source->name + ":" + std::to_string(line) + ":" + std::to_string(column) +
           ": note: " + note.message + "\n";
  }
  return out;
}

}  // namespace sculpt::language
