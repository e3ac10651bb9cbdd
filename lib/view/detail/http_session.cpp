#include "view/detail/http_session.hpp"

#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <cctype>
#include <chrono>
#include <optional>
#include <string>

#include "view/detail/websocket_session.hpp"

namespace sculpt::view::detail {
namespace {

namespace beast = boost::beast;
namespace http = boost::beast::http;

std::string_view std_view(beast::string_view s) { return {s.data(), s.size()}; }

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(boost::asio::ip::tcp::socket socket, std::shared_ptr<Hub> hub)
      : stream_(std::move(socket)), hub_(std::move(hub)) {}

  void read() {
    parser_.emplace();
    parser_->header_limit(8 * 1024);
    parser_->body_limit(8 * 1024);
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

 private:
  void on_read(beast::error_code ec) {
    if (ec) {
      stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_both, ec);
      return;
    }
    const auto& request = parser_->get();
    if (!host_allowed(std_view(request[http::field::host]), hub_->port))
      return respond(http::status::forbidden, "text/plain", "sculpt view: refused: unknown Host header\n");
    std::string_view target = std_view(request.target());
    if (const auto query = target.find('?'); query != std::string_view::npos) target = target.substr(0, query);
    if (beast::websocket::is_upgrade(request)) {
      if (target != "/ws") return respond(http::status::not_found, "text/plain", "sculpt view: no such socket\n");
      if (!origin_allowed(std_view(request[http::field::origin]), hub_->port))
        return respond(http::status::forbidden, "text/plain", "sculpt view: refused: foreign Origin\n");
      stream_.expires_never();  // the WebSocket keeps its own timeouts
      std::make_shared<WebSocketSession>(std::move(stream_), hub_)->run(parser_->release());
      return;
    }
    if (request.method() != http::verb::get)
      return respond(http::status::method_not_allowed, "text/plain", "sculpt view: only GET\n");
    if (target == "/" || target == "/index.html")
      return respond(http::status::ok, "text/html; charset=utf-8", hub_->site.page);
    if (auto script = hub_->site.scripts.find(std::string(target)); script != hub_->site.scripts.end())
      return respond(http::status::ok, "application/javascript", script->second);
    respond(http::status::not_found, "text/plain", "sculpt view: not found\n");
  }

  void respond(http::status status, const char* type, const std::string& body) {
    const auto& request = parser_->get();
    response_ = {};
    response_.result(status);
    response_.version(request.version());
    response_.set(http::field::server, "sculpt view");
    response_.set(http::field::content_type, type);
    response_.set(http::field::cache_control, "no-store");
    response_.set("X-Content-Type-Options", "nosniff");
    response_.keep_alive(request.keep_alive() && status == http::status::ok);
    response_.body() = body;
    response_.prepare_payload();
    http::async_write(stream_, response_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return;
      if (!self->response_.keep_alive()) {
        self->stream_.socket().shutdown(boost::asio::ip::tcp::socket::shutdown_send, ec);
        return;
      }
      self->read();
    });
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  http::response<http::string_body> response_;
  std::shared_ptr<Hub> hub_;
};

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

}  // namespace

bool host_allowed(std::string_view host, int port) {
  const std::string suffix = ":" + std::to_string(port);
  return equal_ignoring_case(host, "127.0.0.1" + suffix) || equal_ignoring_case(host, "localhost" + suffix);
}

bool origin_allowed(std::string_view origin, int port) {
  if (origin.empty()) return true;  // not a browser page (a test, a tool on this machine)
  return origin.substr(0, 7) == "http://" && host_allowed(origin.substr(7), port);
}

void start_http_session(boost::asio::ip::tcp::socket socket, std::shared_ptr<Hub> hub) {
  std::make_shared<HttpSession>(std::move(socket), std::move(hub))->read();
}

}  // namespace sculpt::view::detail
