#pragma once
// tongue_viewer as a whole: the web server in front of the live feed from the bus or of the
// replayed run files, until SIGINT or SIGTERM.
#include <cstdio>

#include "viewer/viewer_options.hpp"

namespace tongue::viewer {

// Serves until SIGINT or SIGTERM (then returns kExitInterrupted). Prints where it listens on out
// ("tongue_viewer: serving http://ADDR:PORT/"). Throws std::exception naming the file or address
// when it cannot start (a bad run file, the port in use, the bus not opened).
int run_viewer(const ViewerOptions& options, std::FILE* out);

}  // namespace tongue::viewer
