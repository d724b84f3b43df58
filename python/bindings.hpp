#pragma once
// One function per stage, each adding its classes and functions to the module (module.cpp).
#include <string>

#include <pybind11/pybind11.h>

namespace plumekit::python {

namespace py = pybind11;

void bind_map(py::module_& m);
void bind_flow(py::module_& m);
void bind_plume(py::module_& m);
void bind_dataset(py::module_& m);
void bind_surrogate(py::module_& m);
void bind_planner(py::module_& m);
void bind_ste_options(py::module_& m);  // before bind_ste
void bind_ste(py::module_& m);
void bind_gdm(py::module_& m);
void bind_tunnel(py::module_& m);  // the 3-D wind tunnel

// The shipped data folder: $PLUMEKIT_DATA if set, else the source tree's data/ (as the CLI).
std::string data_dir();

}  // namespace plumekit::python
