// plumekit predict: the surrogate CNN's plume (mean and std concentration) for one source in a map.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/map_json.hpp"
#include "core/map_render.hpp"
#include "core/npy.hpp"
#include "core/output_target.hpp"
#include "surrogate/plume_model.hpp"

namespace plumekit::cli {

namespace {

namespace fs = std::filesystem;
using surrogate::PlumePrediction;

}  // namespace

void add_predict_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "predict",
      "The surrogate CNN's plume for one source: mean.npy, std.npy (float32 [64,64], row 0 at "
      "y = 0) and plume.png");
  struct Args {
    std::string model = (data_dir() / "models" / "plume-unet.pkcnn").string();
    std::string map = default_map().string();
    std::string source;
    std::string out;
    int threads = 1;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--model", a->model, "Model file (plumekit-cnn/1)")->capture_default_str();
  cmd->add_option("--map", a->map, "Map file (JSON)")->capture_default_str();
  cmd->add_option("--source", a->source, "Source position X,Y in metres")->required();
  cmd->add_option("--out,-o", a->out, "Output folder: new, empty, or an earlier `predict` output")
      ->required();
  cmd->add_option("--threads", a->threads, "Engine threads")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  add_common_flags(cmd);
  cmd->callback([a] {
    const auto start = std::chrono::steady_clock::now();
    const Vec2 source = parse_point(a->source, "--source");
    std::error_code ec;
    if (!fs::exists(a->model, ec)) {
      throw InputError(a->model + ": no such model file" +
                       std::string(a->model == (data_dir() / "models" / "plume-unet.pkcnn").string()
                                       ? " (the shipped model is not there yet: train one as "
                                         "surrogate/README.md says, or give --model)"
                                       : ""));
    }
    const Map map = read_map(a->map);
    OutputDirectory out(a->out, "predict", {a->map, a->model});
    auto network = std::make_shared<const surrogate::Network>(
        surrogate::Network::load(a->model, surrogate::EngineOptions{a->threads}));
    std::unique_ptr<surrogate::PlumeModel> model;
    try {
      model = std::make_unique<surrogate::PlumeModel>(network, map);
    } catch (const InputError& e) {
      throw InputError(a->model + ": " + e.what());
    }
    const auto t0 = std::chrono::steady_clock::now();
    const PlumePrediction p = model->predict(source);
    const double predict_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    const GridShape& g = p.grid;
    const std::vector<std::size_t> shape{static_cast<std::size_t>(g.ny),
                                         static_cast<std::size_t>(g.nx)};
    const auto peak = std::max_element(p.mean.begin(), p.mean.end()) - p.mean.begin();
    const Vec2 peak_at = g.centre(static_cast<int>(peak % g.nx), static_cast<int>(peak / g.nx));
    const float peak_std = *std::max_element(p.std.begin(), p.std.end());
    const auto& outs = network->file().outputs;
    std::string unit;
    for (const auto& o : outs)
      if (o.name == "mean") unit = o.unit;

    const Picture image = draw_plume(map, g, p.mean, p.std, source, "surrogate", unit);

    const fs::path& dir = out.open();
    write_file_atomic(dir / "mean.npy", npy_float32(p.mean, shape));
    write_file_atomic(dir / "std.npy", npy_float32(p.std, shape));
    write_png(image, dir / "plume.png");
    out.commit();

    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::ordered_json j{{"ok", true},
                             {"model", a->model},
                             {"model_sha256", network->file().sha256_hex},
                             {"map", a->map},
                             {"source", {source.x, source.y}},
                             {"out", a->out},
                             {"grid", {g.ny, g.nx}},
                             {"unit", unit},
                             {"peak_mean", p.mean[peak]},
                             {"peak_mean_at", {peak_at.x, peak_at.y}},
                             {"peak_std", peak_std},
                             {"mean_at_source", p.mean_at(source)},
                             {"predict_seconds", predict_s},
                             {"seconds", seconds}};
    std::ostringstream human;
    human << std::setprecision(4) << "wrote " << a->out << "/{mean,std}.npy, plume.png: peak mean "
          << p.mean[peak] << " at (" << peak_at.x << ", " << peak_at.y << "), peak std " << peak_std
          << (unit.empty() ? "" : " [" + unit + "]") << "; network " << predict_s * 1e3
          << " ms, total " << seconds << " s";
    report(j, human.str());
  });
}

}  // namespace plumekit::cli
