#pragma once
/// \file http_session.hpp
/// One HTTP connection to the view's server (internal): serves the page at "/" and the three.js
/// files at "/three/...", hands a WebSocket upgrade at "/ws" to a WebSocketSession, and refuses
/// everything else: a Host other than 127.0.0.1:port or localhost:port (403), another method
/// (405), another path (404), requests larger than a few KiB.

#include <boost/asio/ip/tcp.hpp>
#include <memory>

#include "view/detail/hub.hpp"

namespace sculpt::view::detail {

/// Starts serving `socket` on the server's I/O thread; the connection keeps itself alive.
void start_http_session(boost::asio::ip::tcp::socket socket, std::shared_ptr<Hub> hub);

}  // namespace sculpt::view::detail
