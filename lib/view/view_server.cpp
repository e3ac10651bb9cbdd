#include "view/view_server.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <iostream>
#include <thread>

#include "base/errors.hpp"
#include "view/detail/http_session.hpp"
#include "view/detail/hub.hpp"
#include "view/view_errors.hpp"

namespace sculpt::view {

namespace asio = boost::asio;
using asio::ip::tcp;

struct ViewServer::Impl {
  asio::io_context io{1};
  tcp::acceptor acceptor{io};
  std::shared_ptr<detail::Hub> hub = std::make_shared<detail::Hub>();
  std::thread thread;

  void accept() {
    acceptor.async_accept([this](boost::system::error_code ec, tcp::socket socket) {
      if (!acceptor.is_open()) return;
      if (!ec) detail::start_http_session(std::move(socket), hub);
      accept();  // an error on one connection (too many open files, say) does not stop the server
    });
  }

  /// Opens the acceptor on 127.0.0.1:port; false if the port is in use.
  bool bind(int port) {
    boost::system::error_code ec;
    acceptor.open(tcp::v4());
    acceptor.set_option(tcp::acceptor::reuse_address(true));
    acceptor.bind({asio::ip::make_address_v4("127.0.0.1"), static_cast<unsigned short>(port)}, ec);
    if (ec == asio::error::address_in_use) {
      acceptor.close();
      return false;
    }
    if (ec) throw ViewError("cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + ec.message());
    acceptor.listen(asio::socket_base::max_listen_connections);
    return true;
  }
};

ViewServer::ViewServer(const ServerOptions& options) : impl_(std::make_unique<Impl>()) {
  if (options.port < 0 || options.port > 65535)
    throw InvalidInput("view: port " + std::to_string(options.port) + " is not in [0, 65535]");
  if (options.tries < 1) throw InvalidInput("view: tries must be at least 1");
  impl_->hub->site = detail::load_site(detail::three_directory(options.three_dir));
  const int last = options.port == 0 ? 0 : std::min(65535, options.port + options.tries - 1);
  bool bound = false;
  try {
    for (int port = options.port; port <= last && !bound; ++port) bound = impl_->bind(port);
  } catch (const boost::system::system_error& e) {
    throw ViewError(std::string("cannot listen on 127.0.0.1: ") + e.what());
  }
  if (!bound) throw PortInUse(options.port, last);
  impl_->hub->port = impl_->acceptor.local_endpoint().port();
  impl_->accept();
  impl_->thread = std::thread([impl = impl_.get()] {
    while (true) {
      try {
        impl->io.run();
        return;
      } catch (const std::exception& e) {  // a connection's handler failed (out of memory): the others go on
        std::cerr << "sculpt: view: " << e.what() << "\n";
      }
    }
  });
}

ViewServer::~ViewServer() {
  asio::post(impl_->io, [impl = impl_.get()] {
    boost::system::error_code ec;
    impl->acceptor.close(ec);
    impl->io.stop();
  });
  impl_->thread.join();
}

int ViewServer::port() const { return impl_->hub->port; }

std::string ViewServer::url() const { return "http://127.0.0.1:" + std::to_string(port()) + "/"; }

void ViewServer::publish_scene(std::string message) {
  asio::post(impl_->io, [hub = impl_->hub, m = std::make_shared<const std::string>(std::move(message))] {
    hub->publish(true, m);
  });
}

void ViewServer::publish_status(std::string message) {
  asio::post(impl_->io, [hub = impl_->hub, m = std::make_shared<const std::string>(std::move(message))] {
    hub->publish(false, m);
  });
}

int ViewServer::clients() const { return impl_->hub->clients.load(); }

bool ViewServer::depth_wanted() const { return impl_->hub->depth_pages.load() > 0; }

bool ViewServer::take_scene_request() { return impl_->hub->scene_request.exchange(false); }

}  // namespace sculpt::view
