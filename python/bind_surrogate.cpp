// The CNN surrogate (surrogate/): plumes predicted from a map and a source.
#include <filesystem>
#include <memory>
#include <optional>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "core/error.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "surrogate/plume_network.hpp"
#include "surrogate/prediction_report.hpp"
#include "surrogate/shipped_models.hpp"

namespace plumekit::python {

namespace {

// A path or str (a file, or a shipped model's name: "hybrid", "thesis", ...), or None for the
// default model (hybrid).
std::filesystem::path cnn_path(const py::object& cnn) {
  if (cnn.is_none()) return surrogate::default_model(data_dir());
  return surrogate::resolve_model(
      py::str(py::module_::import("os").attr("fspath")(cnn)).cast<std::string>(), data_dir());
}

// The CLI's errors: a model that is not there, a model that does not fit the map, named.
// A model that takes the wind (a physical-grid model) gets the map's, solved as `plumekit
// predict` does (surrogate::model_wind), or read from `wind` (a `plumekit flow` folder).
std::unique_ptr<surrogate::PlumeNetwork> load_surrogate(const Map& map,
                                                        const std::filesystem::path& cnn,
                                                        int threads,
                                                        const std::filesystem::path& wind = {}) {
  std::error_code ec;
  if (!std::filesystem::exists(cnn, ec)) throw InputError(cnn.string() + ": no such model file");
  surrogate::EngineOptions engine;
  engine.threads = threads;
  auto network = std::make_shared<const surrogate::Network>(surrogate::Network::load(cnn, engine));
  try {
    std::optional<cfd::WindField> field;
    if (surrogate::PlumeNetwork::takes_wind(*network))
      field = surrogate::model_wind(map, surrogate::kModelWindCell, wind);
    return std::make_unique<surrogate::PlumeNetwork>(network, map, field ? &*field : nullptr);
  } catch (const surrogate::MapSizeError& e) {
    throw InputError(cnn.string() + ": " + with_any_map_advice(e.what(), "cnn"));
  } catch (const InputError& e) {
    throw InputError(cnn.string() + ": " + e.what());
  }
}

py::dict prediction_dict(const surrogate::PlumePrediction& p, const surrogate::Network& network) {
  py::dict out;
  out["mean"] = grid_array(p.mean, p.grid);
  out["std"] = p.std.empty() ? py::object(py::none()) : py::object(grid_array(p.std, p.grid));
  out["unit"] = surrogate::mean_unit(network);
  return out;
}

}  // namespace

std::string with_any_map_advice(const std::string& message, const std::string& keyword) {
  return message + ". For a map of any size, use the default model (" + keyword + "=\"hybrid\")";
}

void bind_surrogate(py::module_& m) {
  py::class_<surrogate::PlumeNetwork>(
      m, "Surrogate",
      "The CNN surrogate on one map (`plumekit predict`): the network is loaded and the map's "
      "features built once, then each predict() is one forward pass.")
      .def(py::init([](const Map& map, const py::object& cnn, int threads, const py::object& wind) {
             const std::filesystem::path w =
                 wind.is_none()
                     ? std::filesystem::path()
                     : std::filesystem::path(py::str(py::module_::import("os").attr("fspath")(wind))
                                                 .cast<std::string>());
             const std::filesystem::path model = cnn_path(cnn);
             ReleasedGil release;  // the flow of a large map takes seconds
             return load_surrogate(map, model, threads, w);
           }),
           py::arg("map"), py::arg("cnn") = py::none(), py::arg("threads") = 1,
           py::arg("wind") = py::none(),
           "`cnn`: a plumekit-cnn model file or a shipped model's name (\"hybrid\", the "
           "default, for any map; \"thesis\", \"v2\", \"faithful\"); `threads`: the "
           "engine's threads (0: one per core); `wind`: for a model that takes the wind, a "
           "`plumekit flow` folder of this map (default: solved here, as `plumekit predict` "
           "does).")
      .def(
          "predict",
          [](const surrogate::PlumeNetwork& net, const py::handle& source) {
            const Vec2 s = net.map().from_frame(to_point(source, "source"));
            surrogate::PlumePrediction p;
            {
              ReleasedGil release;
              p = net.predict(s);
            }
            return prediction_dict(p, net.network());
          },
          py::arg("source"),
          "The plume of a source (map frame): a dict with 'mean' and 'std' float32 [rows, cols] "
          "on the model's grid over the map ([64, 64] for a thesis model; 'std' None for a "
          "mean-only model) and the mean's 'unit'.")
      .def_property_readonly(
          "warnings", &surrogate::PlumeNetwork::warnings,
          "Where the map lies outside what the model was trained on (its file's trained_on), "
          "one sentence each; empty when inside it or when the file states no ranges.")
      .def(
          "features",
          [](const surrogate::PlumeNetwork& net, const py::handle& source) {
            const Vec2 s = net.map().from_frame(to_point(source, "source"));
            const std::vector<float> x = net.features(s);
            const py::ssize_t c =
                static_cast<py::ssize_t>(x.size()) / (net.input_rows() * net.input_cols());
            py::array_t<float> out(
                {c, py::ssize_t{net.input_rows()}, py::ssize_t{net.input_cols()}});
            std::copy(x.begin(), x.end(), out.mutable_data());
            return out;
          },
          py::arg("source"),
          "The network's input for a source (map frame): float32 [channels, rows, cols], the "
          "channels of the model's feature contract (region, signed distance, [wind u, v,] the "
          "source channel in the model's form), row 0 at y = 0; [3, 64, 64] for a thesis model, "
          "the map's grid padded with zeros to the network's multiple for a physical-grid one.");
  m.def(
      "predict",
      [](const Map& map, const py::handle& source, const py::object& cnn) {
        const auto net = load_surrogate(map, cnn_path(cnn), 1);
        const Vec2 s = map.from_frame(to_point(source, "source"));
        surrogate::PlumePrediction p;
        {
          ReleasedGil release;
          p = net->predict(s);
        }
        return prediction_dict(p, net->network());
      },
      py::arg("map"), py::arg("source"), py::arg("cnn") = py::none(),
      "One prediction (`plumekit predict`); for many, make a Surrogate once.");
}

}  // namespace plumekit::python
