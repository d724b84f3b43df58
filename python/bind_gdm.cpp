// Gas distribution maps (gdm/): Kernel DM+V and DM+V/W from readings a user brings.
#include <pybind11/stl.h>

#include "gdm/kernel_dmv.hpp"
#include "gdm/map_score.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"
#include "python/wind.hpp"

namespace plumekit::python {

namespace {

// Rows (x, y, reading) or (x, y, reading, u, v), map frame, as a sequence or an [n, 3|5] array.
std::vector<gdm::Sample> samples_from(const Map& map, const py::handle& rows) {
  std::vector<gdm::Sample> out;
  for (const py::handle row : rows) {
    const auto v = row.cast<std::vector<double>>();
    if (v.size() != 3 && v.size() != 5)
      throw py::type_error("samples: each row is (x, y, reading) or (x, y, reading, u, v)");
    gdm::Sample s;
    s.position = map.from_frame({v[0], v[1]});
    s.reading = v[2];
    if (v.size() == 5) s.wind = Vec2{v[3], v[4]};
    out.push_back(s);
  }
  return out;
}

}  // namespace

void bind_gdm(py::module_& m) {
  py::class_<gdm::GdmOptions> c(m, "GdmOptions", "Options of gas_map() (gdm/README.md)");
  c.def(py::init<>());
  PK_FIELD(c, gdm::GdmOptions, cell, "The map's cell, m");
  PK_FIELD(c, gdm::GdmOptions, kernel_width, "The kernel's sigma, m");
  PK_FIELD(c, gdm::GdmOptions, sigma_omega, "Confidence scale");
  PK_FIELD(c, gdm::GdmOptions, wind_stretch, "gamma, s: 0 gives DM+V, more gives DM+V/W");
  PK_FIELD(c, gdm::GdmOptions, cutoff, "Kernels reach this many widths");
  c.def_property(
      "background",
      [](const gdm::GdmOptions& o) { return std::string(gdm::to_string(o.background)); },
      [](gdm::GdmOptions& o, const std::string& v) { o.background = gdm::parse_background(v); },
      "'mean' or 'min' of the readings, where no reading reaches");
  m.def(
      "gas_map",
      [](const Map& map, const py::handle& rows, const py::object& source, const py::object& wind,
         const py::object& options, const py::kwargs& kw) {
        const auto o = options_from<gdm::GdmOptions>(options, kw, "gas_map");
        const std::vector<gdm::Sample> samples = samples_from(map, rows);
        std::optional<Vec2> s;
        if (!source.is_none()) s = map.from_frame(to_point(source, "source"));
        const Wind* w = wind.is_none() ? nullptr : &wind.cast<const Wind&>();
        if (s && !w) throw py::type_error("gas_map: scoring against a source needs wind=");
        gdm::GdmMaps maps;
        std::optional<gdm::MapScore> score;
        {
          ReleasedGil release;
          maps = gdm::kernel_dmv(map, samples, o);
          if (s)
            score = gdm::score_mean(maps.mean,
                                    gdm::true_mean_plume(map, w->field, *s, maps.mean.shape));
        }
        py::dict out;
        out["mean"] = grid_array(maps.mean.values, maps.mean.shape);
        out["variance"] = grid_array(maps.variance.values, maps.variance.shape);
        out["confidence"] = grid_array(maps.confidence.values, maps.confidence.shape);
        py::list estimates;
        for (const gdm::SourceEstimate& e : gdm::source_estimates(maps))
          estimates.append(py::make_tuple(e.name, from_point(map.to_frame(e.position))));
        out["source_estimates"] = estimates;
        if (score) {
          out["kl_distance"] = score->kl_distance;
          out["rmse"] = score->rmse;
        }
        return out;
      },
      py::arg("map"), py::arg("samples"), py::arg("source") = py::none(),
      py::arg("wind") = py::none(), py::arg("options") = py::none(),
      "Kernel DM+V (or DM+V/W with wind_stretch > 0 and rows with u, v) maps of readings "
      "(`plumekit gdm`): a dict of 'mean', 'variance', 'confidence' [ny, nx] (NaN in obstacles) "
      "and the six 'source_estimates'; with source= and wind= (a Wind of the map) also the "
      "'kl_distance' and 'rmse' against the true mean plume.");
}

}  // namespace plumekit::python
