#pragma once
// What `evaluate tunnel` writes to be browsed (docs/report.md, "The tunnel"): tracks.json and
// report.html, the page of every evaluation with the tunnel seen from above as its one map. The
// runs' heights are in tracks.json (each path's z, the source's and the estimate's) and in their
// replays, which the page plays from above and from the side.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/tunnel_run.hpp"

namespace plumekit::run {

// One method's runs as the page shows them.
struct TunnelPageMethod {
  const TunnelOptions* options;  // its method among them
  const std::vector<TunnelRun>* runs;
  // Each run's replay folder relative to the page (--replays), or none at all.
  std::vector<std::string> replays;
};

// tracks.json (format plumekit-tracks/1) of the runs: the tunnel from above as the map; per run
// its source, estimate and the robot's way from above (a path through its start and every
// reading; STE's stops with their readings), each with "_z": the heights.
nlohmann::ordered_json tunnel_tracks_json(const world::Tunnel& tunnel,
                                          const std::vector<TunnelRun>& runs);

// report.html of the methods' runs of evaluation seed `seed`: the summary (the success rates
// within 0.5 and 1 m of the source in 3-D, with their Wilson intervals; a tracker's found rate as
// its "reached"), the box plots, the runs on the tunnel and their replays.
std::string tunnel_report_html(const std::vector<TunnelPageMethod>& methods, std::uint64_t seed);

}  // namespace plumekit::run
