#pragma once
// The viewer's HTTP and WebSocket server (Boost.Beast on one asio thread): answers GET requests
// through the Routes and, live, upgrades /ws to a WebSocket whose page the LiveHub feeds. Every
// request is bounded (header and body size, idle time) and at most kMaxConnections are served at
// once, so that no client can exhaust the viewer; nothing a client sends reaches the bus.
#include <memory>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "viewer/live_hub.hpp"
#include "viewer/routes.hpp"

namespace tongue::viewer {

class WebServer {
 public:
  // Binds and listens on address:port (port 0: any free one); throws std::runtime_error naming
  // the address when it cannot (e.g. "127.0.0.1:8080: Address already in use").
  WebServer(boost::asio::io_context& io, const std::string& address, unsigned short port,
            const Routes& routes, LiveHub* hub);
  ~WebServer();

  // The port listened on (the one chosen, for port 0).
  unsigned short port() const;
  void start();

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace tongue::viewer
