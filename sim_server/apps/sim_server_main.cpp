// sim_server SCENE.yaml [--mode lockstep|fast|realtime] [--lcm-url URL] [--prefix TONGUE_]
//            [--output FILE] [--timeout-ms N] [--silence-s S] [--on-silence hold|stop|decay]
//            [--max-steps N] [--nodes all|surface|midsagittal|landmarks] [--publish-every K]
//            [--controllers N] [--repeat-ms MS] [--repeats N]
//
// Runs a dynamic scene with muscles on the LCM bus (server/server_loop.hpp): publishes the model
// and the state of step 0, then advances under activation messages (lock-step: one step per
// activation tagged with the next step, or per N of them merged with --controllers N, the state
// published again while they are late (--repeat-ms, --repeats) so that a lost datagram is
// recovered; fast: free-running with the latest activation; realtime: as fast, paced to the wall
// clock, overruns counted), logging every step to the run file when one is given (--output or
// the scene's output.file).
//
// Exit status (common/exit_code.hpp): 0 shutdown command or --max-steps reached; 1 bad command
// line, scene error (e.g. a mesh without the sets --nodes needs), bus or I/O error; 2 a step failed
// to converge even after cuts (its state is published with converged = false; the run file keeps
// the accepted steps); 3 silence with --on-silence stop (lock-step or realtime); 130 SIGINT or
// SIGTERM (the run file is closed with status "interrupted").
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "bus/channels.hpp"
#include "bus/lcm_server_bus.hpp"
#include "bus/receive_limits.hpp"
#include "common/exit_code.hpp"
#include "common/interrupt.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "server/server_loop.hpp"
#include "sim_server_options.hpp"

namespace tongue::apps {
namespace {

using common::kExitError;

const char* mode_name(server::Mode mode) {
  switch (mode) {
    case server::Mode::lockstep:
      return "lock-step";
    case server::Mode::fast:
      return "fast";
    case server::Mode::realtime:
      return "real-time";
  }
  return "?";
}

int run(int argc, char** argv) {
  std::optional<Options> options = parse_arguments(argc, argv);
  if (!options) {
    print_usage(stderr);
    return kExitError;
  }
  try {
    const bus::Channels channels(options->prefix);
    const scene::Scene scene = scene::read_scene(options->scene_path);
    scene::BuiltScene built = scene::build_scene(scene);
    options->server.output = options->output ? *options->output : scene.output.file;
    const common::InterruptHandlers interrupt;
    std::vector<std::string> muscles;
    if (built.muscles)
      for (const auto& m : built.muscles->muscles()) muscles.push_back(m.name);
    bus::LcmServerBus bus(options->url, channels, bus::activation_limit(muscles));
    server::ServerLoop loop(scene, std::move(built), bus, options->server,
                            [&interrupt] { return interrupt.raised(); });
    const std::string controllers =
        options->server.controllers == 1
            ? ""
            : " (" + std::to_string(options->server.controllers) + " controllers)";
    std::fprintf(stderr, "sim_server: %s, %s mode%s, bus %s, channels %s*, run file %s\n",
                 options->scene_path.c_str(), mode_name(options->server.mode), controllers.c_str(),
                 options->url.c_str(), options->prefix.c_str(),
                 options->server.output.empty() ? "none" : options->server.output.c_str());
    const int status = static_cast<int>(loop.run());
    if (const bus::DropCounts d = bus.drops(); d.total() > 0)
      std::fprintf(stderr,
                   "sim_server: bus: dropped %lld oversize messages, %lld bad datagrams, %lld bad "
                   "fragments, %lld incomplete messages\n",
                   static_cast<long long>(d.oversize), static_cast<long long>(d.not_lcm),
                   static_cast<long long>(d.bad_fragment), static_cast<long long>(d.incomplete));
    return status;
  } catch (const scene::SceneError& e) {
    std::fprintf(stderr, "sim_server: scene error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sim_server: error: %s\n", e.what());
  }
  return kExitError;
}

}  // namespace
}  // namespace tongue::apps

int main(int argc, char** argv) {
  return tongue::apps::run(argc, argv);
}
