#pragma once
// The parts of the Python module `tongue` (module.cpp), each bound in its own file.
#include <pybind11/pybind11.h>

namespace tongue::python {

// BusClient, ControllerOptions, Model, State, the controllers' command line.
void bind_bus_client(pybind11::module_& m);

}  // namespace tongue::python
