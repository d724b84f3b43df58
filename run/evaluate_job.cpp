#include "run/evaluate_job.hpp"

#include <iomanip>
#include <memory>
#include <optional>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/output_target.hpp"
#include "core/sha256.hpp"
#include "run/comparison.hpp"
#include "run/evaluation_html.hpp"
#include "run/evaluation_parts.hpp"
#include "run/replay.hpp"
#include "run/report.hpp"
#include "run/run_tracks.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

std::vector<std::string> evaluated_methods(const EvaluationOptions& options,
                                           const std::vector<std::string>& several) {
  return several.size() > 1 ? several : std::vector<std::string>{options.ste.method.name};
}

Report method_report(const EvaluationResult& result, EvaluationOptions options,
                     const std::string& method, const fs::path& map_dir, const fs::path& out) {
  options.ste.method.name = method;
  return evaluation_report(result, evaluation_settings(options, map_dir), out);
}

namespace {

// The output folders. With several methods OUT is one output, checked and locked like any before
// the work, and written whole, so that no earlier method's results mix with these and an
// interrupt leaves nothing; each method's folder inside is its own output.
struct Outputs {
  std::optional<OutputDirectory> whole;
  std::vector<fs::path> outs;  // as the user named them
  std::vector<std::unique_ptr<OutputDirectory>> dirs;

