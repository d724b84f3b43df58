#include "run/report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/output_target.hpp"
#include "map/map_json.hpp"
#include "map/map_render.hpp"
#include "run/evaluation_html.hpp"
#include "run/render.hpp"
#include "run/run_tracks.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

ordered_json finite_or_null(double v) {
  return std::isfinite(v) ? ordered_json(v) : ordered_json();
}

namespace {

std::string fmt(double v, int digits = 2) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string fmt(Vec2 p) {
  return "(" + fmt(p.x) + ", " + fmt(p.y) + ")";
}

ordered_json point_json(Vec2 p) {
  return ordered_json::array({p.x, p.y});
}

// A grid's cell, m; null where there is none (0).
ordered_json cell_json(double cell) {
  return cell > 0.0 ? ordered_json(cell) : ordered_json(nullptr);
}

// The candidate source grid of a table model; null for the Gaussian plume (MH on the bins).
ordered_json source_cell_json(const SteOptions& o) {
  return cell_json(o.source_cell_in_use());
}

// Every position a report holds is in the map's frame (MapFrame).
ordered_json steps_json(const MapFrame& f, const std::vector<Step>& steps) {
  ordered_json out = ordered_json::array();
  for (const Step& s : steps) {
    out.push_back({{"position", point_json(f.to_frame(s.position))},
                   {"recorded_position", point_json(f.to_frame(s.recorded))},
                   {"value", s.value},
                   {"wind", {s.wind.x, s.wind.y}},
                   {"arrived_s", s.arrived_s},
                   {"time_s", s.time_s},
                   {"distance_m", s.distance_m},
                   {"estimate", point_json(f.to_frame(s.estimate))},
                   {"entropy", s.entropy},
                   {"compute_s", s.compute_s}});
    // The readings on the way here, each [x, y, recorded x, recorded y, time_s, value].
    if (s.on_the_way.empty()) continue;
    ordered_json passing = ordered_json::array();
    for (const PassingRecord& r : s.on_the_way) {
      const Vec2 p = f.to_frame(r.position), q = f.to_frame(r.recorded);
      passing.push_back({p.x, p.y, q.x, q.y, r.time_s, r.value});
    }
    out.back()["on_the_way"] = std::move(passing);
  }
  return out;
}

// A team's robots: each one's start, path and samples, and how it ended.
ordered_json team_json(const MapFrame& f, const LocalizationResult& r) {
  ordered_json robots = ordered_json::array();
  for (const TeamRobot& t : r.team)
    robots.push_back({{"start", point_json(f.to_frame(t.start))},
                      {"samples", t.steps.size()},
                      {"distance_m", t.distance_m},
                      {"stopped_by", t.stopped_by},
                      {"estimate", point_json(f.to_frame(t.estimate))},
                      {"entropy", t.entropy},
                      {"swaps", t.swaps},
                      {"waited_s", t.waited_s},
                      {"closest_m", finite_or_null(t.closest_m)},
                      {"steps", steps_json(f, t.steps)}});
  return {{"robots", r.team.size()},
          {"strategy", r.strategy},
          {"declared_by", r.declared_by},
          {"members", robots}};
}

// null: the run never got there.
ordered_json mission_times_json(const MissionTimes& t) {
  return {{"first_detection_s", finite_or_null(t.first_detection_s)},
          {"within_1m_s", finite_or_null(t.within_1m_s)},
          {"within_0_5m_s", finite_or_null(t.within_0_5m_s)},
          {"declared_s", t.declared_s},
          {"optimum_s", finite_or_null(t.optimum_s)},
          {"over_optimum", finite_or_null(t.over_optimum())},
          {"gsl_bench_success", t.gsl_bench_success()}};
}

ordered_json run_json(const Scenario& sc, Vec2 source, const LocalizationResult& r) {
  ordered_json expected = ordered_json::object();
  if (sc.has_model()) {
    const auto& params = sc.model().parameters();
    for (std::size_t k = 0; k < params.size() && k < r.expected.size(); ++k)
      expected[params[k].name] = r.expected[k];
  }
  const MapFrame& f = sc.map().frame;
  if (!f.is_identity() && expected.contains("x") && expected.contains("y")) {
    const Vec2 at = f.to_frame({expected["x"].get<double>(), expected["y"].get<double>()});
    expected["x"] = at.x;
    expected["y"] = at.y;
  }
  ordered_json j{{"method", r.method},
                 {"estimate", point_json(f.to_frame(r.estimate))},
                 {"error_m", norm(r.estimate - source)},
                 {"reached_source_box", r.reached},
                 {"samples", r.samples},
                 {"distance_m", r.distance_m},
                 {"compute_s", r.compute_s},
                 {"stopped_by", r.stopped_by},
                 {"median_step_s", r.median_step_s},
                 {"mission_s", r.time_s},
                 {"times", mission_times_json(r.times)},
                 {"map_estimate", point_json(f.to_frame(r.map))},
                 {"source_cell", source_cell_json(sc.options())},
                 {"table_cell", cell_json(sc.table_cell())},
                 {"expected_parameters", expected},
                 {"entropy", r.posterior.entropy},
                 {"max_entropy", r.posterior.max_entropy},
                 {"seen_mass", r.posterior.seen_mass},
                 {"start", point_json(f.to_frame(r.start))},
                 {"source", point_json(f.to_frame(source))},
                 {"wind_s", sc.wind_s()},
                 {"table_build_s", sc.model_build_s()},
                 {"steps", steps_json(f, r.steps)}};
  // A team's samples and distance are summed over its robots, its mission time runs to the
  // declaration, and "steps" are those of the robot whose estimate it declares.
  if (!r.team.empty()) j["team"] = team_json(f, r);
  if (!r.approach.empty()) {  // the drive to the estimate after the last step (--approach)
    ordered_json way = ordered_json::array();
    for (Vec2 p : r.approach)
      way.push_back(point_json(f.to_frame(p)));
    j["drive_to_estimate"] = {{"path", way}, {"drive_s", r.approach_s}};
  }
  return j;
}

ordered_json times_json(const RunTimes& t) {
  return {{"total_s", t.total_s},
          {"wind_s", t.wind_s},
          {"model_build_s", t.model_build_s},
          {"plume_simulation_s", t.plume_s},
          {"decisions_s", t.decisions_s},
          {"other_s", t.other_s}};
}

// "time 43.0 s: wind 5.1 s + model build 13.4 s + ...", in tenths of a second that add up as
// printed (the rest takes the rounding).
std::string times_text(const RunTimes& t) {
  const auto tenths = [](double s) { return std::llround(10.0 * s); };
  const std::pair<const char*, double> parts[] = {{"wind", t.wind_s},
                                                  {"model build", t.model_build_s},
                                                  {"plume simulation", t.plume_s},
                                                  {"decisions", t.decisions_s}};
  long long total = tenths(t.total_s), sum = 0;
  for (const auto& [name, s] : parts)
    sum += tenths(s);
  total = std::max(total, sum);
  const auto shown = [](long long n) { return fmt(static_cast<double>(n) / 10.0, 1) + " s"; };
  std::string text = "time " + shown(total) + " (wall clock):";
  for (const auto& [name, s] : parts)
    text += std::string(" ") + name + " " + shown(tenths(s)) + " +";
  return text + " other " + shown(total - sum);
}

// "mission 112 s, 6.6 times the shortest way's 17 s; within 1 m of the source after 60 s": the
// field's time metrics (issue 47), in words; with an approach, the declaration and the arrival.
std::string mission_time_text(const LocalizationResult& r) {
  const MissionTimes& t = r.times;
  std::string text = r.approach_s > 0.0
                         ? "declared after " + fmt(t.declared_s, 0) + " s, at its estimate after " +
                               fmt(t.ended_s, 0) + " s"
                         : "mission " + fmt(t.ended_s, 0) + " s";
  if (std::isfinite(t.over_optimum()))
    text +=
        ", " + fmt(t.over_optimum(), 1) + " times the shortest way's " + fmt(t.optimum_s, 0) + " s";
  return text + (std::isnan(t.within_1m_s)
                     ? "; never within 1 m of the source"
                     : "; within 1 m of the source after " + fmt(t.within_1m_s, 0) + " s");
}

std::string run_text(const Scenario& sc, Vec2 source, const LocalizationResult& r,
                     const RunTimes& times) {
  const MapFrame& f = sc.map().frame;
  std::ostringstream h;
  h << sc.map().name << ", " << run_label(sc.options())
    << (sc.has_model() ? " plume model" : " method") << ": source " << fmt(f.to_frame(source))
    << ", start " << fmt(f.to_frame(r.start)) << "\n"
    << "estimate " << fmt(f.to_frame(r.estimate)) << ", error " << fmt(norm(r.estimate - source))
    << " m after " << r.samples << " samples and " << fmt(r.distance_m, 1) << " m (stopped by "
    << r.stopped_by << ")\n"
    << mission_time_text(r) << "\n";
  if (!r.team.empty()) {
    h << r.team.size() << " " << r.strategy << " robots (samples and metres summed; robot "
      << r.declared_by + 1 << "'s estimate, at " << fmt(r.time_s, 0) << " s):";
    for (std::size_t k = 0; k < r.team.size(); ++k)
      h << (k ? "," : "") << " robot " << k + 1 << " " << r.team[k].steps.size() << " samples "
        << fmt(r.team[k].distance_m, 1) << " m";
    h << "\n";
  }
  h << times_text(times) << "; decision compute median " << fmt(r.median_step_s * 1000, 1)
    << " ms a step";
  return h.str();
}

// `tracking`: a plume tracker's runs, which have the source box and the distance overhead too.
ordered_json stats_json(const Stats& s, bool tracking) {
  ordered_json j{{"runs", s.runs},
                 {"median_error_m", s.median_error_m},
                 {"mean_error_m", s.mean_error_m},
                 {"success_0_5m", s.success_0_5},
                 {"success_0_5m_ci95", {s.success_0_5_ci95.lo, s.success_0_5_ci95.hi}},
                 {"success_1_0m", s.success_1_0},
                 {"success_1_0m_ci95", {s.success_1_0_ci95.lo, s.success_1_0_ci95.hi}},
                 {"median_samples", s.median_samples},
                 {"median_distance_m", s.median_distance_m},
                 {"median_mission_s", s.median_mission_s},
                 {"entropy_stops", s.entropy_stops}};
  j["median_time_to_detection_s"] = finite_or_null(s.median_first_detection_s);
  j["detected_runs"] = s.detected_runs;
  j["median_time_to_1m_s"] = finite_or_null(s.median_within_1m_s);
  j["within_1m_runs"] = s.within_1m_runs;
  j["median_time_to_0_5m_s"] = finite_or_null(s.median_within_0_5m_s);
  j["within_0_5m_runs"] = s.within_0_5m_runs;
  j["median_mission_over_optimum"] = finite_or_null(s.median_over_optimum);
  j["gsl_bench_success"] = s.gsl_bench_success;
  j["gsl_bench_success_ci95"] = {s.gsl_bench_success_ci95.lo, s.gsl_bench_success_ci95.hi};
  if (tracking) {
    j["reached_source_box"] = s.reached;
    j["reached_source_box_ci95"] = {s.reached_ci95.lo, s.reached_ci95.hi};
    j["median_distance_overhead"] = finite_or_null(s.median_distance_overhead);
    j["distance_overhead_runs"] = s.distance_overhead_runs;
  }
  return j;
}

// The errors (or sample counts) of each map's runs, in map order: the box plots' groups.
std::vector<std::vector<double>> per_map(const EvaluationResult& res, bool errors) {
  std::vector<std::vector<double>> groups(res.maps.size());
  for (const RunRecord& r : res.runs)
    groups.at(r.map_index).push_back(errors ? r.error_m : r.samples);
  return groups;
}

// The options of a method other than STE, for its summary: the step and detection threshold
// they share, the method's own (its registry entry's options_json), the step budget.
ordered_json method_options_json(const MethodOptions& m) {
  const methods::TrackingOptions& t = m.tracking;
  ordered_json j{{"step_m", t.step}, {"detection_threshold", t.detection_threshold}};
  const methods::MethodSpec& spec = methods::find_method(m.name);
  if (spec.options_json) spec.options_json(m, j);
  j["max_steps"] = m.max_steps;  // 0: auto (MethodOptions::max_steps_in_use)
  return j;
}

std::string evaluation_table(const EvaluationResult& res, const std::string& label,
                             const fs::path& out, bool pictures) {
  std::ostringstream h;
  h << "evaluated " << res.runs.size() << " runs (" << res.maps.size() << " maps, " << label << ")";
  if (res.methods_together > 1) {  // the wall time is all the methods': this one's own parts
    h << ": model build " << fmt(res.model_build_s(), 1) << " s, decisions "
      << fmt(res.decisions_s, 1) << " s summed over its runs (the " << res.methods_together
      << " methods ran together; their total time is below)\n";
  } else {
    h << " in " << fmt(res.wall_s, 1) << " s\n";
  }
  h << std::left << std::setw(22) << "map"
    << " median_err  mean_err  ok@0.5  (95% CI)  ok@1.0  (95% CI)  samples"
    << "  dist_m  time_s  t@1m_s  x_opt  gsl300  step_ms  table_s"
    << (res.tracking() ? "  reached   d_o" : "") << "\n";
  auto ci = [](const Interval& i) {
    return "(" + fmt(100 * i.lo, 0) + "-" + fmt(100 * i.hi, 0) + ")";
  };
  auto line = [&](const std::string& name, const Stats& s, double table) {
    h << std::left << std::setw(22) << name << std::right << std::setw(11) << fmt(s.median_error_m)
      << std::setw(10) << fmt(s.mean_error_m) << std::setw(8) << fmt(100 * s.success_0_5, 0) + "%"
      << std::setw(10) << ci(s.success_0_5_ci95) << std::setw(8)
      << fmt(100 * s.success_1_0, 0) + "%" << std::setw(10) << ci(s.success_1_0_ci95)
      << std::setw(9) << fmt(s.median_samples, 0) << std::setw(8) << fmt(s.median_distance_m, 1)
      << std::setw(8) << fmt(s.median_mission_s, 0) << std::setw(8)
      << (std::isfinite(s.median_within_1m_s) ? fmt(s.median_within_1m_s, 0) : std::string("-"))
      << std::setw(7)
      << (std::isfinite(s.median_over_optimum) ? fmt(s.median_over_optimum, 1) : std::string("-"))
      << std::setw(8) << fmt(100 * s.gsl_bench_success, 0) + "%" << std::setw(9)
      << fmt(1000 * s.median_step_s, 1) << std::setw(9)
      << (table >= 0 ? fmt(table, 1) : std::string("-"));
    if (res.tracking())
      h << std::setw(9) << fmt(100 * s.reached, 0) + "%" << std::setw(6)
        << (std::isfinite(s.median_distance_overhead) ? fmt(s.median_distance_overhead)
                                                      : std::string("-"));
    h << "\n";
  };
  for (const MapReport& mr : res.maps)
    line(mr.name, mr.stats, mr.table_build_s);
  line("overall", res.overall, -1);
  h << "wrote " << out.string()
    << "/{report.html, runs.csv, summary.json, timings.csv, timings.json, tracks.json, "
       "boxplot-error.png, boxplot-samples.png"
    << (pictures ? ", trajectories/}" : "}");
  return h.str();
}

}  // namespace

