#pragma once
// What tunnel runs (tunnel_run.hpp) write: a run's JSON, an evaluation's runs.csv and summary,
// and pictures: a run's path seen from above (x, y) and from the side (x, z), and the
// evaluation's box plots (the errors per axis of Fig. 11.3; the tracker's times of Fig. 17.4).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "map/map_render.hpp"
#include "run/tunnel_run.hpp"

namespace plumekit::run {

// The settings a run depends on (tunnel, wind, release, method's options).
nlohmann::ordered_json tunnel_settings(const TunnelOptions& options);
// One run: source, start, estimate, errors, distance, time, samples, stopped_by, and with
// `steps` every step.
nlohmann::ordered_json tunnel_run_json(const TunnelRun& run, bool steps);
// Header and one line per run (column names in docs/methods.md, "The 3-D tunnel").
std::string tunnel_runs_csv(const std::vector<TunnelRun>& runs);
// Medians and rates over the runs: errors per axis, success (found, or within 0.5 m for STE),
// distance, mission time, samples, entropy stops, the median compute per STE step.
nlohmann::ordered_json tunnel_summary(const std::vector<TunnelRun>& runs);
// "ste-3d: error 0.21 m (x 0.1, y 0.1, z 0.12), 23 samples, 11.4 m, 163 s, stopped by entropy".
std::string tunnel_run_line(const TunnelRun& run);
// The run from above and from the side: the tunnel, the path (coloured by phase for a tracker),
// the start, the true source and the estimate; `title` over both.
Picture draw_tunnel_run(const TunnelRun& run, const world::Tunnel& tunnel,
                        const std::string& title);
// Box plots of the runs' errors per axis (STE) or mission times (a tracker).
Picture draw_tunnel_box_plot(const std::vector<TunnelRun>& runs, const std::string& title);

}  // namespace plumekit::run