  Outputs(const EvaluateRequest& q, const std::vector<std::string>& kinds) {
    const bool several = kinds.size() > 1;
    const EvaluationOptions& eo = q.options;
    const std::vector<fs::path> inputs{q.map_dir, eo.ste.table_cache, eo.ste.model_path};
    if (several) whole.emplace(q.out, "evaluate", inputs);
    for (const std::string& name : kinds) {
      outs.push_back(several ? q.out / name : q.out);
      dirs.push_back(std::make_unique<OutputDirectory>(several ? whole->open() / name : outs.back(),
                                                       "evaluate", inputs));
    }
  }
};

// A run's replay folder in its method's folder (evaluate --replays): replays/MAPFILE-sK-rN, and
// -seedS where several seeds are pooled.
std::string replay_folder(const MapFolder& maps, const RunRecord& r, int seeds) {
  const std::string& picture = maps.picture_names.at(static_cast<std::size_t>(r.map_index));
  std::string id = fs::path(picture).stem().string() + "-s" + std::to_string(r.source_index) +
                   "-r" + std::to_string(r.run);
  if (seeds > 1) id += "-seed" + std::to_string(r.seed);
  return "replays/" + id;
}

// Writes each run's replay into its method's folder as it ends (on the run's thread), with
// replay.js beside it: the same JSON as a script, which report.html can load from a file://
// page where reading a file is not allowed.
ReplaySink replay_writer(const MapFolder& maps, const EvaluationOptions& eo, Outputs& o) {
  for (const std::unique_ptr<OutputDirectory>& dir : o.dirs)
    fs::create_directories(dir->open() / "replays");
  return [&maps, &o, seeds = eo.seeds](std::size_t m, const RunRecord& rec, const Replay& replay) {
    const fs::path folder = o.dirs[m]->open() / replay_folder(maps, rec, seeds);
    fs::create_directory(folder);
    write_file_atomic(folder / "replay.js",
                      "plumekitReplay(" + write_replay(replay, folder) + ");\n");
  };
}

// Every method on the same runs, each map's median trajectory drawn into its method's folder.
std::vector<EvaluationResult> run_methods(const EvaluateRequest& q, const MapFolder& maps,
                                          const std::vector<std::string>& kinds, Outputs& o,
                                          const JobProgress& progress) {
  const EvaluationOptions& eo = q.options;
  std::vector<AfterMap> pictures;
  for (const std::unique_ptr<OutputDirectory>& dir : o.dirs)
    pictures.push_back(trajectory_pictures(dir->open(), maps.picture_names));
  const std::string per_run =
      kinds.size() > 1 ? " runs of " + std::to_string(kinds.size()) + " methods" : " runs";
  return evaluate_methods(
      maps.maps, eo, kinds,
      [&](int done, int total) {
        if (progress)
          progress(static_cast<double>(done) / total,
                   std::to_string(done) + "/" + std::to_string(total) + per_run);
      },
      [&](std::size_t m, const Scenario& sc, const std::vector<RunRecord>& records) {
        pictures[m](sc, records);
      },
      q.replays ? replay_writer(maps, eo, o) : ReplaySink());
}

// Each run's replay folder relative to `prefix` (none without --replays).
std::vector<std::string> replay_links(const EvaluateRequest& q, const MapFolder& maps,
                                      const EvaluationResult& res, const std::string& prefix) {
  std::vector<std::string> links;
  if (q.replays)
    for (const RunRecord& r : res.runs)
      links.push_back(prefix + replay_folder(maps, r, res.seeds));
  return links;
}

// The part folder of `evaluate --shard K/N`: part.json, runs.csv, timings.csv, and the
// trajectory pictures of this part's median runs.
Report write_part(OutputDirectory& dir, const EvaluationResult& res, const EvaluationOptions& eo,
                  const PartIdentity& id, const ordered_json& tracks, const fs::path& out) {
  EvaluationFiles files;
  files.runs_csv = runs_csv(res);
  files.timings_csv = timings_csv(res);
  files.tracks = tracks;
  write_file_atomic(dir.open() / "runs.csv", files.runs_csv);
  write_file_atomic(dir.open() / "timings.csv", files.timings_csv);
  write_file_atomic(dir.open() / kTracksFile, files.tracks.dump() + "\n");
  write_file_atomic(dir.open() / kPartFile, part_json(res, eo, id, files).dump(2) + "\n");
  dir.commit();
  const std::string part = std::to_string(eo.part_k) + "/" + std::to_string(eo.part_n);
  const ordered_json j{{"ok", true},           {"part", eo.part_k},
                       {"parts", eo.part_n},   {"runs", res.runs.size()},
                       {"wall_s", res.wall_s}, {"out", out.string()}};
  return {
      j, "evaluated part " + part + ": " + std::to_string(res.runs.size()) + " runs (pairs " +
             std::to_string(res.pairs.first) + ".." + std::to_string(res.pairs.end) + " of " +
             std::to_string(res.pairs.total) + " map sources)\nwrote " + out.string() +
             "/{part.json, runs.csv, timings.csv, tracks.json, trajectories/}; join the parts with "
             "`plumekit evaluate merge PART_DIR... --out DIR`"};
}

// Method m's folder: its part, or its summary, runs, timings and box plots.
Report write_method(const EvaluateRequest& q, const MapFolder& maps, const EvaluationResult& res,
                    const ordered_json& tracks, const std::string& method, OutputDirectory& dir,
                    const fs::path& out) {
  EvaluationOptions each = q.options;
  each.ste.method.name = method;
  if (q.part) {
    ordered_json options = q.result_options;
    // The map folder and the CNN are compared by their files' SHA-256, so that paths may differ
    // between machines.
    if (each.ste.model == PlumeModelKind::Surrogate)
      options["cnn_sha256"] = sha256_file(each.ste.model_path);
    options["--method"] = method;  // as the part of a single method
    const PartIdentity id{evaluation_settings(each, q.map_dir), options, map_files_json(maps)};
    return write_part(dir, res, each, id, tracks, out);
  }
  Report rep = method_report(res, q.options, method, q.map_dir, out);
  write_evaluation_files(dir.open(), res,
                         {runs_csv(res), timings_csv(res), rep.json, evaluation_timings(res),
                          tracks, replay_links(q, maps, res, "")});
  dir.commit();
  // On stdout the times go with the summary (they are apart only in the files).
  rep.json["timings"] = evaluation_timings(res);
  return rep;
}

// Several methods: each one's result, and one total, since the methods ran together, each run's
// plume simulated once for all of them.
Report methods_total(const std::vector<std::string>& kinds,
                     const std::vector<EvaluationResult>& results,
                     const std::vector<Report>& reports) {
  double wind_s = 0;
  for (const MapReport& mr : results.front().maps)
    wind_s += mr.wind_s;
  ordered_json j{{"ok", true}, {"methods", ordered_json::array()}};
  std::string text;
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    j["methods"].push_back({{"method", kinds[m]},
                            {"model_build_s", results[m].model_build_s()},
                            {"decisions_s", results[m].decisions_s},
                            {"result", reports[m].json}});
    text += std::string(m ? "\n\n" : "") + "== " + kinds[m] + " ==\n" + reports[m].text;
  }
  j["wall_s"] = results.front().wall_s;
  j["wind_s"] = wind_s;
  std::ostringstream total;
  total << std::fixed << std::setprecision(1) << "\n\nall " << kinds.size() << " methods in "
        << results.front().wall_s << " s (wall clock; wind " << wind_s
        << " s, then every run's plume once for all the methods)";
  return {j, text + total.str()};
}

}  // namespace