std::string summary_label(const ordered_json& settings) {
  const std::string method = settings.value("method", std::string("ste"));
  return method == "ste" ? "STE (" + settings.at("plume_model").get<std::string>() + ")" : method;
}

RunTimes run_times(const Scenario& scenario, const LocalizationResult& result, double total_s) {
  RunTimes t;
  t.wind_s = scenario.wind_s();
  t.model_build_s = scenario.model_build_s();
  t.plume_s = result.plume_s;
  t.decisions_s = result.decisions_s;
  const double parts = t.wind_s + t.model_build_s + t.plume_s + t.decisions_s;
  t.total_s = total_s > 0.0 ? total_s : t.wind_s + t.model_build_s + result.run_s;
  t.total_s = std::max(t.total_s, parts);  // clock reads a few ns apart
  t.other_s = t.total_s - parts;
  return t;
}

Report run_report(const Scenario& scenario, Vec2 source, const LocalizationResult& result,
                  double total_s) {
  const RunTimes times = run_times(scenario, result, total_s);
  Report r{run_json(scenario, source, result), run_text(scenario, source, result, times)};
  r.json["time"] = times_json(times);
  return r;
}

RunPictures write_run_pictures(const Scenario& sc, Vec2 source, const LocalizationResult& r,
                               const fs::path& dir) {
  RunPictures p{dir / "trajectory.png", {}};
  const RunToDraw run = run_to_draw(sc.map(), r, source, run_label(sc.options()));
  write_png(draw_trajectory(sc.map(), sc.mean_plume(source), run), p.trajectory);
  if (!r.posterior.marginal.values.empty()) {
    p.posterior = dir / "posterior.png";
    write_png(draw_posterior(sc.map(), run), p.posterior);
  }
  return p;
}

