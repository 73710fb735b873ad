// The Python side of BusClient (bus_client.hpp) and the messages it hands out: states and the
// model as read-only objects whose arrays are NumPy arrays in SI units. The waits release the GIL
// and look for Python's signals (Ctrl-C) every 50 ms at most.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Python.h>

#include "controller/muscle_selection.hpp"
#include "python/bindings.hpp"
#include "python/bus_client.hpp"

namespace py = pybind11;

namespace tongue::python {
namespace {

using controller::CommonOptions;
using controller::LoopMode;
using controller::Model;
using controller::MuscleLevels;
using controller::State;

// values as an array of rows of `columns` (one axis when columns is 0).
template <typename T>
py::array_t<T> array(const std::vector<T>& values, std::size_t columns = 0) {
  if (columns == 0) return py::array_t<T>(values.size(), values.data());
  return py::array_t<T>({values.size() / columns, columns}, values.data());
}

// A wait on the bus without the GIL, asking Python for its signals between the slices; a
// signal's exception (KeyboardInterrupt) ends the session ("stopped by KeyboardInterrupt") and
// is raised once the wait is over.
class PythonWait {
 public:
  PythonWait()
      : stop_([this]() -> std::optional<std::string> {
          py::gil_scoped_acquire gil;
          if (PyErr_CheckSignals() == 0) return std::nullopt;
          PyErr_Fetch(&type_, &value_, &trace_);
          return "stopped by " + std::string(py::str(py::handle(type_).attr("__name__")));
        }) {}
  const controller::ControlSession::StopCheck& stop() const { return stop_; }
  // Raises the signal's exception, if one came (with the GIL held).
  void raise_pending() {
    if (type_ == nullptr) return;
    PyErr_Restore(type_, value_, trace_);
    type_ = value_ = trace_ = nullptr;
    throw py::error_already_set();
  }

