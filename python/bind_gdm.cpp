// Gas distribution maps (gdm/): Kernel DM+V and DM+V/W from readings a user brings.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "core/error.hpp"

#include "methods/gdm_estimates.hpp"
#include "methods/kernel_dmv.hpp"
#include "methods/option_tables.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/options.hpp"
#include "python/wind.hpp"
#include "run/gdm_score.hpp"

namespace plumekit::python {

namespace {

constexpr const char* kRowsExpected =
    "samples: expected rows (x, y, reading) or (x, y, reading, u, v), map frame: an [n, 3] or "
    "[n, 5] array or a list of such tuples";

// One row's numbers; InputError (a ValueError) naming the row and the expected shape otherwise.
std::vector<double> row_values(const py::handle& row, std::size_t n) {
  std::vector<double> v;
  try {
    v = row.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw InputError(std::string(kRowsExpected) + "; row " + std::to_string(n) + " is " +
                     std::string(py::str(py::repr(row))).substr(0, 60));
  }
  if (v.size() != 3 && v.size() != 5)
    throw InputError(std::string(kRowsExpected) + "; row " + std::to_string(n) + " has " +
                     std::to_string(v.size()) + " values");
  return v;
}

// Rows (x, y, reading) or (x, y, reading, u, v), map frame, as a sequence or an [n, 3|5] array;
// each sample keeps methods::sample_fault's rules.
std::vector<methods::Sample> samples_from(const Map& map, const py::handle& rows) {
  if (py::isinstance<py::array>(rows)) {
    const auto a = py::reinterpret_borrow<py::array>(rows);
    if (a.ndim() != 2 || (a.shape(1) != 3 && a.shape(1) != 5)) {
      std::string shape;
      for (py::ssize_t d = 0; d < a.ndim(); ++d)
        shape += (d ? ", " : "") + std::to_string(a.shape(d));
      throw InputError(std::string(kRowsExpected) + "; got an array of shape (" + shape + ")" +
                       (a.ndim() == 1 ? " (one sample: [[x, y, reading]]; flat rows: "
                                        "rows.reshape(-1, 3))"
                                      : ""));
    }
  } else if (!py::isinstance<py::sequence>(rows) || py::isinstance<py::str>(rows)) {
    throw InputError(std::string(kRowsExpected) + "; got " +
                     std::string(py::str(py::type::of(rows).attr("__name__"))));
  }
  std::vector<methods::Sample> out;
  std::size_t n = 0;
  for (const py::handle row : rows) {
    const std::vector<double> v = row_values(row, n);
    methods::Sample s;
    s.position = map.from_frame({v[0], v[1]});
    s.reading = v[2];
    if (v.size() == 5) s.wind = Vec2{v[3], v[4]};
    if (const methods::SampleFault f = methods::sample_fault(map, s); !f.column.empty())
      throw InputError("samples: row " + std::to_string(n) + ", " + f.column + ": " + f.reason);
    out.push_back(s);
    ++n;
  }
  return out;
}

}  // namespace

void bind_gdm(py::module_& m) {
  py::class_<methods::GdmOptions> c(m, "GdmOptions", "Options of gas_map() (docs/methods.md)");
  c.def(py::init<>());
  bind_table(c, methods::gdm_option_table());
  m.def(
      "gas_map",
      [](const Map& map, const py::handle& rows, const py::object& source, const py::object& wind,
         const py::object& options, const py::kwargs& kw) {
        const auto o = options_from<methods::GdmOptions>(options, kw, "gas_map");
        const std::vector<methods::Sample> samples = samples_from(map, rows);
        std::optional<Vec2> s;
        if (!source.is_none()) s = map.from_frame(to_point(source, "source"));
        const Wind* w = wind.is_none() ? nullptr : &wind.cast<const Wind&>();
        if (s && !w) throw py::type_error("gas_map: scoring against a source needs wind=");
        if (s)
          methods::check_grid_memory(map, o.cell,
                                     methods::kGdmBytesPerCell + run::kScoreBytesPerCell);
        methods::GdmMaps maps;
        std::optional<run::MapScore> score;
        {
          ReleasedGil release;
          maps = methods::kernel_dmv(map, samples, o);
          if (s)
            score = run::score_mean(maps.mean,
                                    run::true_mean_plume(map, w->field, *s, maps.mean.shape));
        }
        py::dict out;
        out["mean"] = grid_array(maps.mean.values, maps.mean.shape);
        out["variance"] = grid_array(maps.variance.values, maps.variance.shape);
        out["confidence"] = grid_array(maps.confidence.values, maps.confidence.shape);
        py::list estimates;
        for (const methods::SourceEstimate& e : methods::source_estimates(maps))
          estimates.append(py::make_tuple(e.name, from_point(map.to_frame(e.position))));
        out["source_estimates"] = estimates;
        out["samples_outside_arena"] = maps.outside_arena;
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
      "and the six 'source_estimates', and 'samples_outside_arena' (counted: their kernels reach "
      "in); with source= and wind= (a Wind of the map) also the "
      "'kl_distance' and 'rmse' against the true mean plume.");
}

}  // namespace plumekit::python
