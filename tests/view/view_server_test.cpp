// The view's server (lib/view/view_server.hpp) from a client on this machine: the page, the
// three.js files, refusals (foreign Host, unknown path, other methods), the WebSocket's scene and
// status, pages that drop, a port in use, three.js missing.
#include "view/view_server.hpp"

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <thread>

#include "base/errors.hpp"
#include "view/scene_message.hpp"
#include "view/view_errors.hpp"

namespace sculpt::view {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;
using asio::ip::tcp;

struct Reply {
  unsigned status = 0;
  std::string type;
  std::string body;
};

Reply request(int port, const std::string& target, const std::string& host, http::verb verb = http::verb::get) {
  asio::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)));
  http::request<http::string_body> req(verb, target, 11);
  req.set(http::field::host, host);
  http::write(stream, req);
  beast::flat_buffer buffer;
  http::response<http::string_body> res;
  http::read(stream, buffer, res);
  return {static_cast<unsigned>(res.result_int()), std::string(res[http::field::content_type]), res.body()};
}

std::string local(int port) { return "127.0.0.1:" + std::to_string(port); }

TEST(ViewServer, ServesThePageAndThreeJs) {
  ViewServer server({.port = 0});
  ASSERT_GT(server.port(), 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
  const Reply page = request(server.port(), "/", local(server.port()));
  EXPECT_EQ(page.status, 200u);
  EXPECT_EQ(page.type, "text/html; charset=utf-8");
  EXPECT_NE(page.body.find("/three/three.min.js"), std::string::npos);
  EXPECT_NE(page.body.find("new WebSocket"), std::string::npos);
  const Reply three = request(server.port(), "/three/three.min.js", "localhost:" + std::to_string(server.port()));
  EXPECT_EQ(three.status, 200u);
  EXPECT_GT(three.body.size(), 100000u);
  EXPECT_EQ(request(server.port(), "/three/OrbitControls.js", local(server.port())).status, 200u);
}

TEST(ViewServer, RefusesForeignHostsUnknownPathsAndOtherMethods) {
  ViewServer server({.port = 0});
  const int port = server.port();
  EXPECT_EQ(request(port, "/", "evil.example:" + std::to_string(port)).status, 403u);
  EXPECT_EQ(request(port, "/", "127.0.0.1:" + std::to_string(port + 1)).status, 403u);
  EXPECT_EQ(request(port, "/", "127.0.0.1").status, 403u);
  EXPECT_EQ(request(port, "/etc/passwd", local(port)).status, 404u);
  EXPECT_EQ(request(port, "/three/../../../etc/passwd", local(port)).status, 404u);
  EXPECT_EQ(request(port, "/three/GLTFLoader.js", local(port)).status, 404u);
  EXPECT_EQ(request(port, "/", local(port), http::verb::post).status, 405u);
  EXPECT_EQ(request(port, "/?x=1", local(port)).status, 200u);
}

/// A WebSocket client of the view.
struct Page {
  asio::io_context io;
  websocket::stream<beast::tcp_stream> ws{io};
  explicit Page(int port, const std::string& host = "") {
    beast::get_lowest_layer(ws).connect(
        tcp::endpoint(asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)));
    beast::get_lowest_layer(ws).expires_after(std::chrono::seconds(10));
    ws.handshake(host.empty() ? local(port) : host, "/ws");
  }
  /// The next message and whether it was binary.
  std::pair<std::string, bool> next() {
    beast::flat_buffer buffer;
    ws.read(buffer);
    return {beast::buffers_to_string(buffer.data()), ws.got_binary()};
  }
};

