// The Python module `tongue`: the simulator in-process (Simulation). NumPy arrays in SI units;
// the library's exceptions become Python's (std::invalid_argument: ValueError, others:
// RuntimeError) with the library's messages. A step releases the GIL.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "python/simulation.hpp"

namespace py = pybind11;
using tongue::python::Simulation;
using tongue::python::StepFigures;

namespace {

// Runs a step without the GIL, then raises its warnings as Python RuntimeWarnings (they need
// the GIL), so that a loss of the material's stability is not left unsaid.
template <typename Levels>
StepFigures step(Simulation& simulation, const Levels& levels) {
  StepFigures figures;
  {
    py::gil_scoped_release release;
    figures = simulation.step(levels);
  }
  for (const std::string& w : figures.warnings)
    if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 1) != 0) throw py::error_already_set();
  return figures;
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
      .def("reset", &Simulation::reset,
           "Back to the settled state at time 0 with all levels 0; the run that follows repeats "
           "the first one exactly.")
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
}
