#include "controller/command_line.hpp"

#include <algorithm>
#include <stdexcept>

#include "bus/channels.hpp"
#include "bus/lcm_url.hpp"
#include "common/number_text.hpp"
#include "common/untrusted_text.hpp"

namespace tongue::controller {
namespace {

constexpr double kMaxTimeout = 3600.0;  // s; longer waits are a typo, not an experiment

const std::vector<std::string>& common_option_names() {
  static const std::vector<std::string> names = {"--lcm-url", "--prefix", "--mode", "--max-steps",
                                                 "--timeout-s"};
  return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

void set_common(CommonOptions& o, const std::string& name, const std::string& value) {
  if (name == "--lcm-url") {
    try {
      bus::parse_lcm_url(value);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--lcm-url: ") + e.what());
    }
    o.lcm_url = value;
  } else if (name == "--prefix") {
    if (!bus::is_valid_channel_prefix(value))
      throw UsageError("--prefix " + common::quoted_untrusted(value) + " " +
                       std::string(bus::kChannelPrefixRule));
    o.prefix = value;
  } else if (name == "--mode") {
    if (value == "lockstep") {
      o.mode = LoopMode::lockstep;
    } else if (value == "realtime") {
      o.mode = LoopMode::realtime;
    } else {
      throw UsageError("--mode must be lockstep or realtime, not " +
                       common::quoted_untrusted(value));
    }
  } else if (name == "--max-steps") {
    const std::optional<long long> steps = common::parse_integer(value);
    if (!steps || *steps < 0)
      throw UsageError("--max-steps must be an integer >= 0, not '" + value + "'");
    o.max_steps = *steps;
  } else if (name == "--timeout-s") {
    const double s = parse_number(name, value);
    if (!(s > 0.0) || s > kMaxTimeout)
      throw UsageError("--timeout-s must be in (0, 3600] s, not '" + value + "'");
    o.timeout_s = s;
  }
}

}  // namespace

double parse_number(const std::string& option, const std::string& text) {
  const std::optional<double> v = common::parse_number(text);
  if (!v) throw UsageError(option + " must be a number, not '" + text + "'");
  return *v;
}

CommandLine parse_command_line(int argc, const char* const* argv,
                               const std::vector<std::string>& program_options) {
  CommandLine out;
  for (int i = 1; i < argc; ++i) {
    std::string name = argv[i];
    std::optional<std::string> value;
    if (name == "--help" || name == "-h") {
      out.help = true;
      continue;
    }
    if (name.rfind("--", 0) != 0) throw UsageError("unexpected argument '" + name + "'");
    if (const auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const bool common = contains(common_option_names(), name);
    if (!common && !contains(program_options, name))
      throw UsageError("unknown option '" + name + "'");
    if (!value) {
      if (i + 1 >= argc) throw UsageError(name + " needs a value");
      value = argv[++i];
    }
    if (common) {
      set_common(out.common, name, *value);
    } else {
      out.values[name] = *value;
    }
  }
  return out;
}

std::string common_usage() {
  return std::string("  --lcm-url URL     LCM provider (default ") +
         std::string(bus::kDefaultLcmUrl) +
         ")\n"
         "  --prefix P        channel prefix of the server, A-Z 0-9 _ (default TONGUE_)\n"
         "  --mode M          lockstep (default): answer state k with the activation for step\n"
         "                    k+1; realtime: answer each state with step -1 (apply now)\n"
         "  --max-steps N     send nothing for steps beyond N, exit 0 after state N\n"
         "  --timeout-s S     give up (exit 4) after S s without the model or a state\n"
         "                    (default 5)\n";
}

}  // namespace tongue::controller
