#include "view_mode.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <thread>
#include <vector>

#include "base/errors.hpp"
#include "language/source.hpp"
#include "last_solid.hpp"
#include "view/scene.hpp"
#include "view/scene_message.hpp"
#include "view/view_errors.hpp"

namespace sculpt::repl {
namespace {

/// Ports tried after the default one when it is taken (and no --port was given).
constexpr int kDefaultTries = 10;

std::atomic<bool> stop_requested{false};
extern "C" void on_stop(int) { stop_requested.store(true, std::memory_order_relaxed); }

/// What tells that a file changed: it exists, its modification time and its size.
struct Stamp {
  bool exists = false;
  std::filesystem::file_time_type time{};
  std::uintmax_t size = 0;
  bool operator==(const Stamp&) const = default;
};

Stamp stamp_of(const std::string& path) {
  std::error_code ec;
  Stamp s;
  s.time = std::filesystem::last_write_time(path, ec);
  if (ec) return {};
  s.size = std::filesystem::file_size(path, ec);
  s.exists = !ec;
  return s;
}

// Now, in milliseconds since the Unix epoch (the system clock, which the page's Date.now() reads).
double system_milliseconds() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// A key for what the scene of `parts`/`last` is made of: the objects (values are immutable),
/// names and colours, so that an entry that changed nothing sends nothing.
std::string scene_key(const std::vector<language::ShownPart>& parts, const std::optional<language::Value>& last) {
  std::string key;
  auto add_object = [&key](const language::Value& v) {
    key += std::to_string(reinterpret_cast<std::uintptr_t>(v.object<language::Object>())) + ";";
  };
  for (const auto& p : parts) {
    add_object(p.value);
    key += p.name + ";";
    if (p.color)
      key += std::to_string((*p.color)[0]) + "," + std::to_string((*p.color)[1]) + "," + std::to_string((*p.color)[2]);
    key += "|";
  }
  if (parts.empty() && last) add_object(*last);
  return key;
}

}  // namespace

std::unique_ptr<view::ViewServer> start_view_server(const ViewPort& port, std::ostream& err) {
  try {
    return std::make_unique<view::ViewServer>(
        view::ServerOptions{.port = port.port, .tries = port.given ? 1 : kDefaultTries});
  } catch (const view::PortInUse& e) {
    err << "sculpt: --view: " << e.what() << " (another sculpt view, or another program); choose a free port with "
        << "--port N, or --port 0 for any free port\n";
  } catch (const std::exception& e) {
    err << "sculpt: --view: " << e.what() << "\n";
  }
  return nullptr;
}

int run_script_view(const ScriptViewOptions& options) {
  const std::unique_ptr<view::ViewServer> server = start_view_server(options.port, std::cerr);
  if (!server) return 1;
  std::cout << "view: " << server->url() << " (Ctrl-C ends it)" << std::endl;
  stop_requested.store(false);
  struct sigaction action {
  }, previous_interrupt{}, previous_terminate{};
  action.sa_handler = on_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_interrupt);
  sigaction(SIGTERM, &action, &previous_terminate);

