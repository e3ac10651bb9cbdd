#pragma once
// Runs script text through the interpreter and returns what it printed and the formatted
// error (empty if none), as the sculpt executable would show them.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "language/interpreter.hpp"

namespace sculpt::language::testing {

struct RunResult {
  std::string out;
  std::string error;
  std::string err;  ///< built-ins' summaries and warnings (standard error)
};

inline SourcePtr text_source(const std::string& text, const std::string& name = "t.bsp") {
  auto source = std::make_shared<SourceFile>();
  source->name = name;
  source->text = text;
  return source;
}

inline RunResult run_script(const std::string& text, InterpreterOptions options = {}) {
  std::ostringstream out, err;
  options.out = &out;
  options.err = &err;
  Interpreter interpreter(options);
  RunResult result;
  try {
    interpreter.run(text_source(text));
  } catch (const ScriptError& e) {
    result.error = format_error(e);
  }
  result.out = out.str();
  result.err = err.str();
  return result;
}

/// The first line of the error a script stops with (empty if it runs).
inline std::string first_error_line(const std::string& text) {
  const auto r = run_script(text);
  return r.error.substr(0, r.error.find('\n'));
}

/// Runs `text`, expects no error, and returns the numbers it printed, one per print() argument.
inline std::vector<double> numbers(const std::string& text) {
  const auto r = run_script(text);
  EXPECT_EQ(r.error, "") << text;
  std::vector<double> out;
  std::istringstream in(r.out);
  for (std::string word; in >> word;) out.push_back(std::stod(word));
  return out;
}

}  // namespace sculpt::language::testing
