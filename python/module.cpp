// The Python module `tongue`: the simulator in-process (Simulation), run files (RunFile) and a
// controller's connection to a server (BusClient, bus_client_bindings.cpp). NumPy arrays in SI
// units; the library's exceptions become Python's (std::invalid_argument: ValueError, others:
// RuntimeError) with the library's messages. A step and a reset release the GIL.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "python/run_data.hpp"
#include "python/simulation.hpp"

namespace py = pybind11;
using tongue::python::RunData;
using tongue::python::Simulation;
using tongue::python::StepFigures;

namespace {

// The library's warnings as Python RuntimeWarnings (they need the GIL), so that a loss of the
// material's stability is not left unsaid.
const std::vector<std::string>& warn(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 1) != 0) throw py::error_already_set();
  return warnings;
}

// Runs a step without the GIL, then raises its warnings.
template <typename Levels>
StepFigures step(Simulation& simulation, const Levels& levels) {
  StepFigures figures;
  {
    py::gil_scoped_release release;
    figures = simulation.step(levels);
  }
  warn(figures.warnings);
  return figures;
}

// Resets without the GIL, then raises the ended run's warnings.
template <typename Levels>
std::vector<std::string> reset(Simulation& simulation, const Levels& first_levels) {
  std::vector<std::string> warnings;
  {
    py::gil_scoped_release release;
    warnings = simulation.reset(first_levels);
  }
  return warn(warnings);
}

// A dataset as a NumPy array of its shape.
py::array_t<double> to_array(const tongue::python::Dataset& d) {
  std::vector<py::ssize_t> shape(d.shape.begin(), d.shape.end());
  py::array_t<double> a(shape);
  std::copy(d.values.begin(), d.values.end(), a.mutable_data());
  return a;
}

py::array_t<double> to_array(std::vector<double> v) {
  const std::size_t n = v.size();
  return to_array(tongue::python::Dataset{std::move(v), {n}});
}

}  // namespace

