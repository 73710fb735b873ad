// sim_server SCENE.yaml [--mode lockstep|fast|realtime] [--lcm-url URL] [--prefix TONGUE_]
//            [--output FILE] [--timeout-ms N] [--silence-s S] [--on-silence hold|stop|decay]
//            [--max-steps N] [--nodes all|surface|midsagittal|landmarks] [--publish-every K]
//            [--controllers N]
//
// Runs a dynamic scene with muscles on the LCM bus (server/server_loop.hpp): publishes the model
// and the state of step 0, then advances under activation messages (lock-step: one step per
// activation tagged with the next step, or per N of them merged with --controllers N; fast:
// free-running with the latest activation; realtime: as fast, paced to the wall clock, overruns
// counted), logging every step to the run file when one is given (--output or the scene's
// output.file).
//
// Exit status (common/exit_code.hpp): 0 shutdown command or --max-steps reached; 1 bad command
// line, scene error (e.g. a mesh without the sets --nodes needs), bus or I/O error; 2 a step failed
// to converge even after cuts (its state is published with converged = false; the run file keeps
// the accepted steps); 3 silence with --on-silence stop (lock-step or realtime); 130 SIGINT or
// SIGTERM (the run file is closed with status "interrupted").
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>

#include "bus/channels.hpp"
#include "bus/lcm_server_bus.hpp"
#include "common/exit_code.hpp"
#include "common/interrupt.hpp"
#include "common/number_text.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "server/server_loop.hpp"

