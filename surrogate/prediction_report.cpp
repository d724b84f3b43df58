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
  const float peak_std = *std::max_element(p.std.begin(), p.std.end());
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
            {"peak_std", peak_std},
            {"mean_at_source", p.mean_at(run.source)},
            {"predict_s", run.predict_s},
            {"seconds", run.seconds}};
  std::ostringstream text;
  text << std::setprecision(4) << "wrote " << run.out << "/{mean,std}.npy, plume.png: peak mean "
       << p.mean[peak] << " at (" << peak_at.x << ", " << peak_at.y << "), peak std " << peak_std
       << (unit.empty() ? "" : " [" + unit + "]") << "; network " << run.predict_s * 1e3
       << " ms, total " << run.seconds << " s";
  r.text = text.str();
  return r;
}

}  // namespace plumekit::surrogate
