#include "python/convert.hpp"

#include <pybind11/stl.h>

#include <utility>
#include <vector>

namespace plumekit::python {

Vec2 to_point(const py::handle& value, const char* what) {
  try {
    const auto xy = value.cast<std::vector<double>>();
    if (xy.size() == 2) return {xy[0], xy[1]};
  } catch (const py::cast_error&) {
  }
  throw py::type_error(std::string(what) + ": expected a point (x, y) of two numbers");
}

py::tuple from_point(Vec2 p) {
  return py::make_tuple(p.x, p.y);
}

// Through Python's own json module: summaries are small, and this keeps every number's spelling.
py::object from_json(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

nlohmann::json to_json(const py::handle& value) {
  const std::string text = py::str(py::module_::import("json").attr("dumps")(value));
  return nlohmann::json::parse(text);
}

void set_gas_sensor(world::GasSensorModel& sensor, const std::string& name) {
  const double baseline = sensor.baseline;
  sensor = world::gas_sensor_preset(name);
  sensor.baseline = baseline;
}

void set_options(py::object options, const py::dict& values, const std::string& what) {
  // A preset first, whatever the order given: the fields given with it override their part of it.
  std::vector<std::pair<py::handle, py::handle>> items;
  for (const auto& item : values)
    if (py::str(item.first).cast<std::string>() == "protocol") items.emplace_back(item);
  for (const auto& item : values)
    if (py::str(item.first).cast<std::string>() != "protocol") items.emplace_back(item);
  for (const auto& item : items) {
    const std::string name = py::str(item.first);
    if (!py::hasattr(options, name.c_str()) || name.rfind('_', 0) == 0)
      throw py::type_error(what + ": no option named '" + name + "'");
    py::object current = options.attr(name.c_str());
    if (py::isinstance<py::dict>(item.second) && !py::isinstance<py::dict>(current)) {
      // A nested options object: set its fields, then put the copy back.
      set_options(current, item.second.cast<py::dict>(), what + "." + name);
      options.attr(name.c_str()) = current;
    } else {
      options.attr(name.c_str()) = item.second;
    }
  }
}

void set_options(py::object options, const py::kwargs& kwargs, const std::string& what) {
  set_options(std::move(options), static_cast<const py::dict&>(kwargs), what);
}

}  // namespace plumekit::python
