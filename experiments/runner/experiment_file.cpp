#include "experiment_file.hpp"

#include <cctype>
#include <cmath>
#include <set>

#include "bus/channels.hpp"
#include "common/yaml_reader.hpp"

namespace tongue::runner {
namespace {

namespace fs = std::filesystem;
using common::child_path;
using common::index_path;
using common::present;
using common::YamlReader;

bool is_plain_name(const std::string& s) {
  if (s.empty()) return false;
  for (const char c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  }
  return true;
}

// A name of the run's files: [A-Za-z0-9_-].
std::string plain_name(const YamlReader& y, const YAML::Node& n, const std::string& path) {
  const std::string name = y.text(n, path);
  if (!is_plain_name(name)) y.fail(path, "must be made of A-Z a-z 0-9 _ -", n);
  return name;
}

}  // namespace

Experiment read_experiment(const fs::path& path) {
  Experiment e;
  std::error_code ec;
  e.file = fs::absolute(path, ec).lexically_normal();
  const YamlReader y = YamlReader::load(path.string());
  const YAML::Node& top = y.root();
  y.expect_map(top, "(top level)");
  y.check_keys(
      top, "",
      {"name", "scene", "duration", "bus", "server", "controllers", "lcm_log", "plots", "timeout"});

  e.name = plain_name(y, y.required(top, "", "name"), "name");
  const YAML::Node scene = y.required(top, "", "scene");
  e.scene = (e.folder() / y.text(scene, "scene")).lexically_normal();
  if (!fs::is_regular_file(e.scene)) y.fail("scene", "no such file: " + e.scene.string(), scene);
  e.duration = y.positive(y.required(top, "", "duration"), "duration", "s");
  if (const auto t = top["timeout"]; present(t)) e.timeout = y.positive(t, "timeout", "s");
  if (const auto l = top["lcm_log"]; present(l)) e.lcm_log = y.boolean(l, "lcm_log");

  if (const auto bus = top["bus"]; present(bus)) {
    y.expect_map(bus, "bus");
    y.check_keys(bus, "bus", {"port", "prefix"});
    if (const auto p = bus["port"]; present(p)) {
      e.port = y.integer(p, "bus.port");
      if (e.port < 1024 || e.port > 65535) y.fail("bus.port", "must be in [1024, 65535]", p);
    }
    if (const auto p = bus["prefix"]; present(p)) {
      e.prefix = y.text(p, "bus.prefix");
      if (!bus::is_valid_channel_prefix(e.prefix)) y.fail("bus.prefix", "must be UPPER_SNAKE", p);
    }
  }
  if (const auto server = top["server"]; present(server)) {
    y.expect_map(server, "server");
    y.check_keys(server, "server", {"mode", "args"});
    if (const auto m = server["mode"]; present(m)) {
      e.server_mode = y.text(m, "server.mode");
      if (e.server_mode != "lockstep" && e.server_mode != "realtime")
        y.fail("server.mode", "must be lockstep or realtime", m);
    }
    if (const auto a = server["args"]; present(a)) e.server_args = y.texts(a, "server.args");
  }
  if (const auto plots = top["plots"]; present(plots)) {
    y.expect_map(plots, "plots");
    y.check_keys(plots, "plots", {"times"});
    if (const auto t = plots["times"]; present(t)) {
      e.plot_times = y.numbers(t, "plots.times", 0);
      for (const double time : e.plot_times) {
        if (!(time >= 0.0) || time > e.duration)
          y.fail("plots.times", "must lie in [0, duration]", t);
      }
    }
  }

  const YAML::Node list = top["controllers"];
  if (!list.IsSequence() || list.size() == 0)
    y.fail("controllers", "must list at least one controller", present(list) ? list : top);
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node c = list[i];
    const std::string c_path = index_path("controllers", i);
    y.expect_map(c, c_path);
    y.check_keys(c, c_path, {"name", "program", "args"});
    ProcessSpec spec;
    const YAML::Node name = y.required(c, c_path, "name");
    spec.name = plain_name(y, name, child_path(c_path, "name"));
    if (spec.name == "sim_server" || spec.name == "lcm-logger" || !names.insert(spec.name).second)
      y.fail(child_path(c_path, "name"), "'" + spec.name + "' is already taken", name);
    spec.program = y.text(y.required(c, c_path, "program"), child_path(c_path, "program"));
    if (const auto a = c["args"]; present(a)) spec.args = y.texts(a, child_path(c_path, "args"));
    e.controllers.push_back(std::move(spec));
  }
  return e;
}

}  // namespace tongue::runner
