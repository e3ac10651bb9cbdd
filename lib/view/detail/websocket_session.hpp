#pragma once
/// \file websocket_session.hpp
/// One page's WebSocket (internal): gets the latest scene and status when it opens, then every
/// new one. Writes never wait for each other: a message not yet started is replaced by a newer
/// one of its kind, so a slow or stalled page holds at most one scene besides the one in flight,
/// and it never stalls the session that publishes. A dropped page ends only its own connection.

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/websocket/stream.hpp>
#include <deque>
#include <memory>
#include <string>
#include <string_view>

#include "view/detail/hub.hpp"

namespace sculpt::view::detail {

class WebSocketSession : public std::enable_shared_from_this<WebSocketSession> {
 public:
  WebSocketSession(boost::beast::tcp_stream stream, std::shared_ptr<Hub> hub);
  ~WebSocketSession();
  /// Completes the upgrade `request` (already checked) and starts reading and writing.
  void run(boost::beast::http::request<boost::beast::http::string_body> request);
  /// Queues `message` (on the I/O thread).
  void send(bool binary, std::shared_ptr<const std::string> message);

 private:
  struct Outgoing {
    bool binary;
    std::shared_ptr<const std::string> data;
  };
  void on_accept(boost::beast::error_code ec);
  void read();
  /// Acts on a message from the page ("depth:1", "depth:0"; anything else is ignored).
  void on_message(std::string_view text);
  void set_depth(bool wanted);
  void write_next();

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  std::shared_ptr<Hub> hub_;
  boost::beast::flat_buffer incoming_;
  std::deque<Outgoing> queue_;
  bool writing_ = false;
  bool open_ = false;
  bool depth_ = false;  ///< the page is in the depth mode
};

}  // namespace sculpt::view::detail
