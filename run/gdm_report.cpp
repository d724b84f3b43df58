#include "run/gdm_report.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace plumekit::run {

namespace {

nlohmann::ordered_json point(Vec2 p) {
  return nlohmann::ordered_json::array({p.x, p.y});
}

}  // namespace

std::string method_name(const methods::GdmOptions& options,
                        const std::vector<methods::Sample>& samples) {
  bool wind = false;
  for (const methods::Sample& s : samples)
    wind = wind || s.wind.has_value();
  return options.wind_stretch > 0.0 && wind ? "Kernel DM+V/W" : "Kernel DM+V";
}

Report gdm_report(const Map& map, const methods::GdmMaps& maps, const GdmRun& run) {
  using nlohmann::ordered_json;
  const methods::GdmOptions& o = run.options;
  ordered_json j{{"ok", true},
                 {"map", run.map_file},
                 {"samples_file", run.samples_file},
                 {"samples", maps.samples},
                 {"samples_outside_arena", maps.outside_arena},
                 {"grid", {maps.mean.shape.nx, maps.mean.shape.ny}},
                 {"cell", o.cell},
                 {"kernel_width", o.kernel_width},
                 {"sigma_omega", o.sigma_omega},
                 {"wind_stretch", o.wind_stretch},
                 {"background", to_string(o.background)},
                 {"background_mean", maps.background_mean},
                 {"background_variance", maps.background_variance}};
  std::ostringstream text;
  text << std::setprecision(3) << "mapped " << maps.samples << " samples on " << maps.mean.shape.nx
       << " x " << maps.mean.shape.ny << " cells";
  if (maps.outside_arena > 0)
    text << " (" << maps.outside_arena
         << " of them outside the map's arena: counted, their kernels reach in)";
  ordered_json estimates = ordered_json::array();
  for (const methods::SourceEstimate& e : methods::source_estimates(maps)) {
    ordered_json entry{{"name", e.name}, {"position", point(map.to_frame(e.position))}};
    if (e.name.rfind("90%", 0) == 0)
      entry["extent"] = {point(map.to_frame(e.lo)), point(map.to_frame(e.hi))};
    if (run.source) entry["error_m"] = norm(e.position - *run.source);
    estimates.push_back(entry);
  }
  j["source_estimates"] = estimates;
  if (run.source) j["source"] = point(map.to_frame(*run.source));
  if (run.score) {
    j["score"] = {{"kl_distance", run.score->kl_distance},
                  {"rmse", run.score->rmse},
                  {"truth_peak", run.score->truth_peak}};
    text << "; against the true mean plume: KL distance " << run.score->kl_distance << ", RMSE "
         << run.score->rmse << " (truth peak " << run.score->truth_peak << ")";
  }
  if (run.source) {
    text << "; peak variance " << estimates[1].value("error_m", 0.0) << " m from the source";
  }
  if (!run.out.empty()) j["out"] = run.out;
  return {j, text.str()};
}

}  // namespace plumekit::run
