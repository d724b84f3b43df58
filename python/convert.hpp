#pragma once
// What every binding shares: points as (x, y) tuples, JSON summaries as dicts, grids as numpy
// arrays, and options set from keyword arguments.
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <nlohmann/json.hpp>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "world/gas_sensor.hpp"

namespace plumekit::python {

namespace py = pybind11;

// (x, y) from any two-number sequence; TypeError naming `what` otherwise.
Vec2 to_point(const py::handle& value, const char* what);
py::tuple from_point(Vec2 p);

// A JSON value as Python objects (dicts keep the JSON's key order).
py::object from_json(const nlohmann::json& value);
nlohmann::json to_json(const py::handle& value);

// A [ny, nx] copy of a grid's values (row 0 at y = 0, as everywhere in plumekit).
template <class T>
py::array_t<T> grid_array(const std::vector<T>& values, const GridShape& shape) {
  py::array_t<T> a({shape.ny, shape.nx});
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

// A read-only [rows, cols] view of `values`, kept alive by `owner`: no copy.
template <class T>
py::array_t<T> grid_view(const std::vector<T>& values, int rows, int cols, py::handle owner) {
  py::array_t<T> a({rows, cols}, values.data(), owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// Replaces `sensor` by the named preset (world::gas_sensor_preset), keeping its baseline, as the
// command line's --gas-sensor does.
void set_gas_sensor(world::GasSensorModel& sensor, const std::string& name);

// Sets each keyword argument as an attribute of `options` (a bound options object): a dict value
// sets the nested options object's attributes in turn. TypeError for a name the options do not
// have, naming `what` and the name.
void set_options(py::object options, const py::kwargs& kwargs, const std::string& what);
void set_options(py::object options, const py::dict& values, const std::string& what);

// The options of type T with the library's defaults, `base` if given, then `kwargs` applied.
template <class T>
T options_from(const py::object& base, const py::kwargs& kwargs, const std::string& what) {
  py::object o = base.is_none() ? py::cast(T{}) : py::cast(base.cast<T>());
  set_options(o, kwargs, what);
  return o.cast<T>();
}

}  // namespace plumekit::python
