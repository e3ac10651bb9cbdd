#pragma once
/// \file interactive.hpp
/// The interactive session on a terminal: libedit line editing, history in ~/.sculpt_history,
/// tab completion of names, continuation prompt for unfinished entries.

#include <functional>

#include "language/interpreter.hpp"

namespace sculpt::repl {

/// Runs until :quit or end of input. `setup` prepares the session's interpreter first (the
/// -D bindings); a ScriptError it throws ends the session with code 1. Returns the exit code.
int run_interactive(const std::function<void(language::Interpreter&)>& setup);

}  // namespace sculpt::repl
