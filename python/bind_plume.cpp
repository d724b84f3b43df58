// Plumes: the filament and advection-diffusion simulators (dataset/) in a solved wind.
#include <pybind11/stl.h>

#include "core/seed.hpp"
#include "dataset/plume.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"
#include "python/wind.hpp"
#include "surrogate/features.hpp"
#include "world/option_tables.hpp"

namespace plumekit::python {

namespace {

using cfd::AdvectionDiffusionOptions;
using dataset::PlumeOptions;
using world::FilamentOptions;
using world::GasSensorModel;

// The preset the two world fields and the engine match: "faithful", "thesis" (each with "-v1"
// for the V1 engine), or "custom".
std::string world_name(const world::FilamentOptions& o) {
  const std::string v1 = o.engine == world::PlumeEngine::V1 ? "-v1" : "";
  if (o.occlusion && o.unsteady_wind) return "faithful" + v1;
  return !o.occlusion && !o.unsteady_wind ? "thesis" + v1 : "custom";
}

void bind_filament_options(py::module_& m) {
  py::class_<world::FilamentOptions> c(m, "FilamentOptions",
                                       "The filament plume (docs/options.md)");
  c.def(py::init<>());
  bind_table(c, world::filament_option_table());
  bind_deprecated_alias(c, "release_per_second", "filaments_per_second");
  c.def_property(
      "world", &world_name,
      [](world::FilamentOptions& o, const std::string& name) { world::set_world(o, name); },
      "World preset: 'faithful' (occlusion, unsteady wind) or 'thesis' (neither); with '-v1' "
      "the world before issue 45");
}

void bind_sensor(py::module_& m) {
  py::class_<world::GasSensorModel> c(m, "GasSensorModel",
                                      "A gas sensor's response (docs/world.md, \"Gas sensors\")");
  c.def(py::init<>());
  bind_table(c, world::gas_sensor_option_table());
  PK_FIELD(c, world::GasSensorModel, name, "The preset it came from");
  static const std::string doc = [] {
    std::string names;
    for (const auto& n : world::gas_sensor_preset_names())
      names += (names.empty() ? "" : ", ") + n;
    return "A gas sensor preset: " + names;
  }();
  m.def("gas_sensor", &world::gas_sensor_preset, py::arg("name"), doc.c_str());
}

void bind_plume_options(py::module_& m) {
  py::class_<cfd::AdvectionDiffusionOptions> ad(m, "AdvectionDiffusionOptions",
                                                "The steady advection-diffusion plume");
  ad.def(py::init<>());
  bind_table(ad, cfd::advection_diffusion_option_table());

  py::class_<PlumeOptions> c(m, "PlumeOptions", "Options of plume() (`plumekit plume`)");
  c.def(py::init<>());
  c.def_property(
      "model", [](const PlumeOptions& o) { return std::string(dataset::to_string(o.model)); },
      [](PlumeOptions& o, const std::string& s) { o.model = dataset::parse_plume_simulator(s); },
      "'filament' or 'advection-diffusion'");
  PK_FIELD(c, PlumeOptions, filament, "FilamentOptions");
  PK_FIELD(c, PlumeOptions, advection_diffusion, "AdvectionDiffusionOptions");
  PK_FIELD(c, PlumeOptions, sensor, "The static sensors' GasSensorModel");
  c.def_property(
      "release_rate", [](const PlumeOptions& o) { return o.filament.release_rate; },
      &PlumeOptions::set_release_rate, "Both models' release rate");
  c.def_property(
      "world", [](const PlumeOptions& o) { return world_name(o.filament); },
      [](PlumeOptions& o, const std::string& name) { world::set_world(o.filament, name); },
      "World preset of the filament plume: 'faithful' or 'thesis'");
  c.def_property(
      "gas_sensor", [](const PlumeOptions& o) { return o.sensor.name; },
      [](PlumeOptions& o, const std::string& name) { set_gas_sensor(o.sensor, name); },
      "The static sensors' gas sensor preset (gas_sensor())");
}

}  // namespace

void bind_plume(py::module_& m) {
  bind_filament_options(m);
  bind_sensor(m);
  bind_plume_options(m);
  m.def(
      "plume",
      [](const Wind& wind, const py::handle& source, std::uint64_t seed, double cell,
         const py::object& options, const py::kwargs& kw) {
        const auto o = options_from<PlumeOptions>(options, kw, "plume");
        const Map& map = *wind.map;
        const Vec2 s = map.from_frame(to_point(source, "source"));
        const GridShape grid = cell > 0 ? GridShape::with_cell(map.width, map.height, cell)
                                        : surrogate::feature_grid(map);
        dataset::PlumeTargets t;
        {
          ReleasedGil release;
          dataset::check_source(map, s);
          const dataset::MapPlumes plumes(map, wind.field, grid, o);
          t = plumes.run(s, seed);
        }
        py::dict out;
        out["mean"] = grid_array(t.mean.values, grid);
        out["std"] = grid_array(t.std.values, grid);
        out["spinup_s"] = t.filament.spinup_s;
        out["steady"] = t.filament.steady;
        out["filaments"] = t.filament.filaments_at_end;
        return out;
      },
      py::arg("wind"), py::arg("source"), py::arg("seed") = kDefaultSeed, py::arg("cell") = 0.0,
      py::arg("options") = py::none(),
      "One source's plume in a solved wind (`plumekit plume`): a dict with 'mean' and 'std' "
      "[ny, nx] (float64) on the dataset's 64 x 64 sensor grid, or on cells of about `cell` m, "
      "and the filament model's spin-up. Keyword arguments set PlumeOptions fields: "
      "plume(wind, (2, 2), model='advection-diffusion'), world='thesis', gas_sensor='mox-fast'.");
}

}  // namespace plumekit::python
