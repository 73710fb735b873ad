#pragma once
// tongue_viewer's command line: live on a bus, or the replay of one or two run files.
#include <optional>
#include <string>
#include <vector>

namespace tongue::viewer {

struct ViewerOptions {
  std::string lcm_url;                 // live: the bus of the server watched
  std::string prefix;                  // live: its channel prefix
  std::vector<std::string> run_files;  // replay: a run, and perhaps the reference it is compared to
  std::string listen_address = "127.0.0.1";
  unsigned short listen_port = 8080;  // 0: any free port (printed when listening)
  std::string web_dir;                // the page's files
  bool help = false;

  bool replay() const { return !run_files.empty(); }
};

// Throws std::invalid_argument with a one-line reason for a bad command line.
ViewerOptions parse_viewer_options(const std::vector<std::string>& args);

std::string viewer_usage();

}  // namespace tongue::viewer
