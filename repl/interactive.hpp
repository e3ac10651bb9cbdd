#pragma once
/// \file interactive.hpp
/// The interactive session on a terminal: libedit line editing, history in ~/.sculpt_history,
/// tab completion of names, continuation prompt for unfinished entries.

#include <functional>

#include "language/interpreter.hpp"
#include "view_mode.hpp"

namespace sculpt::repl {

/// The session's live view (`:view`; sculpt --view without a script opens it at the start).
struct SessionViewOptions {
  ViewPort port{};
  bool open = false;  ///< open the view before the first entry
};

/// Runs until :quit or end of input. `setup` prepares the session's interpreter first (the
/// -D bindings); a ScriptError it throws ends the session with code 1. Returns the exit code.
int run_interactive(const std::function<void(language::Interpreter&)>& setup, const SessionViewOptions& view = {});

}  // namespace sculpt::repl
