#include "viewer/viewer.hpp"

#include <csignal>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>

#include "common/exit_code.hpp"
#include "viewer/live_feed.hpp"
#include "viewer/live_hub.hpp"
#include "viewer/routes.hpp"
#include "viewer/run_replay.hpp"
#include "viewer/web_server.hpp"

namespace tongue::viewer {

int run_viewer(const ViewerOptions& o, std::FILE* out) {
  if (!std::filesystem::is_regular_file(std::filesystem::path(o.web_dir) / "index.html"))
    throw std::runtime_error("the page's folder " + o.web_dir + " has no index.html (--web)");
  // Destroyed in reverse: the feed's thread stops before the hub and the io_context go.
  boost::asio::io_context io;
  std::unique_ptr<RunReplay> replay;
  std::unique_ptr<LiveHub> hub;
  if (o.replay()) {
    replay = std::make_unique<RunReplay>(o.run_files);
  } else {
    hub = std::make_unique<LiveHub>(o.lcm_url, o.prefix);
  }
  const Routes routes(o.web_dir, replay.get(), hub.get());
  WebServer server(io, o.listen_address, o.listen_port, routes, hub.get());
  std::unique_ptr<LiveFeed> feed;
  if (hub) {
    // The feed's thread hands its news to the server's thread, which alone touches the hub.
    feed = std::make_unique<LiveFeed>(o.lcm_url, o.prefix, [&io, h = hub.get()](LiveUpdate u) {
      boost::asio::post(io, [h, u = std::move(u)] { h->update(u); });
    });
  }
  int status = common::kExitOk;
  boost::asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code& ec, int) {
    if (ec) return;
    status = common::kExitInterrupted;
    io.stop();
  });
  server.start();
  std::fprintf(out, "tongue_viewer: serving http://%s:%u/\n", o.listen_address.c_str(),
               static_cast<unsigned>(server.port()));
  std::fflush(out);
  io.run();
  return status;
}

}  // namespace tongue::viewer
