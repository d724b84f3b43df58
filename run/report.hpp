#pragma once
// What the STE commands write and print: run.json and its human summary, the
// pictures of a run, and an evaluation's runs.csv, summary.json, box plots and
// per-map trajectory pictures. apps/ only binds flags and prints these.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/report.hpp"
#include "map/map.hpp"
#include "run/evaluation.hpp"
#include "run/scenario.hpp"

namespace plumekit::run {

// Where a run's wall-clock time went: the scenario's wind (flow solve or wind file) and model build
// (table, cached readings), the run's plume simulation (the world's spin-up, steps and readings)
// and decisions, and the rest (reading the map, the planner, pictures, ...). The parts add up to
// total_s.
struct RunTimes {
  double total_s = 0, wind_s = 0, model_build_s = 0, plume_s = 0, decisions_s = 0, other_s = 0;
};
// `total_s`: the wall time to account for (a command's, from its start); 0: the scenario's wind
// and model build plus the run's own wall time (LocalizationResult::run_s).
RunTimes run_times(const Scenario& scenario, const LocalizationResult& result,
                   double total_s = 0.0);

// One run: run.json's content (the JSON) and its human summary (the text), with run_times(...,
// total_s) under "time" and on the summary's last line.
Report run_report(const Scenario& scenario, Vec2 source, const LocalizationResult& result,
                  double total_s = 0.0);

struct RunPictures {
  std::filesystem::path trajectory, posterior;
};
// Writes trajectory.png and posterior.png of one run into `dir` (the true source labelled as in
// the map's list of sources when it is one of them).
RunPictures write_run_pictures(const Scenario& scenario, Vec2 source,
                               const LocalizationResult& result, const std::filesystem::path& dir);

// The map files of a folder (*.json, sorted by name) read, and the name of each one's trajectory
// picture, made from its file name (never from the name inside it). OptionError on
// evaluation.map_dir when the folder is missing or holds no map file.
struct MapFolder {
  std::vector<std::filesystem::path> files;
  std::vector<Map> maps;
  std::vector<std::string> picture_names;  // "<file stem>.png", made safe and unique
};
MapFolder read_map_folder(const std::filesystem::path& dir);

// The run of a map whose error is the median one (the lower of the two middle runs for an even
// count): the map's typical trajectory.
const RunRecord& median_run(const std::vector<RunRecord>& runs);
// A number as JSON, or null where it is not finite: a time the run never reached, an overhead
// without a detection, a team robot alone.
nlohmann::ordered_json finite_or_null(double v);
// Why that run is the one drawn, for its picture's title: "median run of N; map median X m".
// The title states the drawn run's own error; with an even count the map's median is the mean
// of two runs and no run's error, so both are said.
std::string median_run_note(const std::vector<RunRecord>& runs);
// An AfterMap (evaluate()) that draws each map's median run into
// dir/trajectories/<picture_names[map]>.
AfterMap trajectory_pictures(const std::filesystem::path& dir,
                             const std::vector<std::string>& picture_names);

// How the robot sampled and ended (--protocol: "protocol", "read_while_moving", "adaptive_stops",
// "confidence_radius", "confidence_mass", "approach"), into `j`, unless it was the thesis's
// protocol: a summary without these keys was made with the thesis's (every one before issue 47) and
// keeps its bytes when remade.
void sampling_json(const SteOptions& options, nlohmann::ordered_json& j);

// What was evaluated and how: summary.json's keys before "overall" (the options that shape the
// results; never the threads or a time; the plume model's only for STE). `map_dir` is the folder
// the maps came from, as the user named it.
nlohmann::ordered_json evaluation_settings(const EvaluationOptions& options,
                                           const std::filesystem::path& map_dir);
// summary.json's content (`settings`, then the overall and per-map statistics) and the
// evaluation's table (the text); `out` is the output folder as the user named it, `pictures`
// whether it holds trajectories/. summary.json holds no measured time, so a rerun, another
// thread count or a merge of --shard parts writes the same bytes.
Report evaluation_report(const EvaluationResult& result, const nlohmann::ordered_json& settings,
                         const std::filesystem::path& out, bool pictures = true);
// The same with the settings of `options` and `map_dir` (evaluation_settings).
Report evaluation_report(const EvaluationResult& result, const EvaluationOptions& options,
                         const std::filesystem::path& map_dir, const std::filesystem::path& out);
// timings.json: the threads used, the wall time, and the measured compute, wind and table
// build times overall and per map.
nlohmann::ordered_json evaluation_timings(const EvaluationResult& result);
// "STE (physics)", or the method's name ("surge-cast"), from a summary's settings; summaries
// written before --method were STE's.
std::string summary_label(const nlohmann::ordered_json& settings);

struct EvaluationFiles {
  std::string runs_csv, timings_csv;
  nlohmann::ordered_json summary, timings;
  nlohmann::ordered_json tracks;  // tracks.json (run/run_tracks.hpp)
  // Each run's replay folder relative to the output (evaluate --replays), or none at all.
  std::vector<std::string> replays;
};
// Writes runs.csv, summary.json, timings.csv, timings.json, tracks.json, the two box plots and
// report.html (run/evaluation_html.hpp) into `dir`.
void write_evaluation_files(const std::filesystem::path& dir, const EvaluationResult& result,
                            const EvaluationFiles& files);

}  // namespace plumekit::run
