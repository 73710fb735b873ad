#include "viewer/viewer_options.hpp"

#include <charconv>
#include <stdexcept>

#include "bus/channels.hpp"
#include "bus/lcm_url.hpp"
#include "common/untrusted_text.hpp"

#ifndef TONGUE_VIEWER_WEB_DIR
#error "TONGUE_VIEWER_WEB_DIR names the page's folder in the source tree"
#endif

namespace tongue::viewer {
namespace {

// ADDR:PORT, ADDR an IPv4 address or a host name, PORT 0-65535.
void parse_listen(const std::string& text, ViewerOptions& o) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw std::invalid_argument("--listen wants ADDR:PORT, e.g. 127.0.0.1:8080, not " +
                                common::quoted_untrusted(text));
  unsigned port = 0;
  const char* first = text.data() + colon + 1;
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(first, last, port);
  if (first == last || error != std::errc() || end != last || port > 65535)
    throw std::invalid_argument("--listen: the port of " + common::quoted_untrusted(text) +
                                " is not a number in 0-65535");
  o.listen_address = text.substr(0, colon);
  o.listen_port = static_cast<unsigned short>(port);
}

}  // namespace

ViewerOptions parse_viewer_options(const std::vector<std::string>& args) {
  ViewerOptions o;
  o.lcm_url = std::string(bus::kDefaultLcmUrl);
  o.prefix = std::string(bus::kDefaultChannelPrefix);
  o.web_dir = TONGUE_VIEWER_WEB_DIR;
  bool bus_named = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--help" || arg == "-h") {
      o.help = true;
      return o;
    }
    if (arg != "--lcm-url" && arg != "--prefix" && arg != "--run" && arg != "--listen" &&
        arg != "--web")
      throw std::invalid_argument("unexpected argument " + common::quoted_untrusted(arg));
    if (i + 1 >= args.size()) throw std::invalid_argument(arg + " needs a value");
    const std::string& value = args[++i];
    if (arg == "--lcm-url") {
      bus::parse_lcm_url(value);
      o.lcm_url = value;
      bus_named = true;
    } else if (arg == "--prefix") {
      bus::Channels{value};  // throws for a prefix the channels cannot have
      o.prefix = value;
      bus_named = true;
    } else if (arg == "--run") {
      if (o.run_files.size() == 2)
        throw std::invalid_argument(
            "--run at most twice: a run and the reference it is compared to");
      o.run_files.push_back(value);
    } else if (arg == "--listen") {
      parse_listen(value, o);
    } else {
      o.web_dir = value;
    }
  }
  if (bus_named && o.replay())
    throw std::invalid_argument("--run replays files: --lcm-url and --prefix are for live viewing");
  return o;
}

std::string viewer_usage() {
  return "usage: tongue_viewer [--lcm-url URL] [--prefix TONGUE_] [--listen ADDR:PORT] [--web "
         "DIR]\n"
         "       tongue_viewer --run RUN.h5 [--run REFERENCE.h5] [--listen ADDR:PORT] [--web DIR]\n"
         "  Serves a web page showing the tongue in 3D and in the midsagittal plane:\n"
         "  live, the states a sim_server publishes (joining late through describe), or the\n"
         "  frames of one or two run files with a time slider.\n"
         "  --lcm-url  LCM provider URL of the server (default " +
         std::string(bus::kDefaultLcmUrl) +
         ")\n"
         "  --prefix   channel prefix of the server, A-Z 0-9 _ (default TONGUE_)\n"
         "  --run      a run file to replay; twice to compare a run with a reference\n"
         "  --listen   address and port of the page (default 127.0.0.1:8080: this machine only;\n"
         "             0.0.0.0:8080 opens it to the network, see docs/viewer.md); port 0: any "
         "free\n"
         "  --web      folder of the page's files (default the source tree's viewer/web)\n";
}

}  // namespace tongue::viewer