MapFolder read_map_folder(const fs::path& dir) {
  std::error_code ec;
  if (dir.empty()) throw OptionError("evaluation.map_dir", "name a folder of map files");
  if (!fs::is_directory(dir, ec))
    throw OptionError("evaluation.map_dir", dir.string() + " is not a directory");
  MapFolder f;
  // Hidden files are not maps: `plumekit maps random --out DIR` leaves its output marker there.
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".json" && e.path().filename().string()[0] != '.')
      f.files.push_back(e.path());
  std::sort(f.files.begin(), f.files.end());
  if (f.files.empty())
    throw OptionError("evaluation.map_dir", "no *.json map files in " + dir.string());
  std::vector<std::string> taken;
  for (const fs::path& file : f.files) {
    f.maps.push_back(read_map(file));
    f.picture_names.push_back(safe_file_name(file.stem().string(), taken) + ".png");
  }
  return f;
}

const RunRecord& median_run(const std::vector<RunRecord>& runs) {
  std::vector<const RunRecord*> sorted;
  for (const RunRecord& r : runs)
    sorted.push_back(&r);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](auto* a, auto* b) { return a->error_m < b->error_m; });
  return *sorted.at((sorted.size() - 1) / 2);
}

std::string median_run_note(const std::vector<RunRecord>& runs) {
  std::vector<const RunRecord*> all;
  for (const RunRecord& r : runs)
    all.push_back(&r);
  return "median run of " + std::to_string(runs.size()) + "; map median " +
         fmt(summarise(all).median_error_m) + " m";
}

