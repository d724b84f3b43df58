#include "run/tunnel_job.hpp"

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "core/statistics.hpp"
#include "map/map_render.hpp"
#include "run/evaluation_html.hpp"
#include "run/replay.hpp"
#include "run/replay_render.hpp"
#include "run/run_tracks.hpp"
#include "run/tunnel_page.hpp"
#include "run/tunnel_report.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

Report localize_tunnel_job(const TunnelLocalizeRequest& q) {
  q.options.validate();
  std::optional<OutputDirectory> out;
  if (!q.out.empty()) out.emplace(q.out, "localize");
  if (!q.animate.empty()) check_animation_target(q.animate, "--animate");
  std::optional<Replay> replay;
  const TunnelRun run = localize_tunnel(q.options, q.source, q.start, q.seed, 0,
                                        q.animate.empty() ? nullptr : &replay);
  ordered_json j{{"ok", true}, {"seed", q.seed}};
  j["settings"] = tunnel_settings(q.options);
  j.update(tunnel_run_json(run, false));
  std::string text = tunnel_run_line(run);
  if (out) {
    const fs::path& dir = out->open();
    ordered_json file = j;
    file.update(tunnel_run_json(run, true));
    write_file_atomic(dir / "run.json", file.dump(2) + "\n");
    write_png(draw_tunnel_run(run, q.options.tunnel, text), dir / "trajectory.png");
    if (replay) write_replay(*replay, dir);
    out->commit();
    const fs::path& d = q.out;
    j["out"] = {{"run", (d / "run.json").string()},
                {"trajectory", (d / "trajectory.png").string()}};
    if (replay) j["out"]["replay"] = (d / kReplayFile).string();
    text += "\nwrote " + (d / "trajectory.png").string() + ", " + (d / "run.json").string();
  }
  if (replay) {
    AnimateOptions a;
    a.progress = q.progress;
    report_animation(animate_replay(*replay, q.animate, "--animate", a), j, text);
  }
  return {j, text};
}

std::size_t median_tunnel_run(const std::vector<TunnelRun>& runs) {
  std::vector<double> key;
  for (const TunnelRun& r : runs)
    key.push_back(is_tracker(r.method) ? r.mission_s : r.error_m());
  const double m = median(key);
  std::size_t best = 0;
  for (std::size_t k = 1; k < key.size(); ++k)
    if (std::abs(key[k] - m) < std::abs(key[best] - m)) best = k;
  return best;
}

namespace {

// One method's folder: runs.csv, summary.json, tracks.json, the box plot, the median run's
// picture and report.html.
void write_tunnel_files(const fs::path& dir, const std::vector<TunnelRun>& runs,
                        const TunnelOptions& o, const ordered_json& summary,
                        const TunnelPageMethod& page, std::uint64_t seed) {
  write_file_atomic(dir / "runs.csv", tunnel_runs_csv(runs));
  write_file_atomic(dir / "summary.json", summary.dump(2) + "\n");
  write_file_atomic(dir / kTracksFile, tunnel_tracks_json(o.tunnel, runs).dump() + "\n");
  write_file_atomic(dir / kReportFile, tunnel_report_html({page}, seed));
  const std::string name = o.method;
  write_png(draw_tunnel_box_plot(runs, name + ", " + std::to_string(runs.size()) + " runs, wind " +
                                           compact(o.tunnel.speed) + " m/s"),
            dir / "boxplot.png");
  const std::size_t k = median_tunnel_run(runs);
  write_png(draw_tunnel_run(runs[k], o.tunnel,
                            "run " + std::to_string(k) + " (median): " + tunnel_run_line(runs[k])),
            dir / "trajectory-median.png");
}

// The human line of one method's summary `s`, written into `out`.
std::string tunnel_summary_line(const ordered_json& s, std::size_t runs, const fs::path& out) {
  std::ostringstream line;
  line.precision(3);
  line << s["method"].get<std::string>() << ": " << runs << " runs, success "
       << 100.0 * s["success"].get<double>() << " %, median error "
       << s["median_error_m"].get<double>() << " m (z " << s["median_error_z_m"].get<double>()
       << " m), median distance " << s["median_distance_m"].get<double>() << " m, median time "
       << s["median_mission_s"].get<double>() << " s\n  wrote " << out.string()
       << "/{runs.csv, summary.json, tracks.json, report.html, boxplot.png, "
          "trajectory-median.png}\n";
  return line.str();
}

// Run k's replay folder in its method's folder (--replays), relative to it.
std::string replay_folder(int k) {
  return "replays/tunnel-r" + std::to_string(k);
}

// Writes each run's replay into `dir`'s replays/ as it comes (with replay.js for the page), from
// the runs' threads: replays/ is made first, each run's folder by its own thread.
TunnelReplaySink replay_writer(const fs::path& dir) {
  fs::create_directories(dir / "replays");
  return [dir](int k, const TunnelRun&, const Replay& replay) {
    const fs::path folder = dir / replay_folder(k);
    fs::create_directories(folder);
    write_file_atomic(folder / "replay.js",
                      "plumekitReplay(" + write_replay(replay, folder) + ");\n");
  };
}

}  // namespace

