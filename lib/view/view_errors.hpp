#pragma once
/// \file view_errors.hpp
/// Errors of the live view: the server could not start (its port is taken, three.js is not
/// installed). The message says what to do; the sculpt executable adds its own option names.

#include <stdexcept>
#include <string>

namespace sculpt::view {

/// The view cannot start or serve.
class ViewError : public std::runtime_error {
 public:
  explicit ViewError(const std::string& message) : std::runtime_error(message) {}
};

/// Every port tried is in use by another program (or another view).
class PortInUse : public ViewError {
 public:
  PortInUse(int first, int last)
      : ViewError(first == last
                      ? "port " + std::to_string(first) + " on 127.0.0.1 is in use"
                      : "ports " + std::to_string(first) + " to " + std::to_string(last) + " on 127.0.0.1 are in use"),
        first_(first),
        last_(last) {}
  [[nodiscard]] int first() const { return first_; }
  [[nodiscard]] int last() const { return last_; }

 private:
  int first_;
  int last_;
};

}  // namespace sculpt::view
