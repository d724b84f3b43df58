// The CNN surrogate (surrogate/): plumes predicted from a map and a source.
#include <filesystem>
#include <memory>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "core/error.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "surrogate/plume_network.hpp"
#include "surrogate/prediction_report.hpp"

namespace plumekit::python {

namespace {

// A path or str, or None for the shipped model.
std::filesystem::path cnn_path(const py::object& cnn) {
  if (cnn.is_none()) return std::filesystem::path(data_dir()) / "models" / "plume-unet.pkcnn";
  return py::str(py::module_::import("os").attr("fspath")(cnn)).cast<std::string>();
}

// The CLI's errors: a model that is not there, a model that does not fit the map, named.
std::unique_ptr<surrogate::PlumeNetwork> load_surrogate(const Map& map,
                                                        const std::filesystem::path& cnn,
                                                        int threads) {
  std::error_code ec;
  if (!std::filesystem::exists(cnn, ec)) throw InputError(cnn.string() + ": no such model file");
  surrogate::EngineOptions engine;
  engine.threads = threads;
  auto network = std::make_shared<const surrogate::Network>(surrogate::Network::load(cnn, engine));
  try {
    return std::make_unique<surrogate::PlumeNetwork>(network, map);
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

void bind_surrogate(py::module_& m) {
  py::class_<surrogate::PlumeNetwork>(
      m, "Surrogate",
      "The CNN surrogate on one map (`plumekit predict`): the network is loaded and the map's "
      "features built once, then each predict() is one forward pass.")
      .def(py::init([](const Map& map, const py::object& cnn, int threads) {
             return load_surrogate(map, cnn_path(cnn), threads);
           }),
           py::arg("map"), py::arg("cnn") = py::none(), py::arg("threads") = 1,
           "`cnn`: a plumekit-cnn model file (default: the shipped model); `threads`: the "
           "engine's threads (0: one per core).")
      .def(
          "predict",
          [](const surrogate::PlumeNetwork& net, const py::handle& source) {
            const Vec2 s = net.map().from_frame(to_point(source, "source"));
            surrogate::PlumePrediction p;
            {
              py::gil_scoped_release release;
              p = net.predict(s);
            }
            return prediction_dict(p, net.network());
          },
          py::arg("source"),
          "The plume of a source (map frame): a dict with 'mean' and 'std' float32 [64, 64] "
          "('std' None for a mean-only model) and the mean's 'unit'.")
      .def_property_readonly(
          "warnings", &surrogate::PlumeNetwork::warnings,
          "Where the map lies outside what the model was trained on (its file's trained_on), "
          "one sentence each; empty when inside it or when the file states no ranges.")
      .def(
          "features",
          [](const surrogate::PlumeNetwork& net, const py::handle& source) {
            const Vec2 s = net.map().from_frame(to_point(source, "source"));
            const std::vector<float> x = net.features(s);
            const GridShape& g = net.grid();
            py::array_t<float> out({3, g.ny, g.nx});
            std::copy(x.begin(), x.end(), out.mutable_data());
            return out;
          },
          py::arg("source"),
          "The network's input for a source (map frame): float32 [3, 64, 64], the channels of "
          "the model's feature contract (region, signed distance, the source channel in the "
          "model's form), row 0 at y = 0.");
  m.def(
      "predict",
      [](const Map& map, const py::handle& source, const py::object& cnn) {
        const auto net = load_surrogate(map, cnn_path(cnn), 1);
        const Vec2 s = map.from_frame(to_point(source, "source"));
        surrogate::PlumePrediction p;
        {
          py::gil_scoped_release release;
          p = net->predict(s);
        }
        return prediction_dict(p, net->network());
      },
      py::arg("map"), py::arg("source"), py::arg("cnn") = py::none(),
      "One prediction (`plumekit predict`); for many, make a Surrogate once.");
}

}  // namespace plumekit::python