TEST(ViewServer, WebSocketGetsTheLatestSceneThenEveryNewOne) {
  ViewServer server({.port = 0});
  server.publish_scene(encode_scene({}));
  server.publish_status(encode_status({.ok = true, .run = 1}));
  Page page(server.port());
  auto [scene, binary] = page.next();
  EXPECT_TRUE(binary);
  EXPECT_EQ(scene.substr(0, 4), "SCLV");
  auto [status, status_binary] = page.next();
  EXPECT_FALSE(status_binary);
  EXPECT_NE(status.find("\"run\":1"), std::string::npos);
  server.publish_status(encode_status({.ok = false, .error = "x.bsp:1:1: error: boom", .run = 2}));
  auto [error, error_binary] = page.next();
  EXPECT_FALSE(error_binary);
  EXPECT_NE(error.find("boom"), std::string::npos);
  EXPECT_EQ(server.clients(), 1);
}

/// Calls `condition()` until it holds, for up to 2 s; whether it did.
template <typename Condition>
bool eventually(Condition condition) {
  for (int k = 0; k < 100; ++k) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST(ViewServer, PagesInTheDepthModeAskForTheDepths) {
  ViewServer server({.port = 0});
  EXPECT_FALSE(server.depth_wanted());
  EXPECT_FALSE(server.take_scene_request());
  Page a(server.port()), b(server.port());
  a.ws.text(true);
  a.ws.write(asio::buffer(std::string("depth:1")));
  EXPECT_TRUE(eventually([&] { return server.depth_wanted(); }));
  EXPECT_TRUE(server.take_scene_request());  // once: the scene sent lacks the depths
  EXPECT_FALSE(server.take_scene_request());
  b.ws.text(true);
  b.ws.write(asio::buffer(std::string("something else")));  // ignored
  b.ws.write(asio::buffer(std::string("depth:1")));
  EXPECT_TRUE(eventually([&] { return server.take_scene_request(); }));
  a.ws.write(asio::buffer(std::string("depth:0")));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_TRUE(server.depth_wanted()) << "page b still is in the depth mode";
  beast::get_lowest_layer(b.ws).socket().close();  // a page that drops leaves the mode
  EXPECT_TRUE(eventually([&] { return !server.depth_wanted(); }));
  EXPECT_FALSE(server.take_scene_request());
}

TEST(ViewServer, WebSocketRefusesForeignHost) {
  ViewServer server({.port = 0});
  EXPECT_THROW(Page(server.port(), "evil.example:" + std::to_string(server.port())), boost::system::system_error);
}

TEST(ViewServer, DroppedPagesDoNotStopIt) {
  ViewServer server({.port = 0});
  {
    Page page(server.port());
    server.publish_scene(encode_scene({}));
    (void)page.next();
    beast::get_lowest_layer(page.ws).socket().close();  // no close handshake: a dropped socket
  }
  for (int k = 0; k < 50; ++k) server.publish_scene(encode_scene({}));  // into the void, never blocking
  Page again(server.port());
  EXPECT_EQ(again.next().first.substr(0, 4), "SCLV");
  EXPECT_EQ(request(server.port(), "/", local(server.port())).status, 200u);
  // The dropped page is noticed (its read fails) and forgotten.
  for (int k = 0; k < 100 && server.clients() != 1; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(server.clients(), 1);
}

TEST(ViewServer, PortInUseSaysSoAndFallsBack) {
  ViewServer first({.port = 0});
  EXPECT_THROW(ViewServer({.port = first.port()}), PortInUse);
  try {
    ViewServer again({.port = first.port()});
  } catch (const PortInUse& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(first.port()) + " on 127.0.0.1 is in use"), std::string::npos);
  }
  if (first.port() < 65535) {
    ViewServer next({.port = first.port(), .tries = 2});
    EXPECT_NE(next.port(), first.port());
  }
}

TEST(ViewServer, MissingThreeJsIsAClearError) {
  try {
    ViewServer server({.port = 0, .three_dir = "/nonexistent/three"});
    FAIL() << "expected ViewError";
  } catch (const ViewError& e) {
    EXPECT_NE(std::string(e.what()).find("libjs-three"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ViewServer({.port = 70000}), InvalidInput);
}

}  // namespace
}  // namespace sculpt::view