Report evaluate_tunnel_job(const TunnelEvaluateRequest& q, const JobProgress& progress) {
  const std::vector<std::string>& methods = q.methods;
  const bool several = methods.size() > 1;
  std::vector<TunnelOptions> each(methods.size(), q.options);
  for (std::size_t m = 0; m < methods.size(); ++m) {
    each[m].method = methods[m];
    each[m].validate();
  }
  // Several: OUT is one output written whole, each method's folder inside its own.
  std::optional<OutputDirectory> whole;
  if (several) whole.emplace(q.out, "evaluate");
  std::vector<fs::path> outs;
  std::vector<std::unique_ptr<OutputDirectory>> dirs;
  for (const std::string& method : methods) {
    outs.push_back(several ? q.out / method : q.out);
    dirs.push_back(std::make_unique<OutputDirectory>(several ? whole->open() / method : outs.back(),
                                                     "evaluate"));
  }
  ordered_json j{{"ok", true}, {"seed", q.seed}, {"methods", ordered_json::array()}};
  std::string text;
  const int total = q.runs * static_cast<int>(methods.size());
  std::vector<std::vector<TunnelRun>> runs(methods.size());
  std::vector<TunnelPageMethod> pages;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const int before = q.runs * static_cast<int>(m);
    const fs::path& dir = dirs[m]->open();
    runs[m] = evaluate_tunnel(
        each[m], q.runs, q.seed, q.threads,
        [&](int done, int) {
          if (progress)
            progress(static_cast<double>(before + done) / total,
                     std::to_string(before + done) + "/" + std::to_string(total) + " runs");
        },
        q.replays ? replay_writer(dir) : TunnelReplaySink());
    pages.push_back({&each[m], &runs[m], {}});
    if (q.replays)
      for (int k = 0; k < q.runs; ++k)
        pages.back().replays.push_back(replay_folder(k));
    ordered_json summary{{"method", methods[m]}, {"seed", q.seed}};
    summary["settings"] = tunnel_settings(each[m]);
    summary.update(tunnel_summary(runs[m]));
    write_tunnel_files(dir, runs[m], each[m], summary, pages.back(), q.seed);
    dirs[m]->commit();
    j["methods"].push_back(summary);
    text += tunnel_summary_line(summary, runs[m].size(), outs[m]);
  }
  if (whole) {
    // The page of all methods, their replays in their folders.
    for (std::size_t m = 0; m < methods.size(); ++m)
      for (std::string& folder : pages[m].replays)
        folder = methods[m] + "/" + folder;
    write_file_atomic(whole->open() / kReportFile, tunnel_report_html(pages, q.seed));
    whole->commit();
    text += "wrote " + (q.out / kReportFile).string() + " (all methods)\n";
  }
  return {j, text};
}

}  // namespace plumekit::run
