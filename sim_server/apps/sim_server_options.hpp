#pragma once
// sim_server's command line: what it sets, how each option is checked, and the usage text.
#include <cstdio>
#include <optional>
#include <string>

#include "bus/channels.hpp"
#include "server/server_options.hpp"

namespace tongue::apps {

struct Options {
  std::string scene_path;
  std::string url{bus::kDefaultLcmUrl};
  std::string prefix{bus::kDefaultChannelPrefix};
  std::optional<std::string> output;  // overrides the scene's output.file
  server::ServerOptions server;
};

void print_usage(std::FILE* to);

// --help prints the usage and exits 0; a bad command line returns nullopt after printing why.
std::optional<Options> parse_arguments(int argc, char** argv);

}  // namespace tongue::apps