PYBIND11_MODULE(tongue, m) {
  m.doc() = "The tongue simulator in-process: a dynamic scene stepped from Python.";

  py::class_<StepFigures>(m, "StepFigures", "What one step did.")
      .def_readonly("time", &StepFigures::time, "simulated time at the end of the step [s]")
      .def_readonly("iterations", &StepFigures::iterations, "Newton iterations")
      .def_readonly("factorizations", &StepFigures::factorizations, "tangent factorizations")
      .def_readonly("cuts", &StepFigures::cuts, "times the step was halved and retried")
      .def_readonly("error_estimate", &StepFigures::error_estimate,
                    "Newton's estimate of the error left in the displacement [m]")
      .def_readonly("wall_seconds", &StepFigures::wall_seconds,
                    "wall time of the step in C++, the Python call around it not counted [s]")
      .def_readonly("held", &StepFigures::held, "taken as the identity from a state at rest")
      .def_readonly("warnings", &StepFigures::warnings,
                    "warnings the step raised (also issued as RuntimeWarning)")
      .def("__repr__", [](const StepFigures& f) {
        return "StepFigures(time=" + std::to_string(f.time) +
               ", iterations=" + std::to_string(f.iterations) + ")";
      });

  py::class_<Simulation>(m, "Simulation",
                         "A dynamic scene (YAML file), settled, stepped by its dt in-process.")
      .def(py::init<const std::string&>(), py::arg("scene"),
           "Reads, builds and settles the scene; raises RuntimeError naming the file and key "
           "for a scene that cannot be read or built, ValueError for one that is not dynamic.")
      .def(
          "step", &step<tongue::fem::Vector>, py::arg("levels"),
          "One step of dt with the activation level [0, 1] of every muscle, in muscle_names "
          "order. ValueError for a wrong count or range; RuntimeError when the step does not "
          "converge (the state stays at the last accepted step). Returns StepFigures; its warnings "
          "are also issued as RuntimeWarning.")
      .def("step", &step<std::map<std::string, double>>, py::arg("levels"),
           "One step of dt with the levels of the muscles or groups named ({'SG': 0.125} sets "
           "SG_left and SG_right); the others keep the last step's levels.")
      .def(
          "reset", [](Simulation& s) { return reset(s, tongue::fem::Vector()); },
           "Back to the settled state at time 0 with all levels 0; the run that follows repeats "
           "the first one exactly, its warnings too. Returns finish_checks() of the run that "
           "ended (also issued as RuntimeWarning). first_levels: the first step's levels when "
           "known (every muscle's, or a dict of muscles and groups as step() takes, the others "
           "0): the first step's factorization is made here under them, as sim_batch does, "
           "instead of again at the first step; the states are the same either way.")
      .def("reset", &reset<tongue::fem::Vector>, py::arg("first_levels"))
      .def("reset", &reset<std::map<std::string, double>>, py::arg("first_levels"))
      .def(
          "finish_checks", [](Simulation& s) { return warn(s.finish_checks()); },
          "The warnings of the checks still under way on the last state (the material's loss "
          "of strong ellipticity is found off the step's path and reported with the next step "
          "otherwise), also issued as RuntimeWarning: call it at the end of a run.")
      .def("run_file", &Simulation::open_run_file, py::arg("path"),
           "Writes the run from here on into a run file at path (as sim_batch's, readable with "
           "RunFile): the current state as its first frame, then a frame per step; a reset writes "
           "the settled state again. A file already being written is closed first. RuntimeError "
           "naming the file when it cannot be created.")
      .def("close_run_file", &Simulation::close_run_file,
           "Marks the run file 'completed' (or 'failed: ...' after a step that did not converge) "
           "and closes it; also done when the Simulation is deleted.")
      .def_property_readonly("run_file_path", &Simulation::run_file_path,
                             "the run file being written ('' when none)")
      .def_property_readonly("time", &Simulation::time, "simulated time [s]")
      .def_property_readonly("step_count", &Simulation::step_count, "steps since the start")
      .def_property_readonly("dt", &Simulation::dt, "the scene's time step [s]")
      .def_property_readonly("positions", &Simulation::positions, "node positions [m], (n, 3)")
      .def_property_readonly("displacements", &Simulation::displacements,
                             "node displacements from the rest positions [m], (n, 3)")
      .def_property_readonly("velocities", &Simulation::velocities, "node velocities [m/s], (n, 3)")
      .def_property_readonly("levels", &Simulation::levels, "the last step's levels [1]")
      .def_property_readonly("muscle_lengths", &Simulation::muscle_lengths, "muscle lengths [m]")
      .def_property_readonly("muscle_velocities", &Simulation::muscle_velocities,
                             "muscle lengthening rates [m/s]")
      .def_property_readonly("scene_path", &Simulation::scene_path, "the scene file")
      .def_property_readonly("muscle_names", &Simulation::muscle_names, "the muscles, in order")
      .def_property_readonly("max_forces", &Simulation::max_forces, "each muscle's F_max [N]")
      .def_property_readonly("rest_positions", &Simulation::rest_positions,
                             "node rest positions [m], (n, 3)")
      .def_property_readonly("elements", &Simulation::elements,
                             "hexahedra as 8 node indices each (ANSYS SOLID185 order), (e, 8)")
      .def_property_readonly("node_sets", &Simulation::node_sets,
                             "named node sets (landmarks, constraints, muscles): name -> indices");

  py::class_<RunData>(
      m, "RunFile", "A run file (HDF5) written by sim_batch, sim_server or the runner, read back.")
      .def(py::init<const std::string&>(), py::arg("path"),
           "Opens the file; RuntimeError naming it when it is not a run file.")
      .def_property_readonly("path", &RunData::path)
      .def_property_readonly(
          "time", [](const RunData& r) { return to_array(r.dataset("/time")); },
          "each frame's time [s], (T,)")
      .def_property_readonly(
          "positions", [](const RunData& r) { return to_array(r.dataset("/positions")); },
          "node positions [m], (T, n, 3)")
      .def_property_readonly(
          "rest_positions", [](const RunData& r) { return to_array(r.dataset("/rest_positions")); },
          "the mesh's rest positions [m], (n, 3)")
      .def_property_readonly("muscle_names", &RunData::muscle_names, "the muscles, in order")
      .def_property_readonly(
          "activations", [](const RunData& r) { return to_array(r.dataset("/activations")); },
          "each frame's activation levels [1], (T, muscles)")
      .def_property_readonly("status", &RunData::status,
                             "how the run ended ('completed', ...; '' when not said)")
      .def(
          "dataset",
          [](const RunData& r, const std::string& name) { return to_array(r.dataset(name)); },
          py::arg("name"), "any dataset by name ('/solver/iterations', ...), as an array")
      .def("has", &RunData::has, py::arg("name"), "whether the file has that dataset or group")
      .def(
          "muscle",
          [](const RunData& r, const std::string& name) {
            py::dict series;
            series["activation"] = to_array(r.muscle_series("/activations", name));
            series["length"] = to_array(r.muscle_series("/muscles/length", name));
            series["velocity"] = to_array(r.muscle_series("/muscles/velocity", name));
            return series;
          },
          py::arg("name"),
          "one muscle's series by name: {'activation' [1], 'length' [m], 'velocity' [m/s]}, "
          "one value per frame; ValueError for a name not in the run");

  tongue::python::bind_bus_client(m);
}