  for (long long run = 1; !stop_requested.load(); ++run) {
    std::vector<std::string> watched = {options.script};
    std::vector<Stamp> stamps = {stamp_of(options.script)};
    // Files built-ins read (import, curve(source=), load_spline), stamped when the run ends: a
    // script that exports a file and reads it back does not set itself off again.
    std::vector<std::string> data_files;
    const auto start = std::chrono::steady_clock::now();
    view::Status status{.run = run};
    {
      LastSolid last;
      language::InterpreterOptions interpreter_options;
      interpreter_options.interrupt = &stop_requested;
      interpreter_options.top_level_value = [&last](const language::Value& v) { last.see(v); };
      interpreter_options.included = [&](const std::string& path) {
        watched.push_back(path);
        stamps.push_back(stamp_of(path));
      };
      interpreter_options.file_read = [&](const std::string& path) { data_files.push_back(path); };
      language::Interpreter interpreter(interpreter_options);
      last.interpreter = &interpreter;
      try {
        if (options.setup) options.setup(interpreter);
        interpreter.run(language::load_source(options.script));
        status.script_milliseconds = milliseconds_since(start);
        status.script_end = system_milliseconds();
        const view::Scene scene = view::scene_of(interpreter.shown(), last.get());
        server->publish_scene(view::encode_scene(scene, {.depth = server->depth_wanted()}));
        status.scene_sent = system_milliseconds();
        status.parts = scene.parts.size();
      } catch (const language::ScriptError& e) {
        status.ok = false;
        status.error = language::format_error(e);
      } catch (const std::exception& e) {  // the file cannot be read; a part cannot be sent
        status.ok = false;
        status.error = std::string("sculpt: ") + e.what() + "\n";
      }
    }
    if (stop_requested.load()) break;
    for (const std::string& path : data_files) {
      watched.push_back(path);
      stamps.push_back(stamp_of(path));
    }
    status.milliseconds = milliseconds_since(start);
    server->publish_status(view::encode_status(status));
    std::cout.flush();
    if (status.ok) {
      std::cout << "view: run " << run << ": " << status.parts << (status.parts == 1 ? " part" : " parts") << " in "
                << static_cast<long long>(status.milliseconds) << " ms (the script "
                << static_cast<long long>(status.script_milliseconds) << " ms)" << std::endl;
    } else {
      std::cerr << status.error << std::flush;
    }
    // Wait for a change to any file the run read.
    while (!stop_requested.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      bool changed = server->take_scene_request();  // a page asks for the depths: run again
      for (std::size_t k = 0; k < watched.size() && !changed; ++k) changed = stamp_of(watched[k]) != stamps[k];
      if (changed) break;
    }
  }
  sigaction(SIGINT, &previous_interrupt, nullptr);
  sigaction(SIGTERM, &previous_terminate, nullptr);
  std::cout << "view: stopped" << std::endl;
  return 0;
}

SessionView::SessionView(language::Session& session, ViewPort port, std::ostream& out, std::ostream& err)
    : session_(session), port_(port), out_(out), err_(err) {
  session_.add_command(":view", [this](const std::string&) { start(); });
}

void SessionView::start() {
  if (server_) {
    out_ << "view: " << server_->url() << "\n";
    return;
  }
  server_ = start_view_server(port_, err_);
  if (!server_) return;
  out_ << "view: " << server_->url() << " (open it in a browser; it follows the session)\n";
  sent_key_.clear();
  update();
}

void SessionView::update(const std::string& errors) {
  if (!server_) return;
  const auto& shown = session_.interpreter().shown();
  const std::optional<language::Value> last = shown.empty() ? session_.last_solid() : std::nullopt;
  const bool depth = server_->depth_wanted();
  std::string key = scene_key(shown, last) + (depth ? "depth" : "");
  const bool new_scene = key != sent_key_ || updates_ == 0;
  if (!new_scene && errors.empty() && !showing_error_) return;
  const auto start = std::chrono::steady_clock::now();
  view::Status status{.ok = errors.empty(), .error = errors, .run = ++updates_};
  if (new_scene) {
    try {
      const view::Scene scene = view::scene_of(shown, last);
      server_->publish_scene(view::encode_scene(scene, {.depth = depth}));
      status.parts = scene.parts.size();
    } catch (const std::exception& e) {
      status.ok = false;
      status.error += std::string("view: ") + e.what() + "\n";
      err_ << "view: " << e.what() << "\n";
    }
    sent_key_ = std::move(key);
  }
  status.milliseconds = milliseconds_since(start);
  server_->publish_status(view::encode_status(status));
  showing_error_ = !status.ok;
}

int TeeBuffer::overflow(int c) {
  if (c == traits_type::eof()) return traits_type::not_eof(c);
  if (copy_.size() < (64u << 10)) copy_ += static_cast<char>(c);
  return target_->sputc(static_cast<char>(c));
}

std::streamsize TeeBuffer::xsputn(const char* text, std::streamsize n) {
  if (copy_.size() < (64u << 10)) copy_.append(text, static_cast<std::size_t>(n));
  return target_->sputn(text, n);
}

}  // namespace sculpt::repl
