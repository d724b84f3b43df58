#include "run/tunnel_page.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/option_check.hpp"
#include "core/statistics.hpp"
#include "run/evaluation_html.hpp"
#include "run/run_tracks.hpp"
#include "run/tunnel_replay.hpp"
#include "run/tunnel_report.hpp"

namespace plumekit::run {

using nlohmann::ordered_json;

namespace {

ordered_json xy(Vec3 p) {
  return {track_metres(p.x), track_metres(p.y)};
}

ordered_json run_track(const TunnelRun& r) {
  ordered_json path = ordered_json::array(), path_z = ordered_json::array(),
               stops = ordered_json::array();
  path.push_back(track_metres(r.start.x));
  path.push_back(track_metres(r.start.y));
  path_z.push_back(track_metres(r.start.z));
  const bool tracker = is_tracker(r.method);
  for (const TunnelStep& s : r.steps) {
    path.push_back(track_metres(s.position.x));
    path.push_back(track_metres(s.position.y));
    path_z.push_back(track_metres(s.position.z));
    if (tracker) continue;  // a tracker's readings are its way's, not stops
    stops.push_back(track_metres(s.position.x));
    stops.push_back(track_metres(s.position.y));
    stops.push_back(track_reading(s.gas));
    stops.push_back(track_metres(s.time_s));
  }
  return {
      {"source", xy(r.source)},
      {"estimate", xy(r.estimate)},
      {"source_z", track_metres(r.source.z)},
      {"estimate_z", track_metres(r.estimate.z)},
      {"robots",
       {{{"path", std::move(path)}, {"path_z", std::move(path_z)}, {"stops", std::move(stops)}}}}};
}

// The page's summary figures of the runs (its columns, docs/report.md).
ordered_json page_stats(const std::vector<TunnelRun>& runs) {
  std::vector<double> error, samples, distance, mission;
  double error_sum = 0.0;
  int within_half = 0, within_one = 0, found = 0;
  for (const TunnelRun& r : runs) {
    error.push_back(r.error_m());
    error_sum += r.error_m();
    samples.push_back(static_cast<double>(r.steps.size()));
    distance.push_back(r.distance_m);
    mission.push_back(r.mission_s);
    within_half += r.error_m() <= 0.5;
    within_one += r.error_m() <= 1.0;
    found += r.found();
  }
  const int n = static_cast<int>(runs.size());
  const auto rate = [&](int k) { return n > 0 ? static_cast<double>(k) / n : 0.0; };
  const auto ci = [&](int k) {
    const Interval i = wilson_interval(k, n);
    return ordered_json::array({i.lo, i.hi});
  };
  ordered_json s{{"runs", n},
                 {"median_error_m", median(error)},
                 {"mean_error_m", n > 0 ? error_sum / n : 0.0},
                 {"success_0_5m", rate(within_half)},
                 {"success_0_5m_ci95", ci(within_half)},
                 {"success_1_0m", rate(within_one)},
                 {"success_1_0m_ci95", ci(within_one)},
                 {"median_samples", median(samples)},
                 {"median_distance_m", median(distance)},
                 {"median_mission_s", median(mission)}};
  if (!runs.empty() && is_tracker(runs.front().method)) {
    s["reached_source_box"] = rate(found);
    s["reached_source_box_ci95"] = ci(found);
  }
  return s;
}

// A summary as the page reads it: the settings flat (the tunnel's size as words), the figures
// over all runs and on the one map.
ordered_json page_summary(const TunnelPageMethod& m, std::uint64_t seed) {
  ordered_json s{{"method", m.options->method}, {"seed", seed}};
  const ordered_json settings = tunnel_settings(*m.options);
  for (const auto& [key, value] : settings.items())
    if (!value.is_structured()) s[key] = value;
  const world::Tunnel& t = m.options->tunnel;
  s["tunnel"] = compact(t.length) + " x " + compact(t.width) + " x " + compact(t.height) + " m";
  ordered_json stats = page_stats(*m.runs);
  s["overall"] = stats;
  stats["map"] = "tunnel";
  s["maps"] = ordered_json::array({stats});
  return s;
}

}  // namespace

ordered_json tunnel_tracks_json(const world::Tunnel& tunnel, const std::vector<TunnelRun>& runs) {
  Map map = tunnel_map(tunnel);
  ordered_json j{{"format", kTracksFormat},
                 {"maps", ordered_json::array({map_geometry_json(map)})},
                 {"runs", ordered_json::array()}};
  for (const TunnelRun& r : runs)
    j["runs"].push_back(run_track(r));
  return j;
}

std::string tunnel_report_html(const std::vector<TunnelPageMethod>& methods, std::uint64_t seed) {
  if (methods.empty()) throw std::logic_error("tunnel_report_html: no method");
  // The page of any evaluation: each run a row on map 0, its own random source.
  std::vector<EvaluationResult> results(methods.size());
  std::vector<ordered_json> tracks(methods.size());
  std::vector<ReportMethod> page;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const TunnelPageMethod& tm = methods[m];
    results[m].method = tm.options->method;
    for (std::size_t k = 0; k < tm.runs->size(); ++k) {
      const TunnelRun& r = (*tm.runs)[k];
      RunRecord row;
      row.map = "tunnel";
      row.source_index = static_cast<int>(k);
      row.run = static_cast<int>(k);
      row.seed = seed;
      row.error_m = r.error_m();
      row.samples = static_cast<int>(r.steps.size());
      row.distance_m = r.distance_m;
      row.mission_s = r.mission_s;
      row.stopped_by = r.stopped_by;
      results[m].runs.push_back(std::move(row));
    }
    tracks[m] = tunnel_tracks_json(tm.options->tunnel, *tm.runs);
    page.push_back(
        {tm.options->method, page_summary(tm, seed), &results[m], &tracks[m], tm.replays});
  }
  return evaluation_html(page);
}

}  // namespace plumekit::run
