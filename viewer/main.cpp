// tongue_viewer: the tongue in a web browser, live or replayed (docs/viewer.md).
//
// Exit status (common/exit_code.hpp): 130 after SIGINT or SIGTERM; 1 for a bad command line, a
// bad run file, an address it cannot listen on or a bus it cannot open.
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/exit_code.hpp"
#include "viewer/viewer.hpp"
#include "viewer/viewer_options.hpp"

int main(int argc, char** argv) {
  using namespace tongue;
  viewer::ViewerOptions options;
  try {
    options = viewer::parse_viewer_options(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "tongue_viewer: %s\n%s", e.what(), viewer::viewer_usage().c_str());
    return common::kExitError;
  }
  if (options.help) {
    std::fputs(viewer::viewer_usage().c_str(), stdout);
    return common::kExitOk;
  }
  try {
    return viewer::run_viewer(options, stdout);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tongue_viewer: %s\n", e.what());
    return common::kExitError;
  }
}
