#include "interactive.hpp"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "base/cancel.hpp"
#include "language/session.hpp"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>

#ifdef SCULPT_HAVE_LIBEDIT
#include <editline/readline.h>
#include <poll.h>
#endif

namespace sculpt::repl {
namespace {

/// The terminal's width in columns (`:help` wraps to it, read anew at each entry: the window may
/// have been resized), or 0 when standard output is not a terminal.
std::size_t terminal_width() {
  winsize size{};
  if (::isatty(STDOUT_FILENO) && ::ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0) return size.ws_col;
  return 0;
}

constexpr const char* kPrompt = "sculpt> ";
constexpr const char* kContinuation = "   ...> ";

// Ctrl-C: the handler only raises this flag and the library's cancellation request. At a prompt
// the line editor returns (the handler is installed without SA_RESTART) and the unfinished entry
// is dropped; while an entry runs, the interpreter stops at its next step, and a long built-in at
// its next cancellation check, with "interrupted". Either way the session goes on.
std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the flag is set from a signal handler");

// The kernel hands a process's SIGINT to any thread that does not block it: a worker of the
// parallel library or the memory watch may take it while the main thread waits for keys, which
// the signal then does not interrupt. So the handler also writes a byte here, and the wait for
// keys watches the other end (the self-pipe trick; both ends non-blocking).
int interrupt_pipe[2] = {-1, -1};

extern "C" void on_interrupt(int) {
  const int saved = errno;
  interrupted.store(true, std::memory_order_relaxed);
  sculpt::request_cancel();  // long library work stops too (base/cancel.hpp)
  if (interrupt_pipe[1] >= 0) {
    const char byte = 1;
    [[maybe_unused]] const ssize_t written = ::write(interrupt_pipe[1], &byte, 1);  // full: one is there
  }
  errno = saved;
}

struct InterruptHandler {
  struct sigaction previous {};
  InterruptHandler() {
    if (::pipe2(interrupt_pipe, O_NONBLOCK | O_CLOEXEC) != 0) interrupt_pipe[0] = interrupt_pipe[1] = -1;
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;  // no SA_RESTART: a blocking read returns EINTR
    sigaction(SIGINT, &action, &previous);
  }
  ~InterruptHandler() {
    sigaction(SIGINT, &previous, nullptr);
    for (int& end : interrupt_pipe)
      if (end >= 0) ::close(end), end = -1;
  }
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;
};

/// After Ctrl-C at a prompt: drop the unfinished entry and say so.
void cancel_entry(language::Session& session) {
  interrupted.store(false);
  sculpt::clear_cancel();
  session.discard_pending();
  std::cout << "^C (entry cancelled)\n" << std::flush;
}

#ifdef SCULPT_HAVE_LIBEDIT
// libedit's completion callbacks are plain C functions: they reach the session through this
// pointer, set for the duration of run_interactive() only.
language::Session* completing_session = nullptr;
std::string completing_before;  // the line before the word being completed

char* completion_generator(const char* text, int state) {
  static std::vector<std::string> matches;
  static std::size_t next = 0;
  if (state == 0) {
    matches = completing_session ? completing_session->complete(text, completing_before) : std::vector<std::string>{};
    next = 0;
  }
  if (next >= matches.size()) return nullptr;
  return strdup(matches[next++].c_str());
}

char** complete(const char* text, int start, int /*end*/) {
  rl_attempted_completion_over = 1;  // no file-name completion
  // Inside a call's parentheses the function's parameter names are offered (`segments=`).
  completing_before.assign(rl_line_buffer ? rl_line_buffer : "", 0, static_cast<std::size_t>(std::max(start, 0)));
  rl_completion_append_character = '\0';
  return rl_completion_matches(text, completion_generator);
}

/// libedit's character source. A Ctrl-C that arrives before libedit blocks in read() would be
/// lost (the read would not be interrupted), so SIGINT stays blocked except inside ppoll(),
/// which unblocks it atomically while waiting, and which also wakes when another thread took the
/// signal (interrupt_pipe); a raised flag ends the line as end of input.
int read_key(FILE* in) {
  sigset_t interrupt_only, previous;
  sigemptyset(&interrupt_only);
  sigaddset(&interrupt_only, SIGINT);
  sigprocmask(SIG_BLOCK, &interrupt_only, &previous);
  sigset_t waiting = previous;
  sigdelset(&waiting, SIGINT);
  const int fd = fileno(in);
  int key = EOF;
  while (!interrupted.load()) {
    pollfd p[2] = {{fd, POLLIN, 0}, {interrupt_pipe[0], POLLIN, 0}};
    const int ready = ppoll(p, interrupt_pipe[0] >= 0 ? 2 : 1, nullptr, &waiting);
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) break;
    if ((p[1].revents & POLLIN) != 0) {  // a SIGINT (maybe taken by another thread, maybe an old one)
      char bytes[64];
      while (::read(interrupt_pipe[0], bytes, sizeof bytes) > 0) {}
      continue;  // the loop's condition decides
    }
    unsigned char c = 0;
    const ssize_t n = read(fd, &c, 1);
    if (n == 1) key = c;
    if (n < 0 && errno == EINTR) continue;
    break;
  }
  sigprocmask(SIG_SETMASK, &previous, nullptr);
  return key;
}

std::string history_path() {
  const char* home = std::getenv("HOME");
  return home && *home ? std::string(home) + "/.sculpt_history" : std::string();
}
#endif

}  // namespace

int run_interactive(const std::function<void(language::Interpreter&)>& setup, const SessionViewOptions& view_options) {
  // Error messages go to the terminal and, as the page's error panel, to the view.
  TeeBuffer errors(std::cerr.rdbuf());
  std::ostream error_stream(&errors);
  language::Session session(std::cout, error_stream, &interrupted);
  SessionView view(session, view_options.port, std::cout, std::cerr);
  try {
    setup(session.interpreter());
  } catch (const language::ScriptError& e) {
    std::cerr << language::format_error(e);
    return 1;
  }
  std::cout << "sculpt " << SCULPT_VERSION << " - :help for help, :quit to leave\n" << std::flush;
  if (view_options.open) view.start();
  const InterruptHandler handler;
#ifdef SCULPT_HAVE_LIBEDIT
  completing_session = &session;
  rl_readline_name = "sculpt";
  rl_attempted_completion_function = complete;
  rl_getc_function = read_key;
  rl_basic_word_break_characters = const_cast<char*>(" \t\n\"\\'`@$><=;|&{([,+-*/%");
  const std::string history = history_path();
  using_history();
  if (!history.empty()) read_history(history.c_str());
  while (true) {
    interrupted.store(false);
    sculpt::clear_cancel();
    char* line = readline(session.continuing() ? kContinuation : kPrompt);
    if (interrupted.load()) {
      std::free(line);
      cancel_entry(session);
      continue;
    }
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
    session.set_width(terminal_width());
    if (!session.feed(text)) break;
    view.update(errors.take());
  }
  completing_session = nullptr;
#else
  std::string text;
  while (true) {
    interrupted.store(false);
    sculpt::clear_cancel();
    std::cout << (session.continuing() ? kContinuation : kPrompt) << std::flush;
    const bool got = static_cast<bool>(std::getline(std::cin, text));
    if (interrupted.load()) {
      std::cin.clear();
      cancel_entry(session);
      continue;
    }
    if (!got) {
      std::cout << "\n";
      break;
    }
    session.set_width(terminal_width());
    if (!session.feed(text)) break;
    view.update(errors.take());
  }
#endif
  return 0;
}

}  // namespace sculpt::repl
