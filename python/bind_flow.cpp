// Wind: the steady flow of a map (cfd/), its arrays as numpy views that copy nothing.
#include <chrono>
#include <memory>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "cfd/flow_output.hpp"
#include "cfd/flow_policy.hpp"
#include "cfd/wind_file.hpp"
#include "core/output_target.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"
#include "python/wind.hpp"

namespace plumekit::python {

namespace {

void bind_flow_options(py::module_& m) {
  using cfd::FlowOptions;
  py::class_<FlowOptions> c(m, "FlowOptions",
                            "Options of the steady flow solver (docs/options.md); the "
                            "defaults are the dataset generator's");
  c.def(py::init<>())
      .def_readwrite("wall_speed", &FlowOptions::wall_speed,
                     "Tangential speed of the left, right, bottom, top walls, m/s (a moving lid)");
  bind_table(c, cfd::flow_option_table());
}

using WindClass = py::class_<Wind, std::shared_ptr<Wind>>;

// A read-only numpy view of one of the field's arrays, kept alive by the Wind: `extra_rows` and
// `extra_cols` beyond the cell grid for the face velocities.
template <class T>
void view_property(WindClass& c, const char* name,
                   const std::vector<T>& (cfd::WindField::*array)() const, int extra_rows,
                   int extra_cols, const char* doc) {
  c.def_property_readonly(
      name,
      [array, extra_rows, extra_cols](py::object self) {
        const cfd::WindField& w = self.cast<const Wind&>().field;
        return grid_view((w.*array)(), w.shape().ny + extra_rows, w.shape().nx + extra_cols, self);
      },
      doc);
}

void bind_wind_class(py::module_& m) {
  WindClass c(m, "Wind",
              "A map's steady wind. u, v, p and solid are read-only numpy views [ny, nx] of the "
              "solver's own arrays (no copy), cell-centred, row 0 at the arena's lower edge.");
  view_property(c, "u", &cfd::WindField::u, 0, 0, "x velocity, m/s, [ny, nx]");
  view_property(c, "v", &cfd::WindField::v, 0, 0, "y velocity, m/s, [ny, nx]");
  view_property(c, "p", &cfd::WindField::p, 0, 0, "Kinematic pressure, m^2/s^2, [ny, nx]");
  view_property(c, "solid", &cfd::WindField::solid_cells, 0, 0, "1 in obstacle cells, [ny, nx]");
  view_property(c, "face_u", &cfd::WindField::face_u, 0, 1,
                "x velocity on the vertical faces, as solved, [ny, nx + 1]");
  view_property(c, "face_v", &cfd::WindField::face_v, 1, 0,
                "y velocity on the horizontal faces, as solved, [ny + 1, nx]");
  c.def_property_readonly("nx", [](const Wind& w) { return w.field.shape().nx; })
      .def_property_readonly("ny", [](const Wind& w) { return w.field.shape().ny; })
      .def_property_readonly(
          "cell",
          [](const Wind& w) { return py::make_tuple(w.field.shape().dx(), w.field.shape().dy()); },
          "(dx, dy), m")
      .def_property_readonly(
          "extent",
          [](const Wind& w) {
            const Vec2 lo = w.map->to_frame({0, 0}),
                       hi = w.map->to_frame({w.map->width, w.map->height});
            return py::make_tuple(lo.x, hi.x, lo.y, hi.y);
          },
          "(x0, x1, y0, y1) of the arena in the map frame: matplotlib's imshow extent")
      .def_property_readonly("map", [](const Wind& w) { return *w.map; })
      .def_property_readonly(
          "summary", [](const Wind& w) { return from_json(w.summary); },
          "The solve's report, as `plumekit flow --json` prints it")
      .def(
          "at",
          [](const Wind& w, const py::handle& p) {
            return from_point(w.field.at(w.map->from_frame(to_point(p, "p"))));
          },
          py::arg("p"), "The velocity (u, v) at a point (map frame), bilinear; 0 in obstacles")
      .def(
          "save",
          [](const Wind& w, const std::filesystem::path& dir) {
            OutputDirectory out(dir, "flow");
            cfd::write_flow(out.open(), *w.map, w.field, w.file_summary);
            out.commit();
          },
          py::arg("dir"),
          "Writes the `plumekit flow` files (u/v/p .npy, wind.json, wind.vti, wind.png) into a "
          "new or empty folder, or an earlier flow output");
}

}  // namespace

void bind_flow(py::module_& m) {
  bind_flow_options(m);
  bind_wind_class(m);
  m.def(
      "flow",
      [](const Map& map, const py::object& options, const py::kwargs& kw) {
        const auto o = options_from<cfd::FlowOptions>(options, kw, "flow");
        auto wind = std::make_shared<Wind>();
        wind->map = std::make_shared<const Map>(map);
        {
          ReleasedGil release;
          cfd::WindResult r = cfd::solve_wind(map, o);
          wind->summary = cfd::flow_report_json(r, o);
          wind->file_summary = cfd::summary_json(r.flow.summary, r.flow.wind, o);
          wind->field = std::move(r.flow.wind);
        }
        return wind;
      },
      py::arg("map"), py::arg("options") = py::none(),
      "Solves the map's steady incompressible flow (`plumekit flow`). Keyword arguments set "
      "FlowOptions fields: flow(map, cell=0.1, nu=0.01). InputError when the solver does not "
      "converge or the map cannot be solved.");
  // The baseline of bench/python_flow_bench.py: the same library call, timed in C++ with no
  // conversion on either side, in the same process as the Python calls it is compared with.
  m.def(
      "_library_flow_seconds",
      [](const Map& map, const py::kwargs& kw) {
        const auto o = options_from<cfd::FlowOptions>(py::none(), kw, "flow");
        ReleasedGil release;
        const auto t0 = std::chrono::steady_clock::now();
        const cfd::WindResult r = cfd::solve_wind(map, o);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      },
      py::arg("map"));
  m.def(
      "read_wind",
      [](const std::filesystem::path& dir, const Map& map) {
        auto wind = std::make_shared<Wind>();
        wind->map = std::make_shared<const Map>(map);
        wind->field = cfd::read_wind(dir, map);
        wind->summary = nlohmann::ordered_json{{"read_from", dir.string()}};
        wind->file_summary = wind->summary;
        return wind;
      },
      py::arg("dir"), py::arg("map"),
      "The wind of a `plumekit flow` output folder (either engine) for `map`, checked against "
      "its checksums and the map.");
}

}  // namespace plumekit::python
