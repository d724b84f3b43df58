// plumekit predict: the surrogate CNN's plume (mean and std concentration) for one source in a map.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "map/map_json.hpp"
#include "map/map_render.hpp"
#include "surrogate/plume_network.hpp"
#include "surrogate/prediction_report.hpp"

namespace plumekit::cli {

namespace {

namespace fs = std::filesystem;
using surrogate::PlumePrediction;

}  // namespace

void add_predict_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "predict",
      "The surrogate CNN's plume for one source: mean.npy, std.npy (float32 [rows, cols] on the "
      "model's grid, row 0 at y = 0) and plume.png");
  struct Args {
    std::string cnn = shipped_cnn().string();
    std::string map, source, out, wind;
    double flow_cell = surrogate::kModelWindCell;
    surrogate::EngineOptions engine;
  };
  auto a = std::make_shared<Args>();
  add_map_argument(cmd, a->map);
  add_deprecated_alias(cmd, "--map", "MAP", a->map);
  resolve_cnn_names(cmd->add_option("--cnn", a->cnn, cnn_help())->capture_default_str());
  resolve_cnn_names(add_deprecated_alias(cmd, "--model", "--cnn", a->cnn));
  cmd->add_option("--source", a->source, "Source position X,Y in metres")->required();
  cmd->add_option("--out,-o", a->out, "Output folder: new, empty, or an earlier `predict` output")
      ->required();
  add_threads_flag(cmd, a->engine.threads, "engine.threads", "Engine threads (0: one per core)");
  cmd->add_option("--wind", a->wind,
                  "A model that takes the wind (a physical-grid model): use this `plumekit flow` "
                  "output's wind instead of solving one")
      ->check(CLI::ExistingDirectory);
  bind_field(cmd,
             cmd->add_option("--flow-cell", a->flow_cell,
                             "A model that takes the wind: the flow cell its wind is solved on, m"),
             "flow.cell")
      ->capture_default_str();
  add_common_flags(cmd);
  cmd->callback([a] {
    const auto start = std::chrono::steady_clock::now();
    const Vec2 source_typed = parse_point(a->source, "--source");  // in the map's frame
    std::error_code ec;
    if (!fs::exists(a->cnn, ec)) {
      throw InputError(a->cnn + ": no such model file" +
                       std::string(a->cnn == shipped_cnn().string()
                                       ? " (the shipped model is not there yet: train one as "
                                         "docs/design/surrogate.md says, or give --cnn)"
                                       : ""));
    }
    const Map map = read_map(a->map);
    const Vec2 source = map.from_frame(source_typed);
    // Before the model and the wind: the same wording as localize's --source, in the map's frame.
    if (const std::string fault = point_fault(map, source); !fault.empty())
      throw InputError("--source: " + fault);
    OutputDirectory out(a->out, "predict", {a->map, a->cnn});
    auto network =
        std::make_shared<const surrogate::Network>(surrogate::Network::load(a->cnn, a->engine));
    // A physical-grid model reads the map's wind (solved here: well under a second on small
    // maps, tens of seconds on a large building).
    std::optional<cfd::WindField> wind;
    double flow_s = 0.0;
    if (surrogate::PlumeNetwork::takes_wind(*network)) {
      check_range(
          "flow.cell", a->flow_cell, 0.01, 1.0, "m",
          "the default is the model's wind cell, " + compact(surrogate::kModelWindCell) + " m");
      const auto tw = std::chrono::steady_clock::now();
      wind = surrogate::model_wind(map, a->flow_cell, a->wind);
      flow_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count();
    }
    std::unique_ptr<surrogate::PlumeNetwork> model;
    try {
      model = std::make_unique<surrogate::PlumeNetwork>(network, map, wind ? &*wind : nullptr);
    } catch (const surrogate::MapSizeError& e) {
      throw InputError(a->cnn + ": " + with_map_size_advice(e.what(), false));
    } catch (const InputError& e) {
      throw InputError(a->cnn + ": " + e.what());
    }
    const auto t0 = std::chrono::steady_clock::now();
    const PlumePrediction p = model->predict(source);
    const double predict_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    const GridShape& g = p.grid;
    const std::vector<std::size_t> shape{static_cast<std::size_t>(g.ny),
                                         static_cast<std::size_t>(g.nx)};
    const Picture image =
        draw_plume(map, g, p.mean, p.std, source, "surrogate", surrogate::mean_unit(*network));
    const fs::path& dir = out.open();
    write_file_atomic(dir / "mean.npy", npy_float32(p.mean, shape));
    if (!p.std.empty())
      write_file_atomic(dir / "std.npy", npy_float32(p.std, shape));  // none: mean-only
    write_png(image, dir / "plume.png");
    out.commit();

    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    Report r = surrogate::prediction_report(
        {a->cnn, a->map, a->out, source, map.frame, predict_s, seconds}, p, *network);
    if (wind) r.json["flow_s"] = flow_s;
    // Outside what the model was trained on: said, not refused.
    if (!model->warnings().empty()) {
      r.json["warnings"] = model->warnings();
      for (const std::string& w : model->warnings())
        warn(w);
    }
    report(r.json, r.text);
  });
}

}  // namespace plumekit::cli
