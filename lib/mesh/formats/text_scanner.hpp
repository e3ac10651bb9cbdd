#pragma once
/// \file text_scanner.hpp
/// Line and token scanning with line numbers for the text mesh formats (internal).
/// Numbers are parsed with std::from_chars: correctly rounded, locale independent.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "base/errors.hpp"

namespace sculpt::mesh::detail {

class TextScanner {
 public:
  TextScanner(std::string_view data, std::string name) : data_(data), name_(std::move(name)) {}

  /// Advances to the next line that has a token (comments start with `comment`, 0 = none);
  /// false at the end of the data. The line's tokens are then in tokens().
  bool next_line(char comment = '#') {
    while (pos_ < data_.size()) {
      size_t end = data_.find('\n', pos_);
      if (end == std::string_view::npos) end = data_.size();
      std::string_view line = data_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_no_;
      if (comment) line = line.substr(0, line.find(comment));
      split(line);
      if (!tokens_.empty()) return true;
    }
    tokens_.clear();
    return false;
  }

  [[nodiscard]] const std::vector<std::string_view>& tokens() const { return tokens_; }
  [[nodiscard]] int line() const { return line_no_; }
  /// Byte offset just after the current line.
  [[nodiscard]] size_t offset() const { return std::min(pos_, data_.size()); }

  [[noreturn]] void fail(const std::string& message) const { fail_at(line_no_, message); }
  [[noreturn]] void fail_at(int line, const std::string& message) const {
    throw IoError(name_, "line " + std::to_string(line) + ": " + message);
  }

  /// Token `i` of the current line as a finite double (what: for the message).
  [[nodiscard]] double real(size_t i, const char* what) const {
    if (i >= tokens_.size()) fail(std::string("missing ") + what);
    std::string_view t = tokens_[i];
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    double value = 0;
    const auto res = std::from_chars(t.data(), t.data() + t.size(), value);
    if (res.ec == std::errc::result_out_of_range)
      fail(std::string(what) + " '" + std::string(tokens_[i]) + "' is out of the double range");
    if (res.ec != std::errc() || res.ptr != t.data() + t.size() || !std::isfinite(value))
      fail(std::string("expected a finite number for ") + what + ", got '" +
           std::string(tokens_[i]) + "'");
    return value;
  }

  /// Token `i` (or the leading digits of it, when `prefix_ok`) as an integer.
  [[nodiscard]] long long integer(size_t i, const char* what, bool prefix_ok = false) const {
    if (i >= tokens_.size()) fail(std::string("missing ") + what);
    return parse_integer(tokens_[i], what, prefix_ok);
  }

  [[nodiscard]] long long parse_integer(std::string_view t, const char* what,
                                        bool prefix_ok = false) const {
    std::string_view s = t;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    long long value = 0;
    const auto res = std::from_chars(s.data(), s.data() + s.size(), value);
    if (res.ec != std::errc() || (!prefix_ok && res.ptr != s.data() + s.size()))
      fail(std::string("expected an integer for ") + what + ", got '" + std::string(t) + "'");
    return value;
  }

 private:
  void split(std::string_view line) {
    tokens_.clear();
    size_t i = 0;
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; };
    while (i < line.size()) {
      while (i < line.size() && space(line[i])) ++i;
      size_t j = i;
      while (j < line.size() && !space(line[j])) ++j;
      if (j > i) tokens_.push_back(line.substr(i, j - i));
      i = j;
    }
  }

  std::string_view data_;
  std::string name_;
  size_t pos_ = 0;
  int line_no_ = 0;
  std::vector<std::string_view> tokens_;
};

/// Shortest decimal text that reads back as exactly `x` (std::to_chars).
inline void append_number(std::string& out, double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, res.ptr);
}

inline void append_number(std::string& out, long long x) {
  char buf[24];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, res.ptr);
}

/// One face as text, as OFF and ASCII PLY both write it: the corner count, then the indices.
inline void append_face_line(std::string& out, const std::vector<int>& face) {
  append_number(out, static_cast<long long>(face.size()));
  for (int v : face) {
    out += ' ';
    append_number(out, static_cast<long long>(v));
  }
  out += '\n';
}

}  // namespace sculpt::mesh::detail
