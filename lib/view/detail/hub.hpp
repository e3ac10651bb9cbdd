#pragma once
/// \file hub.hpp
/// The state the server's connections share (internal). Everything here is touched on the
/// server's one I/O thread only, except the atomics, which the session's thread reads.

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "view/detail/site.hpp"

namespace sculpt::view::detail {

class WebSocketSession;

struct Hub {
  Site site;
  int port = 0;
  std::shared_ptr<const std::string> scene;   ///< the latest scene message (binary), sent to new pages
  std::shared_ptr<const std::string> status;  ///< the latest status message (text)
  std::vector<std::weak_ptr<WebSocketSession>> sessions;
  std::atomic<int> clients{0};             ///< open WebSocket connections
  std::atomic<int> depth_pages{0};         ///< open pages in the depth mode
  std::atomic<bool> scene_request{false};  ///< a page entered the depth mode since the last take

  /// Sends `message` to every open page and keeps it for pages that connect later.
  void publish(bool binary, std::shared_ptr<const std::string> message);
};

/// True when `host` (a Host header) names this server: 127.0.0.1:port or localhost:port. Any other
/// name is refused, so that a web page elsewhere cannot reach the view through DNS rebinding.
bool host_allowed(std::string_view host, int port);

/// True when `origin` (an Origin header) is empty or this server's own page.
bool origin_allowed(std::string_view origin, int port);

}  // namespace sculpt::view::detail
