#pragma once
/// \file view_server.hpp
/// The live view's server: HTTP and WebSocket on 127.0.0.1 only (Boost.Beast), on a thread of
/// its own. It serves the view's page and Debian's three.js files and nothing else, refuses
/// Host headers other than 127.0.0.1:port and localhost:port, and pushes each published scene
/// and status to every open page (scene_message.hpp). Publishing never waits for a page; a page
/// that closes or a socket that drops ends only its own connection.
///
///     sculpt::view::ViewServer server({.port = 8417});
///     std::cout << server.url() << "\n";             // http://127.0.0.1:8417/
///     server.publish_scene(encode_scene(scene));
///     server.publish_status(encode_status({.ok = true, .run = 1}));

#include <filesystem>
#include <memory>
#include <string>

namespace sculpt::view {

/// The view's port when none is given (sculpt --view, :view).
inline constexpr int kDefaultPort = 8417;

struct ServerOptions {
  int port = kDefaultPort;  ///< 0: a free port the system picks
  int tries = 1;            ///< when the port is in use, also try port + 1, ..., port + tries - 1
  /// The folder of three.js; empty: $SCULPT_THREE_DIR, else /usr/share/javascript/three.
  std::filesystem::path three_dir{};
};

class ViewServer {
 public:
  /// Binds 127.0.0.1 and starts serving.
  /// \throw PortInUse if every port tried is taken; ViewError if three.js is missing or the
  /// socket cannot be opened; InvalidInput for a port outside [0, 65535] or tries < 1.
  explicit ViewServer(const ServerOptions& options = {});
  /// Stops serving and closes every connection.
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  /// The port it listens on.
  [[nodiscard]] int port() const;
  /// http://127.0.0.1:port/
  [[nodiscard]] std::string url() const;
  /// Sends a scene message (binary; encode_scene) to every page and to pages that open later.
  void publish_scene(std::string message);
  /// Sends a status message (text; encode_status) likewise.
  void publish_status(std::string message);
  /// The number of pages connected now.
  [[nodiscard]] int clients() const;
  /// True while an open page is in the depth mode: scenes should then carry the cell depths
  /// (encode_scene with SceneOptions::depth).
  [[nodiscard]] bool depth_wanted() const;
  /// True once after a page entered the depth mode (until the next call): the scene it has lacks
  /// the depths, so the caller should publish the scene again, with them. Any thread.
  [[nodiscard]] bool take_scene_request();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sculpt::view
