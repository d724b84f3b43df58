// The `plumekit` Python module: the library's stages, not the command line (python/README.md).
#include <pybind11/pybind11.h>

#include "core/error.hpp"
#include "python/bindings.hpp"

namespace plumekit::python {

namespace {

// InputError -> plumekit.InputError (a ValueError); OptionError -> plumekit.OptionError, a
// subclass, with the options field it names as `.field`. Messages are the library's own.
// The exception types, made once by bind_errors (the translator takes no captures).
PyObject* input_error_type = nullptr;
PyObject* option_error_type = nullptr;

void bind_errors(py::module_& m) {
  // Leaked on purpose: the module's exception types live as long as the interpreter.
  auto* input_error = new py::exception<InputError>(m, "InputError", PyExc_ValueError);
  input_error->doc() =
      "Bad input: a malformed file, a point inside an obstacle, an option out of range. The "
      "message names the file or field and the fault (the command line exits 2 for these).";
  auto* option_error = new py::exception<OptionError>(m, "OptionError", input_error->ptr());
  option_error->doc() = "An option outside its allowed range; `.field` names it (\"flow.cell\").";
  input_error_type = input_error->ptr();
  option_error_type = option_error->ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Interrupted&) {
      // A signal handler's exception (KeyboardInterrupt) is already set: ReleasedGil.
      if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const OptionError& e) {
      py::object instance = py::handle(option_error_type)(e.what());
      instance.attr("field") = e.field();
      PyErr_SetObject(option_error_type, instance.ptr());
    } catch (const InputError& e) {
      PyErr_SetString(input_error_type, e.what());
    }
  });
}

}  // namespace

ReleasedGil::ReleasedGil()
    : check_([] {
        py::gil_scoped_acquire gil;
        return PyErr_CheckSignals() != 0;  // its exception stays set until the call returns
      }) {}

}  // namespace plumekit::python

PYBIND11_MODULE(plumekit, m) {
  using namespace plumekit::python;
  m.doc() =
      "plumekit: gas source localization with mobile robots in cluttered indoor maps.\n\n"
      "Maps, wind (flow), plumes, the CNN surrogate (predict), the planner (plan) and source term "
      "estimation (localize, evaluate, Mission). Points are (x, y) in metres in the map's frame, "
      "as in map files and on the command line; grids are numpy arrays [ny, nx] with row 0 at "
      "the arena's lower edge.";
  m.attr("__version__") = PLUMEKIT_VERSION;
  bind_errors(m);
  bind_map(m);
  bind_flow(m);
  bind_plume(m);
  bind_dataset(m);
  bind_surrogate(m);
  bind_planner(m);
  bind_ste_options(m);
  bind_ste(m);
  bind_tunnel(m);
  bind_gdm(m);
}
