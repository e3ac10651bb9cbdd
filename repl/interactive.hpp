#pragma once
/// \file interactive.hpp
/// The interactive session on a terminal: libedit line editing, history in ~/.sculpt_history,
/// tab completion of names, continuation prompt for unfinished entries.

namespace sculpt::repl {

/// Runs until :quit or end of input. Returns the process exit code (0).
int run_interactive();

}  // namespace sculpt::repl
