#include "view/detail/websocket_session.hpp"

#include <boost/asio/buffer.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>

namespace sculpt::view::detail {

namespace beast = boost::beast;
namespace websocket = boost::beast::websocket;

WebSocketSession::WebSocketSession(beast::tcp_stream stream, std::shared_ptr<Hub> hub)
    : ws_(std::move(stream)), hub_(std::move(hub)) {}

WebSocketSession::~WebSocketSession() {
  if (open_) --hub_->clients;
  if (depth_) --hub_->depth_pages;
}

void WebSocketSession::run(beast::http::request<beast::http::string_body> request) {
  // The page sends only its mode: pings (answered by the browser itself) keep a quiet connection
  // open, and a page that has gone without closing (a machine asleep, a cable out) is dropped
  // after 30 s.
  auto timeout = websocket::stream_base::timeout::suggested(beast::role_type::server);
  timeout.idle_timeout = std::chrono::seconds(30);
  timeout.keep_alive_pings = true;
  ws_.set_option(timeout);
  ws_.read_message_max(4096);  // the page sends a few bytes; refuse anything large
  // A scene goes out as one frame in one gathered write: fragments of write_buffer_bytes (4 kB by
  // default) cost a write each, 0.5-1 s for a million triangles' 26 MB.
  ws_.auto_fragment(false);
  ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
}

void WebSocketSession::on_accept(beast::error_code ec) {
  if (ec) return;
  open_ = true;
  ++hub_->clients;
  hub_->sessions.push_back(weak_from_this());
  if (hub_->scene) send(true, hub_->scene);
  if (hub_->status) send(false, hub_->status);
  read();
}

void WebSocketSession::read() {
  ws_.async_read(incoming_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
    if (ec) return;  // closed or dropped: the pending operations end and the session with them
    const auto data = self->incoming_.cdata();
    if (self->ws_.got_text()) self->on_message(std::string_view(static_cast<const char*>(data.data()), data.size()));
    self->incoming_.consume(self->incoming_.size());
    self->read();
  });
}

void WebSocketSession::on_message(std::string_view text) {
  if (text == "depth:1") set_depth(true);
  if (text == "depth:0") set_depth(false);
}

void WebSocketSession::set_depth(bool wanted) {
  if (wanted == depth_) return;
  depth_ = wanted;
  if (wanted) {
    ++hub_->depth_pages;
    hub_->scene_request = true;  // the scene on the page has no depths yet
  } else {
    --hub_->depth_pages;
  }
}

void WebSocketSession::send(bool binary, std::shared_ptr<const std::string> message) {
  // Drop a queued message of the same kind that has not started: only the newest matters.
  for (auto it = queue_.begin() + (writing_ ? 1 : 0); it != queue_.end();) {
    it = it->binary == binary ? queue_.erase(it) : it + 1;
  }
  queue_.push_back({binary, std::move(message)});
  if (!writing_) write_next();
}

void WebSocketSession::write_next() {
  if (queue_.empty()) return;
  writing_ = true;
  ws_.binary(queue_.front().binary);
  ws_.async_write(boost::asio::buffer(*queue_.front().data),
                  [self = shared_from_this()](beast::error_code ec, std::size_t) {
                    self->writing_ = false;
                    if (ec) {
                      self->queue_.clear();
                      return;
                    }
                    self->queue_.pop_front();
                    self->write_next();
                  });
}

void Hub::publish(bool binary, std::shared_ptr<const std::string> message) {
  (binary ? scene : status) = message;
  std::erase_if(sessions, [](const std::weak_ptr<WebSocketSession>& s) { return s.expired(); });
  for (const auto& weak : sessions)
    if (auto session = weak.lock()) session->send(binary, message);
}

}  // namespace sculpt::view::detail