AfterMap trajectory_pictures(const fs::path& dir, const std::vector<std::string>& picture_names) {
  return [dir, picture_names](const Scenario& sc, const std::vector<RunRecord>& runs) {
    const RunRecord& r = median_run(runs);
    fs::create_directories(dir / "trajectories");
    write_png(draw_trajectory(sc.map(), sc.mean_plume(r.source),
                              run_to_draw(r, run_label(sc.options()), median_run_note(runs))),
              dir / "trajectories" / picture_names.at(r.map_index));
  };
}

void sampling_json(const SteOptions& o, ordered_json& j) {
  SteOptions thesis;
  set_protocol(thesis, SamplingProtocol::Thesis);
  if (o.protocol == SamplingProtocol::Thesis &&
      o.world.read_while_moving == thesis.world.read_while_moving &&
      o.world.adaptive_stop == thesis.world.adaptive_stop &&
      o.stop.confidence_radius == thesis.stop.confidence_radius && o.approach == thesis.approach)
    return;
  j["protocol"] = to_string(o.protocol);
  j["read_while_moving"] = o.world.read_while_moving;
  j["adaptive_stops"] = o.world.adaptive_stop;
  j["confidence_radius"] = o.stop.confidence_radius;
  j["confidence_mass"] = o.stop.confidence_mass;
  j["approach"] = o.approach;
}

