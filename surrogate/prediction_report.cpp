#include "surrogate/prediction_report.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace plumekit::surrogate {

std::string mean_unit(const Network& network) {
  for (const auto& o : network.file().outputs)
    if (o.name == "mean") return o.unit;
  return "";
}

Report prediction_report(const PredictRun& run, const PlumePrediction& p, const Network& network) {
  const GridShape& g = p.grid;
  const auto peak = std::max_element(p.mean.begin(), p.mean.end()) - p.mean.begin();
  const Vec2 peak_at =
      run.frame.to_frame(g.centre(static_cast<int>(peak % g.nx), static_cast<int>(peak / g.nx)));
  const Vec2 source = run.frame.to_frame(run.source);
  // A mean-only model has no std: null in the JSON, said in the text.
  const bool has_std = !p.std.empty();
  const float peak_std = has_std ? *std::max_element(p.std.begin(), p.std.end()) : 0.0f;
  const std::string unit = mean_unit(network);
  Report r;
  r.json = {{"ok", true},
            {"model", run.model},
            {"model_sha256", network.file().sha256_hex},
            {"map", run.map},
            {"source", {source.x, source.y}},
            {"out", run.out},
            {"grid", {g.ny, g.nx}},
            {"unit", unit},
            {"peak_mean", p.mean[peak]},
            {"peak_mean_at", {peak_at.x, peak_at.y}},
            {"peak_std", has_std ? nlohmann::ordered_json(peak_std) : nlohmann::ordered_json()},
            {"mean_at_source", p.mean_at(run.source)},
            {"predict_s", run.predict_s},
            {"seconds", run.seconds}};
  std::ostringstream text;
  text << std::setprecision(4) << "wrote " << run.out
       << (has_std ? "/{mean,std}.npy" : "/mean.npy (a mean-only model)")
       << ", plume.png: peak mean " << p.mean[peak] << " at (" << peak_at.x << ", " << peak_at.y
       << ")";
  if (has_std) text << ", peak std " << peak_std;
  text << (unit.empty() ? "" : " [" + unit + "]") << "; network " << run.predict_s * 1e3
       << " ms, total " << run.seconds << " s";
  r.text = text.str();
  return r;
}

}  // namespace plumekit::surrogate
