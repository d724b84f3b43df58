#pragma once
// One function per stage, each adding its classes and functions to the module (module.cpp).
#include <string>

#include <pybind11/pybind11.h>

#include "core/interrupt.hpp"

namespace plumekit::python {

namespace py = pybind11;

// The GIL released around a long call that Ctrl-C can stop. Releasing the GIL alone lets other
// Python threads run, but Python handles a signal only when the call returns. While this lives,
// the library's long loops (core/interrupt.hpp) ask Python, holding the GIL for a moment, to run
// its signal handlers; when a handler raises (KeyboardInterrupt), the call stops with
// plumekit::Interrupted, and module.cpp's translator leaves the handler's exception raised.
class ReleasedGil {
 public:
  ReleasedGil();

 private:
  InterruptCheck check_;            // installed first, removed last
  py::gil_scoped_release release_;  // taken back before the check goes
};

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
// A fixed-grid model's refusal of a map's size with what to pass instead: `keyword`="hybrid".
std::string with_any_map_advice(const std::string& message, const std::string& keyword);

}  // namespace plumekit::python