namespace tongue::apps {
namespace {

using common::kExitError;
const std::string kDefaultUrl{bus::kDefaultLcmUrl};

struct Options {
  std::string scene_path;
  std::string url = kDefaultUrl;
  std::string prefix{bus::kDefaultChannelPrefix};
  std::optional<std::string> output;
  server::ServerOptions server;
};

void print_usage(std::FILE* to) {
  std::fprintf(
      to,
      "usage: sim_server SCENE.yaml [--mode lockstep|fast|realtime] [--lcm-url URL]\n"
      "                  [--prefix TONGUE_] [--output FILE] [--timeout-ms N] [--silence-s S]\n"
      "                  [--on-silence hold|stop|decay] [--max-steps N]\n"
      "                  [--nodes all|surface|midsagittal|landmarks] [--publish-every K]\n"
      "                  [--controllers N]\n"
      "  --mode          lockstep (default): step k+1 when the activation tagged k+1 arrives;\n"
      "                  fast: free-running, latest activation held;\n"
      "                  realtime: as fast, one step per dt of wall-clock time\n"
      "  --lcm-url       LCM provider URL (default %s)\n"
      "  --prefix        channel prefix, A-Z 0-9 _ (default TONGUE_)\n"
      "  --output FILE   run file (overrides the scene's output.file)\n"
      "  --timeout-ms    lock-step silence before a report, ms (default 1000)\n"
      "  --silence-s     realtime silence before --on-silence acts, s (default 0.5)\n"
      "  --on-silence    hold (default: keep waiting / keep the activation), stop (exit 3),\n"
      "                  decay (realtime only: all activations to 0)\n"
      "  --max-steps     end (exit 0) once this step is reached\n"
      "  --nodes         nodes the states carry: all (default), surface, midsagittal, landmarks\n"
      "  --publish-every fast and realtime: publish the state every K steps (default 1)\n"
      "  --controllers   lock-step: step k+1 once N activations tagged k+1 have arrived, each\n"
      "                  naming its own muscles, merged (default 1)\n",
      kDefaultUrl.c_str());
}

bool parse_integer(const std::string& text, long long& out) {
  const std::optional<long long> v = common::parse_integer(text);
  if (v) out = *v;
  return v.has_value();
}

bool parse_number(const std::string& text, double& out) {
  const std::optional<double> v = common::parse_number(text);
  if (v) out = *v;
  return v.has_value();
}

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

std::optional<Options> parse_arguments(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    std::optional<std::string> value;
    if (const auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
    }
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      std::exit(common::kExitOk);
    }
    const bool takes_value = arg == "--mode" || arg == "--lcm-url" || arg == "--prefix" ||
                             arg == "--output" || arg == "--timeout-ms" || arg == "--on-silence" ||
                             arg == "--max-steps" || arg == "--silence-s" || arg == "--nodes" ||
                             arg == "--publish-every" || arg == "--controllers";
    if (takes_value && !value) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "sim_server: %s needs a value\n", arg.c_str());
        return std::nullopt;
      }
      value = argv[++i];
    }
    long long number = 0;
    if (arg == "--mode") {
      if (*value == "lockstep") {
        o.server.mode = server::Mode::lockstep;
      } else if (*value == "fast") {
        o.server.mode = server::Mode::fast;
      } else if (*value == "realtime") {
        o.server.mode = server::Mode::realtime;
      } else {
        std::fprintf(stderr, "sim_server: --mode must be lockstep, fast or realtime, not '%s'\n",
                     value->c_str());
        return std::nullopt;
      }
    } else if (arg == "--lcm-url") {
      o.url = *value;
    } else if (arg == "--prefix") {
      o.prefix = *value;
    } else if (arg == "--output") {
      o.output = *value;
    } else if (arg == "--timeout-ms") {
      if (!parse_integer(*value, number) || number <= 0 || number > 3600000) {
        std::fprintf(stderr, "sim_server: --timeout-ms must be an integer in [1, 3600000] ms\n");
        return std::nullopt;
      }
      o.server.timeout_ms = static_cast<int>(number);
    } else if (arg == "--on-silence") {
      if (*value == "hold") {
        o.server.on_silence = server::OnSilence::hold;
      } else if (*value == "stop") {
        o.server.on_silence = server::OnSilence::stop;
      } else if (*value == "decay") {
        o.server.on_silence = server::OnSilence::decay;
      } else {
        std::fprintf(stderr, "sim_server: --on-silence must be hold, stop or decay, not '%s'\n",
                     value->c_str());
        return std::nullopt;
      }
    } else if (arg == "--max-steps") {
      if (!parse_integer(*value, number) || number < 0) {
        std::fprintf(stderr, "sim_server: --max-steps must be an integer >= 0\n");
        return std::nullopt;
      }
      o.server.max_steps = number;
    } else if (arg == "--silence-s") {
      double seconds = 0.0;
      if (!parse_number(*value, seconds) || !(seconds > 0.0) || seconds > 3600.0) {
        std::fprintf(stderr, "sim_server: --silence-s must be a number in (0, 3600] s\n");
        return std::nullopt;
      }
      o.server.silence_s = seconds;
    } else if (arg == "--nodes") {
      if (*value == "all") {
        o.server.nodes = server::Nodes::all;
      } else if (*value == "surface") {
        o.server.nodes = server::Nodes::surface;
      } else if (*value == "midsagittal") {
        o.server.nodes = server::Nodes::midsagittal;
      } else if (*value == "landmarks") {
        o.server.nodes = server::Nodes::landmarks;
      } else {
        std::fprintf(stderr,
                     "sim_server: --nodes must be all, surface, midsagittal or landmarks, not "
                     "'%s'\n",
                     value->c_str());
        return std::nullopt;
      }
    } else if (arg == "--publish-every") {
      if (!parse_integer(*value, number) || number < 1 || number > 1000000000) {
        std::fprintf(stderr, "sim_server: --publish-every must be an integer >= 1\n");
        return std::nullopt;
      }
      o.server.publish_every = static_cast<int>(number);
    } else if (arg == "--controllers") {
      if (!parse_integer(*value, number) || number < 1 || number > 1000000) {
        std::fprintf(stderr, "sim_server: --controllers must be an integer in [1, 1000000]\n");
        return std::nullopt;
      }
      o.server.controllers = static_cast<int>(number);
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "sim_server: unknown option '%s'\n", arg.c_str());
      return std::nullopt;
    } else if (o.scene_path.empty()) {
      o.scene_path = arg;
    } else {
      std::fprintf(stderr, "sim_server: more than one scene given ('%s')\n", arg.c_str());
      return std::nullopt;
    }
  }
  if (o.scene_path.empty()) {
    std::fprintf(stderr, "sim_server: no scene given\n");
    return std::nullopt;
  }
  if (o.server.mode == server::Mode::lockstep && o.server.publish_every != 1) {
    std::fprintf(stderr,
                 "sim_server: --publish-every applies to --mode fast and realtime only (lock-step "
                 "publishes every step)\n");
    return std::nullopt;
  }
  if (o.server.mode != server::Mode::lockstep && o.server.controllers != 1) {
    std::fprintf(stderr,
                 "sim_server: --controllers applies to --mode lockstep only (fast and realtime "
                 "hold the latest activation, whoever sends it)\n");
    return std::nullopt;
  }
  if (o.server.mode != server::Mode::realtime && o.server.on_silence == server::OnSilence::decay) {
    std::fprintf(stderr, "sim_server: --on-silence decay needs --mode realtime\n");
    return std::nullopt;
  }
  return o;
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
    bus::LcmServerBus bus(options->url, channels);
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
    return static_cast<int>(loop.run());
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