ordered_json evaluation_settings(const EvaluationOptions& eo, const fs::path& map_dir) {
  const ste::LikelihoodOptions l = eo.ste.likelihood_options();
  ordered_json j{{"ok", true},
                 {"map_dir", provenance_path(map_dir)},
                 {"method", eo.ste.method.name},
                 {"plume_model", to_string(eo.ste.model)},
                 {"runs_per_source", eo.runs},
                 {"sources_per_map",
                  eo.source_count > 0 ? ordered_json(eo.source_count) : ordered_json("all")},
                 {"seed", eo.seed},
                 {"seeds", eo.seeds},
                 {"sigma_m", l.sigma_m},
                 {"sigma_rel", l.sigma_rel},
                 {"sigma_std", l.sigma_std},
                 {"source_cell", source_cell_json(eo.ste)},
                 {"noise", eo.ste.world.noise},
                 {"occlusion", eo.ste.world.filament.occlusion},
                 {"wind_model", eo.ste.world.filament.unsteady_wind ? "unsteady" : "steady"},
                 {"gas_sensor", eo.ste.world.sensor.name},
                 {"sensor_baseline", eo.ste.world.sensor.baseline}};
  // Only when set, so that the summaries written before them keep their bytes.
  if (eo.ste.world.filament.release_rate != world::FilamentOptions{}.release_rate)
    j["release_rate"] = eo.ste.world.filament.release_rate;
  if (eo.ste.success_radius > 0.0) j["success_radius"] = eo.ste.success_radius;
  sampling_json(eo.ste, j);
  if (eo.ste.uses_cnn())
    j["cnn"] = provenance_path(eo.ste.model_path);  // which network, for a result to be remade
  if (eo.ste.team.robots > 1)
    j["team"] = {{"robots", eo.ste.team.robots},
                 {"strategy", to_string(eo.ste.team.strategy)},
                 {"separation_m", eo.ste.team.separation},
                 {"patience_s", eo.ste.team.patience_s}};
  if (!uses_plume_model(eo.ste.method.name)) {
    // The plume model's settings mean nothing to a method without one.
    for (const char* key : {"plume_model", "sigma_m", "sigma_rel", "sigma_std", "source_cell"})
      j.erase(key);
    j["method_options"] = method_options_json(eo.ste.method);
  }
  return j;
}

