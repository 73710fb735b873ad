#include "experiment_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "bus/channels.hpp"

namespace tongue::runner {
namespace {

namespace fs = std::filesystem;

// Reads one YAML map, refusing keys it was not told about, so that a typo is an error.
class Reader {
 public:
  Reader(std::string file, const YAML::Node& map, std::string path, std::set<std::string> keys)
      : file_(std::move(file)), map_(map), path_(std::move(path)) {
    if (!map_.IsMap()) fail("", "must be a map");
    for (const auto& entry : map_) {
      const std::string key = entry.first.as<std::string>();
      if (!keys.count(key)) fail(key, "unknown key");
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    const std::string full = path_.empty() ? key : (key.empty() ? path_ : path_ + "." + key);
    throw ExperimentError(file_, full, reason);
  }
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  bool has(const std::string& key) const { return static_cast<bool>(map_[key]); }
  YAML::Node node(const std::string& key) const { return map_[key]; }

  template <typename T>
  T get(const std::string& key, const char* what) const {
    if (!has(key)) fail(key, "required");
    try {
      return map_[key].as<T>();
    } catch (const YAML::Exception&) {
      fail(key, std::string("must be ") + what);
    }
  }
  template <typename T>
  T get(const std::string& key, const char* what, T fallback) const {
    return has(key) ? get<T>(key, what) : fallback;
  }

 private:
  std::string file_;
  YAML::Node map_;
  std::string path_;
};

bool is_plain_name(const std::string& s) {
  if (s.empty()) return false;
  for (const char c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  }
  return true;
}

}  // namespace

Experiment read_experiment(const fs::path& path) {
  Experiment e;
  std::error_code ec;
  e.file = fs::absolute(path, ec).lexically_normal();
  const std::string file = path.string();
  if (!fs::is_regular_file(e.file)) throw ExperimentError(file, "", "no such file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(e.file.string());
  } catch (const YAML::Exception& ex) {
    throw ExperimentError(
        file, "",
        "YAML syntax error: " + ex.msg + " (line " + std::to_string(ex.mark.line + 1) + ")");
  }
  const Reader top(
      file, root, "",
      {"name", "scene", "duration", "bus", "server", "controllers", "lcm_log", "plots", "timeout"});

  e.name = top.get<std::string>("name", "a name");
  if (!is_plain_name(e.name)) top.fail("name", "must be made of A-Z a-z 0-9 _ -");
  e.scene = (e.folder() / top.get<std::string>("scene", "a path")).lexically_normal();
  if (!fs::is_regular_file(e.scene)) top.fail("scene", "no such file: " + e.scene.string());
  e.duration = top.get<double>("duration", "a number of seconds");
  if (!(e.duration > 0.0) || !std::isfinite(e.duration)) top.fail("duration", "must be > 0 s");
  e.timeout = top.get<double>("timeout", "a number of seconds", e.timeout);
  if (!(e.timeout > 0.0) || !std::isfinite(e.timeout)) top.fail("timeout", "must be > 0 s");
  e.lcm_log = top.get<bool>("lcm_log", "true or false", e.lcm_log);

  if (top.has("bus")) {
    const Reader bus(file, top.node("bus"), "bus", {"port", "prefix"});
    e.port = bus.get<int>("port", "an integer", e.port);
    if (e.port < 1024 || e.port > 65535) bus.fail("port", "must be in [1024, 65535]");
    e.prefix = bus.get<std::string>("prefix", "a string", e.prefix);
    if (!bus::is_valid_channel_prefix(e.prefix)) bus.fail("prefix", "must be UPPER_SNAKE");
  }
  if (top.has("server")) {
    const Reader server(file, top.node("server"), "server", {"mode", "args"});
    e.server_mode = server.get<std::string>("mode", "a string", e.server_mode);
    if (e.server_mode != "lockstep" && e.server_mode != "realtime") {
      server.fail("mode", "must be lockstep or realtime");
    }
    e.server_args = server.get<std::vector<std::string>>("args", "a list of strings", {});
  }
  if (top.has("plots")) {
    const Reader plots(file, top.node("plots"), "plots", {"times"});
    e.plot_times = plots.get<std::vector<double>>("times", "a list of seconds", {});
    for (const double t : e.plot_times) {
      if (!(t >= 0.0) || t > e.duration) plots.fail("times", "must lie in [0, duration]");
    }
  }

  const YAML::Node list = top.node("controllers");
  if (!list || !list.IsSequence() || list.size() == 0) {
    top.fail("controllers", "must list at least one controller");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Reader c(file, list[i], "controllers[" + std::to_string(i) + "]",
                   {"name", "program", "args"});
    ProcessSpec spec;
    spec.name = c.get<std::string>("name", "a name");
    if (!is_plain_name(spec.name)) c.fail("name", "must be made of A-Z a-z 0-9 _ -");
    if (spec.name == "sim_server" || spec.name == "lcm-logger" || !names.insert(spec.name).second) {
      c.fail("name", "'" + spec.name + "' is already taken");
    }
    spec.program = c.get<std::string>("program", "a program name or path");
    spec.args = c.get<std::vector<std::string>>("args", "a list of strings", {});
    e.controllers.push_back(std::move(spec));
  }
  return e;
}

}  // namespace tongue::runner
