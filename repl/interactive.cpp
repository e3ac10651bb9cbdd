#include "interactive.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "language/session.hpp"

#ifdef SCULPT_HAVE_LIBEDIT
#include <editline/readline.h>
#endif

namespace sculpt::repl {
namespace {

constexpr const char* kPrompt = "sculpt> ";
constexpr const char* kContinuation = "   ...> ";

#ifdef SCULPT_HAVE_LIBEDIT
// libedit's completion callbacks are plain C functions: they reach the session through this
// pointer, set for the duration of run_interactive() only.
language::Session* completing_session = nullptr;

char* completion_generator(const char* text, int state) {
  static std::vector<std::string> matches;
  static std::size_t next = 0;
  if (state == 0) {
    matches = completing_session ? completing_session->complete(text) : std::vector<std::string>{};
    next = 0;
  }
  if (next >= matches.size()) return nullptr;
  return strdup(matches[next++].c_str());
}

char** complete(const char* text, int /*start*/, int /*end*/) {
  rl_attempted_completion_over = 1;  // no file-name completion
  return rl_completion_matches(text, completion_generator);
}

std::string history_path() {
  const char* home = std::getenv("HOME");
  return home && *home ? std::string(home) + "/.sculpt_history" : std::string();
}
#endif

}  // namespace

int run_interactive(const std::function<void(language::Interpreter&)>& setup) {
  language::Session session(std::cout, std::cerr);
  try {
    setup(session.interpreter());
  } catch (const language::ScriptError& e) {
    std::cerr << language::format_error(e);
    return 1;
  }
  std::cout << "sculpt " << SCULPT_VERSION << " - :help for help, :quit to leave\n" << std::flush;
#ifdef SCULPT_HAVE_LIBEDIT
  completing_session = &session;
  rl_readline_name = "sculpt";
  rl_attempted_completion_function = complete;
  rl_basic_word_break_characters = const_cast<char*>(" \t\n\"\\'`@$><=;|&{([,+-*/%");
  const std::string history = history_path();
  using_history();
  if (!history.empty()) read_history(history.c_str());
  while (true) {
    char* line = readline(session.continuing() ? kContinuation : kPrompt);
    if (!line) {
      std::cout << "\n";
      break;
    }
    const std::string text(line);
    std::free(line);
    if (text.find_first_not_of(" \t") != std::string::npos) {
      add_history(text.c_str());
      if (!history.empty()) write_history(history.c_str());
    }
    if (!session.feed(text)) break;
  }
  completing_session = nullptr;
#else
  std::string text;
  while (true) {
    std::cout << (session.continuing() ? kContinuation : kPrompt) << std::flush;
    if (!std::getline(std::cin, text)) {
      std::cout << "\n";
      break;
    }
    if (!session.feed(text)) break;
  }
#endif
  return 0;
}

}  // namespace sculpt::repl
