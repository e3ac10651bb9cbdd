#pragma once
/// \file errors.hpp
/// Typed errors shared by every layer. Each carries what a user needs to act on it;
/// where the error is tied to a position in a text input, it carries that position too,
/// so that the language front end can report `file:line:col: error: message`.

#include <stdexcept>
#include <string>
#include <utility>

namespace sculpt {

/// A position in a text input. `line` and `column` are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  [[nodiscard]] bool known() const { return !file.empty() || line > 0; }
  /// "file:line:col", "file:line" or "file", as much as is known.
  [[nodiscard]] std::string str() const {
    std::string s = file;
    if (line > 0) {
      s.append(":").append(std::to_string(line));
      if (column > 0) s.append(":").append(std::to_string(column));
    }
    return s;
  }
};

/// Input the caller gave is not acceptable (wrong size, NaN, m < 1, ...).
class InvalidInput : public std::invalid_argument {
 public:
  explicit InvalidInput(const std::string& message, SourceLocation where = {})
      : std::invalid_argument(message), where_(std::move(where)) {}
  [[nodiscard]] const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

/// A value lies outside the range the exact kernel can represent (see docs/kernel.md).
class RangeError : public std::out_of_range {
 public:
  explicit RangeError(const std::string& message) : std::out_of_range(message) {}
};

/// A geometric operation cannot be carried out on valid input (open mesh, non-manifold edge, ...).
class GeometryError : public std::domain_error {
 public:
  explicit GeometryError(const std::string& message, SourceLocation where = {})
      : std::domain_error(message), where_(std::move(where)) {}
  [[nodiscard]] const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

/// Reading or writing a file failed; the message names the path.
class IoError : public std::runtime_error {
 public:
  IoError(const std::string& path, const std::string& message)
      : std::runtime_error(path + ": " + message), path_(path) {}
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace sculpt
