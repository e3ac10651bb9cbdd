#pragma once
/// \file view_mode.hpp
/// sculpt --view: the live view of a script (runs it again whenever it, a file it includes or a
/// file a built-in of it reads changes) and of the interactive session (:view). docs/viewing.md.

#include <functional>
#include <iosfwd>
#include <memory>
#include <streambuf>
#include <string>
#include <utility>

#include "language/interpreter.hpp"
#include "language/session.hpp"
#include "view/view_server.hpp"

namespace sculpt::repl {

/// The port the user asked for (--port N), or the default with a few fallbacks.
struct ViewPort {
  int port = view::kDefaultPort;
  bool given = false;  ///< --port N: exactly that port (0: any free one), no fallback
};

/// Starts the server, or prints why not to `err` (naming --port when the port is taken) and
/// returns null.
std::unique_ptr<view::ViewServer> start_view_server(const ViewPort& port, std::ostream& err);

struct ScriptViewOptions {
  std::string script{};  ///< the .bsp file
  ViewPort port{};
  /// Prepares each run's interpreter (grid, -D bindings) before the script runs.
  std::function<void(language::Interpreter&)> setup{};
};

/// Runs `options.script`, serves its view and runs it again on every change (polled every
/// 100 ms) until Ctrl-C. Returns the exit code: 0 after Ctrl-C, 1 if the server cannot start.
int run_script_view(const ScriptViewOptions& options);

/// The interactive session's view: `:view` starts it; after each entry the page shows what the
/// session showed (show()) or else its last solid.
class SessionView {
 public:
  SessionView(language::Session& session, ViewPort port, std::ostream& out, std::ostream& err);
  /// Starts the server unless it runs (`:view` does this).
  void start();
  /// Sends the scene to the page if it changed since the last one sent, and the entry's error
  /// messages (empty: none) as the page's error panel (call after each entry).
  void update(const std::string& errors = {});

 private:
  language::Session& session_;
  ViewPort port_;
  std::ostream& out_;
  std::ostream& err_;
  std::unique_ptr<view::ViewServer> server_;
  std::string sent_key_;  ///< what the last scene sent was made of
  long long updates_ = 0;
  bool showing_error_ = false;
};

/// A stream buffer that passes everything on to `target` and keeps a copy (at most 64 KiB) until
/// take(): the session's error messages, for its view.
class TeeBuffer : public std::streambuf {
 public:
  explicit TeeBuffer(std::streambuf* target) : target_(target) {}
  /// What was written since the last take().
  std::string take() { return std::exchange(copy_, {}); }

 protected:
  int overflow(int c) override;
  std::streamsize xsputn(const char* text, std::streamsize n) override;
  int sync() override { return target_->pubsync(); }

 private:
  std::streambuf* target_;
  std::string copy_;
};

}  // namespace sculpt::repl
