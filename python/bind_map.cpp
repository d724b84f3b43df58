// Maps: read, write, validate, rasterize, import ROS maps (core/).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"
#include "map/ros_import.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"

namespace plumekit::python {

namespace {

py::list framed_points(const Map& map, const std::vector<Vec2>& points) {
  py::list out;
  for (const Vec2& p : points)
    out.append(from_point(map.to_frame(p)));
  return out;
}

// Warnings (an import's simplifications) as Python warnings, so that filters apply.
void warn_all(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
}

void bind_map_class(py::module_& m) {
  py::class_<Map>(m, "Map",
                  "A plumekit map (plumekit-map/2): an arena, its openings, obstacle polygons, "
                  "ground-truth sources and evaluation starts. Coordinates are in the map's "
                  "frame, as in its file.")
      .def(py::init([](const py::dict& data, const std::string& origin) {
             return parse_map(to_json(data).dump(), origin);
           }),
           py::arg("data"), py::arg("origin") = "<dict>",
           "A map from the dict of a map file's JSON (checked as a file is; `origin` names it "
           "in error messages).")
      .def_readonly("name", &Map::name)
      .def_readonly("width", &Map::width, "Arena width, m (along x)")
      .def_readonly("height", &Map::height, "Arena height, m (along y)")
      .def_readonly("format_version", &Map::format_version)
      .def_property_readonly(
          "origin", [](const Map& map) { return from_point(map.frame.origin); },
          "The arena's lower-left corner in the map frame")
      .def_property_readonly(
          "sources", [](const Map& map) { return framed_points(map, map.sources); },
          "Ground-truth sources, map frame")
      .def_property_readonly(
          "starts", [](const Map& map) { return framed_points(map, map.starts); },
          "Evaluation starts, map frame")
      .def_property_readonly(
          "obstacles",
          [](const Map& map) {
            py::list out;
            for (const Polygon& poly : map.obstacles)
              out.append(framed_points(map, poly));
            return out;
          },
          "Obstacle polygons, each a list of (x, y) vertices in the map frame")
      .def_property_readonly(
          "openings",
          [](const Map& map) {
            py::list out;
            for (const Opening& o : map.openings) {
              py::dict d;
              d["kind"] = to_string(o.kind);
              d["from"] = from_point(map.to_frame(o.from));
              d["to"] = from_point(map.to_frame(o.to));
              if (o.is_inlet()) {
                d["speed"] = o.speed;
                d["profile"] = to_string(o.profile);
              }
              out.append(d);
            }
            return out;
          },
          "Inlets and outlets: dicts of kind, from, to (map frame) and an inlet's speed (m/s) "
          "and profile")
      .def(
          "is_free",
          [](const Map& map, const py::handle& p) {
            return map.is_free(map.from_frame(to_point(p, "p")));
          },
          py::arg("p"), "Whether the point (map frame) is in the arena and outside every obstacle")
      .def(
          "to_dict", [](const Map& map) { return from_json(map_to_json(map)); },
          "The map file's JSON as a dict")
      .def("__repr__", [](const Map& map) {
        return "<plumekit.Map '" + map.name + "' " + compact(map.width) + " x " +
               compact(map.height) + " m, " + std::to_string(map.obstacles.size()) +
               " obstacles, " + std::to_string(map.sources.size()) + " sources>";
      });
}

void bind_ros_import(py::module_& m) {
  py::class_<RosImportOptions> c(m, "RosImportOptions",
                                 "Options of import_ros (the flags of `plumekit map import-ros`)");
  c.def(py::init<>());
  bind_table(c, ros_import_option_table());
  c.def_readwrite("inlets", &RosImportOptions::inlets,
                  "Inlets, map frame: 'X1,Y1,X2,Y2[,SPEED[,PROFILE]]' (none: the whole left "
                  "wall at 1 m/s)")
      .def_readwrite("outlets", &RosImportOptions::outlets, "Outlets, map frame: 'X1,Y1,X2,Y2'")
      .def_readwrite("name", &RosImportOptions::name, "Map name (default: the YAML's stem)");
  m.def(
      "import_ros",
      [](const std::filesystem::path& yaml, const py::object& options, const py::kwargs& kw) {
        const auto o = options_from<RosImportOptions>(options, kw, "import_ros");
        RosImport r;
        {
          ReleasedGil release;
          r = import_ros_map(yaml, o);
        }
        warn_all(r.warnings);
        return r.map;
      },
      py::arg("yaml"), py::arg("options") = py::none(),
      "A ROS map_server map (YAML + image) as a plumekit map; keyword arguments set "
      "RosImportOptions fields. Its warnings arrive as UserWarnings.");
}

}  // namespace

void bind_map(py::module_& m) {
  bind_map_class(m);
  m.def("read_map", &read_map, py::arg("path"),
        "Reads and validates a map file (plumekit-map/1 or /2).");
  m.def(
      "write_map",
      [](Map map, const std::filesystem::path& path) {
        // Marked as plumekit's, so that a later write_map may replace it (and only then).
        if (map.generated_by.empty()) map.generated_by = "plumekit python write_map";
        write_output_file(path, map_file_text(map, path.string()));
      },
      py::arg("map"), py::arg("path"),
      "Writes a map file atomically, marked as plumekit's (generated_by). Refuses to overwrite a "
      "file plumekit did not write.");
  m.def(
      "validate_map",
      [](const Map& map) {
        validate_map(map, map.name.empty() ? "<map>" : map.name);
        const MapGridCheck check = map_grid_check(map);
        py::dict out;
        out["free_fraction"] = check.free_fraction;
        out["inlet_reaches_outlet"] = check.inlet_reaches_outlet;
        out["cell"] = check.cell;
        out["coarsened"] = check.coarsened;
        return out;
      },
      py::arg("map"),
      "Checks a map (InputError naming the fault) and returns the grid check of `plumekit map "
      "validate`: free_fraction, inlet_reaches_outlet, cell, coarsened.");
  m.def(
      "rasterize",
      [](const Map& map, double cell) {
        const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
        return grid_array(rasterize_labels(map, shape).values, shape);
      },
      py::arg("map"), py::arg("cell") = 0.05,
      "The map's region labels on cells of about `cell` m, uint8 [ny, nx]: 0 obstacle, 1 free, 2 "
      "wall, 3 inlet, 4 outlet.");
  bind_ros_import(m);
}

}  // namespace plumekit::python