 private:
  controller::ControlSession::StopCheck stop_;
  PyObject* type_ = nullptr;
  PyObject* value_ = nullptr;
  PyObject* trace_ = nullptr;
};

CommonOptions make_options(std::optional<std::string> lcm_url, std::optional<std::string> prefix,
                           const std::string& mode, std::optional<std::int64_t> max_steps,
                           double timeout_s) {
  // Through the command line, so that every value is checked as the C++ controllers check it.
  std::vector<std::string> args{"--mode", mode, "--timeout-s", py::str(py::float_(timeout_s))};
  if (lcm_url) args.insert(args.end(), {"--lcm-url", *lcm_url});
  if (prefix) args.insert(args.end(), {"--prefix", *prefix});
  if (max_steps) args.insert(args.end(), {"--max-steps", std::to_string(*max_steps)});
  return parse_controller_command_line(args, {}).common;
}

// A dict of muscle or group names (controller/muscle_selection.hpp; a later name overrides an
// earlier one for the muscles both select) or every muscle's level in model order, as the
// muscles named in model order.
MuscleLevels to_levels(const py::handle& levels, const Model& model) {
  const std::vector<std::string>& muscles = model.muscle_names;
  std::vector<std::optional<double>> chosen(muscles.size());
  if (py::isinstance<py::dict>(levels)) {
    for (const auto& [key, level] : levels.cast<py::dict>()) {
      const std::string name = key.cast<std::string>();
      const std::vector<int> selected = controller::select_muscles(name, muscles);
      if (selected.empty())
        throw py::value_error("levels: '" + name + "' is no muscle or group of the model (" +
                              controller::joined_names(muscles) + ")");
      for (int i : selected) chosen[i] = level.cast<double>();
    }
  } else {
    const std::vector<double> all = levels.cast<std::vector<double>>();
    if (all.size() != muscles.size())
      throw py::value_error("levels: " + std::to_string(all.size()) + " values for " +
                            std::to_string(muscles.size()) + " muscles");
    chosen.assign(all.begin(), all.end());
  }
  MuscleLevels out;
  for (std::size_t i = 0; i < muscles.size(); ++i)
    if (chosen[i]) {
      out.names.push_back(muscles[i]);
      out.levels.push_back(*chosen[i]);
    }
  return out;
}

std::string mode_name(LoopMode mode) {
  return mode == LoopMode::lockstep ? "lockstep" : "realtime";
}

void require_mode(const BusClient& client, LoopMode mode) {
  if (client.options().mode != mode)
    throw py::value_error("the client runs in " + mode_name(client.options().mode) + " mode, not " +
                          mode_name(mode) + " (ControllerOptions(mode=...))");
}

// A failure of the bus (LCM, or a state that does not fit the model) ends the session with exit
// code 1, as it ends a C++ controller; the caller's misuse (a state not answered) is raised.
template <typename F>
auto guarded(BusClient& client, F call) -> decltype(call()) {
  try {
    return call();
  } catch (const std::logic_error&) {
    throw;
  } catch (const std::exception& e) {
    client.fail(e.what());
    return {};
  }
}

}  // namespace

void bind_bus_client(py::module_& m) {
  py::register_exception<controller::UsageError>(m, "UsageError", PyExc_ValueError);

  py::class_<CommonOptions>(m, "ControllerOptions",
                            "The options every controller shares (as on the C++ controllers' "
                            "command line).")
      .def(py::init(&make_options), py::arg("lcm_url") = py::none(), py::arg("prefix") = py::none(),
           py::arg("mode") = "lockstep", py::arg("max_steps") = py::none(),
           py::arg("timeout_s") = 5.0,
           "lcm_url: the LCM provider (default: the server's); prefix: the server's channel "
           "prefix; mode: 'lockstep' (the server waits for each answer) or 'realtime' (it does "
           "not); max_steps: end after this step's state; timeout_s: give up when the model or a "
           "state does not come within this many seconds. UsageError (a ValueError) for a bad "
           "value.")
      .def_readonly("lcm_url", &CommonOptions::lcm_url)
      .def_readonly("prefix", &CommonOptions::prefix)
      .def_property_readonly("mode", [](const CommonOptions& o) { return mode_name(o.mode); })
      .def_readonly("max_steps", &CommonOptions::max_steps)
      .def_readonly("timeout_s", &CommonOptions::timeout_s, "[s]");

  m.def(
      "parse_controller_command_line",
      [](const std::vector<std::string>& args, const std::vector<std::string>& options) {
        controller::CommandLine line = parse_controller_command_line(args, options);
        return py::make_tuple(line.common, line.values, line.help);
      },
      py::arg("args"), py::arg("options") = std::vector<std::string>{},
      "The controllers' command line: the common options (--lcm-url, --prefix, --mode, "
      "--max-steps, --timeout-s) and the program's own `options` (e.g. ['--plan']), each taking "
      "one value. Returns (ControllerOptions, {option: value}, help). UsageError for an unknown "
      "option, a missing value or a bad common value.");
  m.def("controller_usage", &controller::common_usage,
        "The usage lines of the common options, for a controller's --help.");
  m.def("select_muscles", &controller::select_muscles, py::arg("name"), py::arg("muscle_names"),
        "Indices into muscle_names of the muscles `name` selects: the muscle of that name, or "
        "the group of every muscle named `name` or starting with `name`_ ('SG': SG_left, "
        "SG_right); empty when none.");
  m.def("muscle_group", &controller::muscle_group, py::arg("muscle_name"),
        "The group of a muscle: its name without _left or _right.");

  py::class_<Model>(m, "Model", "The server's model message: its mesh, muscles and landmarks.")
      .def_readonly("scene", &Model::scene, "the scene file the server runs")
      .def_readonly("dt", &Model::dt, "time step [s]")
      .def_readonly("num_nodes", &Model::num_nodes)
      .def_property_readonly(
          "rest_positions", [](const Model& m) { return array(m.rest_positions, 3); },
          "node rest positions [m], (n, 3)")
      .def_property_readonly(
          "elements", [](const Model& m) { return array(m.elements, 8); },
          "hexahedra as 8 node indices each, (e, 8)")
      .def_readonly("muscle_names", &Model::muscle_names, "the muscles, in order")
      .def_property_readonly(
          "max_forces", [](const Model& m) { return array(m.muscle_max_forces); },
          "each muscle's F_max [N]")
      .def_property_readonly(
          "landmarks",
          [](const Model& m) {
            py::dict d;
            for (std::size_t i = 0; i < m.landmark_names.size(); ++i)
              d[py::str(m.landmark_names[i])] = m.landmark_nodes[i];
            return d;
          },
          "landmark name -> node index")
      .def_readonly("obstacle_names", &Model::obstacle_names);

  py::class_<State>(m, "State", "A state the server published after a step.")
      .def_readonly("step", &State::step, "steps since the start (0: the initial state)")
      .def_readonly("time", &State::time, "simulated time [s]")
      .def_readonly("utime", &State::utime, "wall-clock time of publication [us]")
      .def_property_readonly(
          "node_indices", [](const State& s) { return array(s.node_indices); },
          "the nodes published, in the order of positions")
      .def_property_readonly(
          "positions", [](const State& s) { return array(s.positions, 3); },
          "positions of the nodes published [m], (k, 3)")
      .def_property_readonly(
          "muscle_lengths", [](const State& s) { return array(s.muscle_lengths); }, "[m]")
      .def_property_readonly(
          "muscle_velocities", [](const State& s) { return array(s.muscle_velocities); },
          "lengthening rates [m/s]")
      .def_property_readonly(
          "activations", [](const State& s) { return array(s.activations); },
          "the levels the step used [1]")
      .def_readonly("newton_iterations", &State::newton_iterations)
      .def_readonly("residual_norm", &State::residual_norm)
      .def_readonly("step_wall_time", &State::step_wall_time, "[s]")
      .def_readonly("step_cuts", &State::step_cuts)
      .def_readonly("converged", &State::converged)
      .def_readonly("status", &State::status)
      .def_property_readonly("contact_nodes", [](const State& s) { return array(s.contact_nodes); })
      .def_property_readonly(
          "contact_obstacles", [](const State& s) { return array(s.contact_obstacles); },
          "the obstacle each contact node presses (index in obstacle_names)")
      .def_property_readonly(
          "contact_forces", [](const State& s) { return array(s.contact_forces, 3); },
          "force of the obstacle on each contact node [N], (c, 3)")
      .def_property_readonly(
          "obstacle_forces", [](const State& s) { return array(s.obstacle_forces, 3); },
          "force on each obstacle [N], (o, 3)")
      .def_readonly("max_penetration", &State::max_penetration, "[m]")
      .def("__repr__", [](const State& s) {
        return "State(step=" + std::to_string(s.step) + ", time=" + std::to_string(s.time) + ")";
      });

  py::class_<BusClient>(
      m, "BusClient",
      "A controller's connection to a tongue server on LCM, with the C++ controllers' protocol, "
      "timeouts and exit codes:\n\n"
      "    client = tongue.BusClient(tongue.ControllerOptions(lcm_url=URL))\n"
      "    model = client.connect()          # None when none came: see client.reason\n"
      "    for state in client.lockstep():   # every new state, in order\n"
      "        client.send({'SG': 0.1})      # the levels for the next step\n"
      "    sys.exit(client.exit_code)\n\n"
      "The loop ends after --max-steps' state, when the server falls silent for timeout_s, "
      "publishes an unconverged step or rejects the activations sent; exit_code and reason say "
      "which (0, 4, 2, 5; 1 for a bus error; 130 for Ctrl-C, whose KeyboardInterrupt is raised).")
      .def(py::init([](const CommonOptions& options, const std::string& program) {
             return std::make_unique<BusClient>(program, options);
           }),
           py::arg("options") = CommonOptions{}, py::arg("program") = "python_controller",
           "Starts receiving on the server's channels (nothing published after this is missed). "
           "program names the controller in its messages and its activations' sender "
           "('<program>:<pid>'). RuntimeError naming the URL when LCM cannot be opened.")
      .def(
          "connect",
          [](BusClient& client) -> py::object {
            PythonWait wait;
            const Model* model = nullptr;
            {
              py::gil_scoped_release release;
              model = guarded(client, [&] { return client.connect(wait.stop()); });
            }
            wait.raise_pending();
            return model ? py::cast(*model) : py::none();
          },
          "Waits for the model (sending 'describe' while none comes) and returns it; None when "
          "the session ended first (exit_code and reason say why).")
      .def_property_readonly(
          "model",
          [](const BusClient& client) -> py::object {
            const Model* model = client.model();
            return model ? py::cast(*model) : py::none();
          },
          "the model connect() returned, or None")
      .def("__iter__", [](BusClient& client) -> BusClient& { return client; })
      .def("__next__",
           [](BusClient& client) {
             PythonWait wait;
             std::optional<State> state;
             {
               py::gil_scoped_release release;
               state = guarded(client, [&] { return client.next(wait.stop()); });
             }
             wait.raise_pending();
             if (!state) throw py::stop_iteration();
             return std::move(*state);
           })
      .def(
          "lockstep",
          [](BusClient& client) -> BusClient& {
            require_mode(client, LoopMode::lockstep);
            return client;
          },
          "The states, each new one in order, for a client in 'lockstep' mode: answer each with "
          "send() before the next (the server waits for it). connect() first if not done.")
      .def(
          "realtime",
          [](BusClient& client) -> BusClient& {
            require_mode(client, LoopMode::realtime);
            return client;
          },
          "The same for a client in 'realtime' mode (the server does not wait: its answers are "
          "held until the next).")
      .def(
          "send",
          [](BusClient& client, const py::handle& levels) {
            const Model* model = client.model();
            if (model == nullptr) throw py::value_error("send: no model yet (connect() first)");
            client.send(to_levels(levels, *model));
          },
          py::arg("levels"),
          "The answer to the state last handed out: the levels [0, 1] for the next step, as a "
          "dict of muscle or group names (the server resolves them; muscles not named keep their "
          "levels) or every muscle's level in model.muscle_names order. Nothing is sent for a "
          "state a later one already follows, nor after the last. RuntimeError when that state "
          "was answered already.")
      .def_property_readonly("awaiting_answer", &BusClient::awaiting_answer,
                             "whether the state last handed out waits for send()")
      .def(
          "end_after",
          [](BusClient& c, std::int64_t step, const std::string& reason) {
            c.end_after(step, reason);
          },
          py::arg("step"), py::arg("reason") = " (the controller's last step)",
          "Ends the session after the state of step (when before max_steps), with exit code 0 "
          "and reason 'reached step N' + reason.")
      .def_property_readonly(
          "exit_code", [](const BusClient& c) { return c.outcome().exit_code; },
          "the C++ controllers' exit code for how the session ended (0 while "
          "it runs)")
      .def_property_readonly(
          "reason", [](const BusClient& c) { return c.outcome().reason; },
          "why the session ended ('' while it runs)")
      .def_property_readonly("options", &BusClient::options)
      .def(
          "fail", [](BusClient& c, const std::string& what) { c.fail(what); }, py::arg("what"),
          "Ends the session with exit code 1 and reason 'error: <what>' (the controller's own "
          "failure, e.g. a muscle the model lacks).")
      .def("summary", &BusClient::summary, py::arg("controller_summary") = "",
           "The C++ controllers' summary line: how the session ended, the states received and "
           "activations sent, then controller_summary.");
}

}  // namespace tongue::python
