#include "sim_server_options.hpp"

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "bus/lcm_url.hpp"
#include "common/exit_code.hpp"
#include "common/number_text.hpp"
#include "common/untrusted_text.hpp"

namespace tongue::apps {

void print_usage(std::FILE* to) {
  const std::string default_url{bus::kDefaultLcmUrl};
  std::fprintf(
      to,
      "usage: sim_server SCENE.yaml [--mode lockstep|fast|realtime] [--lcm-url URL]\n"
      "                  [--prefix TONGUE_] [--output FILE] [--timeout-ms N] [--silence-s S]\n"
      "                  [--on-silence hold|stop|decay] [--max-steps N]\n"
      "                  [--nodes all|surface|midsagittal|landmarks] [--publish-every K]\n"
      "                  [--controllers N] [--repeat-ms MS] [--repeats N]\n"
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
      "                  naming its own muscles, merged (default 1)\n"
      "  --repeat-ms     lock-step: publish the state again when the next activations are\n"
      "                  this late, ms, then at twice the interval each time, at most\n"
      "                  --timeout-ms apart (default 50; 0: never)\n"
      "  --repeats       lock-step: at most this many repeats of one state (default 10)\n",
      default_url.c_str());
}

namespace {

// Every check ends here, so that each message has the program's name in front.
bool fail(const std::string& message) {
  std::fprintf(stderr, "sim_server: %s\n", message.c_str());
  return false;
}

// One of the words of an enumerated option, and the value it stands for.
template <typename T>
struct Choice {
  std::string_view word;
  T value;
};

template <typename T, std::size_t N>
bool read_choice(const std::string& value, const Choice<T> (&choices)[N], T& out,
                 const std::string& message) {
  for (const Choice<T>& c : choices) {
    if (value == c.word) {
      out = c.value;
      return true;
    }
  }
  return fail(message + ", not " + common::quoted_untrusted(value));
}

// An integer in [min, max], or nullopt after printing message.
std::optional<long long> integer_in(const std::string& value, long long min, long long max,
                                    const std::string& message) {
  const std::optional<long long> v = common::parse_integer(value);
  if (v && *v >= min && *v <= max) return v;
  fail(message);
  return std::nullopt;
}

bool read_mode(const std::string& value, Options& o) {
  using server::Mode;
  static constexpr Choice<Mode> kModes[] = {
      {"lockstep", Mode::lockstep}, {"fast", Mode::fast}, {"realtime", Mode::realtime}};
  return read_choice(value, kModes, o.server.mode, "--mode must be lockstep, fast or realtime");
}

bool read_on_silence(const std::string& value, Options& o) {
  using server::OnSilence;
  static constexpr Choice<OnSilence> kActions[] = {
      {"hold", OnSilence::hold}, {"stop", OnSilence::stop}, {"decay", OnSilence::decay}};
  return read_choice(value, kActions, o.server.on_silence,
                     "--on-silence must be hold, stop or decay");
}

bool read_nodes(const std::string& value, Options& o) {
  using server::Nodes;
  static constexpr Choice<Nodes> kNodes[] = {{"all", Nodes::all},
                                             {"surface", Nodes::surface},
                                             {"midsagittal", Nodes::midsagittal},
                                             {"landmarks", Nodes::landmarks}};
  return read_choice(value, kNodes, o.server.nodes,
                     "--nodes must be all, surface, midsagittal or landmarks");
}

bool read_timeout_ms(const std::string& value, Options& o) {
  const auto n =
      integer_in(value, 1, 3600000, "--timeout-ms must be an integer in [1, 3600000] ms");
  if (n) o.server.timeout_ms = static_cast<int>(*n);
  return n.has_value();
}

bool read_max_steps(const std::string& value, Options& o) {
  const auto n = integer_in(value, 0, std::numeric_limits<long long>::max(),
                            "--max-steps must be an integer >= 0");
  if (n) o.server.max_steps = *n;
  return n.has_value();
}

bool read_silence_s(const std::string& value, Options& o) {
  const std::optional<double> s = common::parse_number(value);
  if (!s || !(*s > 0.0) || *s > 3600.0) return fail("--silence-s must be a number in (0, 3600] s");
  o.server.silence_s = *s;
  return true;
}

bool read_publish_every(const std::string& value, Options& o) {
  const auto n = integer_in(value, 1, 1000000000, "--publish-every must be an integer >= 1");
  if (n) o.server.publish_every = static_cast<int>(*n);
  return n.has_value();
}

bool read_repeat_ms(const std::string& value, Options& o) {
  const auto n = integer_in(value, 0, 60000, "--repeat-ms must be an integer in [0, 60000] ms");
  if (n) o.server.repeat_ms = static_cast<int>(*n);
  return n.has_value();
}

bool read_repeats(const std::string& value, Options& o) {
  const auto n = integer_in(value, 0, 20, "--repeats must be an integer in [0, 20]");
  if (n) o.server.repeats = static_cast<int>(*n);
  return n.has_value();
}

bool read_controllers(const std::string& value, Options& o) {
  const auto n = integer_in(value, 1, 1000000, "--controllers must be an integer in [1, 1000000]");
  if (n) o.server.controllers = static_cast<int>(*n);
  return n.has_value();
}

bool read_url(const std::string& value, Options& o) {
  try {
    bus::parse_lcm_url(value);
  } catch (const std::invalid_argument& e) {
    return fail(std::string("--lcm-url: ") + e.what());
  }
  o.url = value;
  return true;
}

bool read_prefix(const std::string& value, Options& o) {
  if (!bus::is_valid_channel_prefix(value))
    return fail("--prefix " + common::quoted_untrusted(value) + " " +
                std::string(bus::kChannelPrefixRule));
  o.prefix = value;
  return true;
}

// An option whose value is kept as given.
template <auto member>
bool read_text(const std::string& value, Options& o) {
  o.*member = value;
  return true;
}

[[noreturn]] bool print_help(const std::string&, Options&) {
  print_usage(stdout);
  std::exit(common::kExitOk);
}

struct Option {
  std::string_view name;
  bool takes_value;  // the next argument, or the text after '=' in --name=value
  bool (*read)(const std::string& value, Options& o);  // false after printing why
};

constexpr Option kOptions[] = {
    {"--help", false, print_help},
    {"-h", false, print_help},
    {"--mode", true, read_mode},
    {"--lcm-url", true, read_url},
    {"--prefix", true, read_prefix},
    {"--output", true, read_text<&Options::output>},
    {"--timeout-ms", true, read_timeout_ms},
    {"--on-silence", true, read_on_silence},
    {"--max-steps", true, read_max_steps},
    {"--silence-s", true, read_silence_s},
    {"--nodes", true, read_nodes},
    {"--publish-every", true, read_publish_every},
    {"--controllers", true, read_controllers},
    {"--repeat-ms", true, read_repeat_ms},
    {"--repeats", true, read_repeats},
};

const Option* find_option(const std::string& name) {
  for (const Option& option : kOptions)
    if (option.name == name) return &option;
  return nullptr;
}

// An argument that names no option: the scene, given once.
bool read_scene(const std::string& arg, Options& o) {
  if (!arg.empty() && arg[0] == '-') return fail("unknown option '" + arg + "'");
  if (!o.scene_path.empty()) return fail("more than one scene given ('" + arg + "')");
  o.scene_path = arg;
  return true;
}

// Reads argv[i], and argv[i + 1] when it is the value of the option argv[i] names.
bool read_argument(int argc, char** argv, int& i, Options& o) {
  std::string arg = argv[i];
  std::optional<std::string> value;
  if (const auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
    value = arg.substr(eq + 1);
    arg = arg.substr(0, eq);
  }
  const Option* option = find_option(arg);
  if (!option) return read_scene(arg, o);
  if (option->takes_value && !value) {
    if (i + 1 >= argc) return fail(arg + " needs a value");
    value = argv[++i];
  }
  return option->read(value.value_or(""), o);
}

// What no single option can check: the scene's presence and options that need another mode.
bool check_together(const Options& o) {
  using server::Mode;
  if (o.scene_path.empty()) return fail("no scene given");
  if (o.server.mode == Mode::lockstep && o.server.publish_every != 1)
    return fail(
        "--publish-every applies to --mode fast and realtime only (lock-step publishes every "
        "step)");
  if (o.server.mode != Mode::lockstep && o.server.controllers != 1)
    return fail(
        "--controllers applies to --mode lockstep only (fast and realtime hold the latest "
        "activation, whoever sends it)");
  const server::ServerOptions defaults;
  if (o.server.mode != Mode::lockstep &&
      (o.server.repeat_ms != defaults.repeat_ms || o.server.repeats != defaults.repeats))
    return fail(
        "--repeat-ms and --repeats apply to --mode lockstep only (the other modes publish every "
        "step without waiting)");
  if (o.server.mode != Mode::realtime && o.server.on_silence == server::OnSilence::decay)
    return fail("--on-silence decay needs --mode realtime");
  return true;
}

}  // namespace

std::optional<Options> parse_arguments(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i)
    if (!read_argument(argc, argv, i, o)) return std::nullopt;
  if (!check_together(o)) return std::nullopt;
  return o;
}

}  // namespace tongue::apps