Report evaluation_report(const EvaluationResult& res, const ordered_json& settings,
                         const fs::path& out, bool pictures) {
  ordered_json maps = ordered_json::array();
  for (const MapReport& mr : res.maps) {
    ordered_json j{{"map", mr.name}};
    j.update(stats_json(mr.stats, res.tracking()));
    maps.push_back(j);
  }
  ordered_json summary = settings;
  summary["overall"] = stats_json(res.overall, res.tracking());
  summary["maps"] = maps;
  return {summary, evaluation_table(res, summary_label(settings), out, pictures)};
}

Report evaluation_report(const EvaluationResult& res, const EvaluationOptions& eo,
                         const fs::path& map_dir, const fs::path& out) {
  return evaluation_report(res, evaluation_settings(eo, map_dir), out);
}

ordered_json evaluation_timings(const EvaluationResult& res) {
  ordered_json maps = ordered_json::array();
  for (const MapReport& mr : res.maps)
    maps.push_back({{"map", mr.name},
                    {"median_step_compute_s", mr.stats.median_step_s},
                    {"wind_s", mr.wind_s},
                    {"table_build_s", mr.table_build_s},
                    {"wall_s", mr.wall_s}});
  return {{"threads", res.threads},
          {"wall_s", res.wall_s},
          {"median_step_compute_s", res.overall.median_step_s},
          {"maps", maps}};
}

void write_evaluation_files(const fs::path& dir, const EvaluationResult& res,
                            const EvaluationFiles& files) {
  std::vector<std::string> labels;
  for (std::size_t m = 0; m < res.maps.size(); ++m)
    labels.push_back(res.maps[m].name);
  const std::string label = summary_label(files.summary);
  write_file_atomic(dir / "runs.csv", files.runs_csv);
  write_file_atomic(dir / "summary.json", files.summary.dump(2) + "\n");
  write_file_atomic(dir / "timings.csv", files.timings_csv);
  write_file_atomic(dir / "timings.json", files.timings.dump(2) + "\n");
  write_file_atomic(dir / kTracksFile, files.tracks.dump() + "\n");
  write_file_atomic(
      dir / kReportFile,
      evaluation_html({{res.method, files.summary, &res, &files.tracks, files.replays}}));
  write_png(draw_box_plot(per_map(res, true), labels, "error [m]",
                          label + " localization error per map", 0.5),
            dir / "boxplot-error.png");
  write_png(draw_box_plot(per_map(res, false), labels, "samples", label + " samples per map"),
            dir / "boxplot-samples.png");
}

}  // namespace plumekit::run
