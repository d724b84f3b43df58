#pragma once
// `plumekit evaluate` as one call (apps/ parses its flags into an EvaluateRequest and prints the
// Report; the Python module's evaluate shares evaluated_methods and method_report): the map
// folder read, one or several methods evaluated on the same runs, each method's files (or, with
// --shard, its part folder) written, and the summary with the methods' joint totals.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/report.hpp"
#include "run/evaluation.hpp"

namespace plumekit::run {

struct EvaluateRequest {
  std::filesystem::path map_dir, out = "out/evaluate";
  EvaluationOptions options;
  // More than one: every method samples one world per run, each into out/NAME/, exactly what
  // `--method NAME --out OUT/NAME` writes. Empty or one: options.ste.method.
  std::vector<std::string> methods;
  bool part = false;  // options' part_k/part_n: each method's part folder, for `evaluate merge`
  // Every run's replay (docs/replay.md) into each method's replays/ folder, linked from
  // report.html: recording costs time, so only when asked.
  bool replays = false;
  // A part's record of every flag that shapes the results, flag -> value as given or its default
  // (PartIdentity::options); the job adds "cnn_sha256" (the surrogate's file) and the method.
  nlohmann::ordered_json result_options = nlohmann::ordered_json::object();
};

// Called after each run: the fraction done and "done/total runs" (of how many methods).
using JobProgress = std::function<void(double fraction, const std::string& note)>;

// Evaluates, writes the output folder whole (nothing of it on an error or an interrupt) and
// returns what `evaluate` prints: one method's summary and timings, a part's line, or with
// several methods each one's result and the totals of their shared runs.
Report evaluate_job(const EvaluateRequest& request, const JobProgress& progress = {});

// `evaluate merge`: the part folders verified (merge_evaluation_parts) before `out` is touched,
// then the files of a single evaluation written there whole; returns its summary, with the parts'
// count and the timings.
Report merge_job(const std::vector<std::filesystem::path>& parts, const std::filesystem::path& out);

// The methods an evaluation runs: `several` when it names more than one, else options' method.
std::vector<std::string> evaluated_methods(const EvaluationOptions& options,
                                           const std::vector<std::string>& several);

// One method's summary (summary.json's content and the table) of its result of
// evaluate_methods, `options` with that method; `map_dir` and `out` as the user named them.
Report method_report(const EvaluationResult& result, EvaluationOptions options,
                     const std::string& method, const std::filesystem::path& map_dir,
                     const std::filesystem::path& out);

}  // namespace plumekit::run