Report evaluate_job(const EvaluateRequest& q, const JobProgress& progress) {
  q.options.validate();
  const MapFolder maps = read_map_folder(q.map_dir);
  const std::vector<std::string> kinds = evaluated_methods(q.options, q.methods);
  Outputs o(q, kinds);
  const std::vector<EvaluationResult> results = run_methods(q, maps, kinds, o, progress);
  std::vector<ordered_json> tracks;
  std::vector<Report> reports;
  for (std::size_t m = 0; m < kinds.size(); ++m) {
    tracks.push_back(tracks_json(results[m], maps.maps));
    reports.push_back(
        write_method(q, maps, results[m], tracks[m], kinds[m], *o.dirs[m], o.outs[m]));
  }
  if (kinds.size() == 1) return reports.front();
  if (q.part) {  // parts are compared once merged
    o.whole->commit();
    return methods_total(kinds, results, reports);
  }
  // The methods side by side, in OUT itself.
  std::vector<MethodRow> rows;
  for (std::size_t m = 0; m < kinds.size(); ++m)
    rows.push_back({reports[m].json, results[m].overall.median_step_s, results[m].model_build_s(),
                    results[m].decisions_s});
  const Comparison comparison = compare_methods(rows);
  write_file_atomic(o.whole->open() / "comparison.md", comparison.markdown);
  write_file_atomic(o.whole->open() / "comparison.csv", comparison.csv);
  std::vector<ReportMethod> page;
  for (std::size_t m = 0; m < kinds.size(); ++m)
    page.push_back({kinds[m], reports[m].json, &results[m], &tracks[m],
                    replay_links(q, maps, results[m], kinds[m] + "/")});
  write_file_atomic(o.whole->open() / kReportFile, evaluation_html(page));
  o.whole->commit();
  Report total = methods_total(kinds, results, reports);
  total.json["comparison"] = comparison.rows;
  total.text += "\n\n" + comparison.markdown + "wrote " + (q.out / "comparison.md").string() +
                ", comparison.csv, report.html";
  return total;
}

Report merge_job(const std::vector<fs::path>& parts, const fs::path& out) {
  const MergedEvaluation m = merge_evaluation_parts(parts);
  OutputDirectory dir(out, "evaluate", parts);
  write_evaluation_files(dir.open(), m.result, m.files);
  dir.commit();
  Report rep = evaluation_report(m.result, m.settings, out, false);
  rep.json["parts"] = m.parts;
  rep.json["timings"] = m.files.timings;
  rep.text = "joined " + std::to_string(m.parts) + " parts\n" + rep.text;
  return rep;
}

}  // namespace plumekit::run
