#pragma once
// `plumekit evaluate --shard K/N` and `evaluate merge` (docs/design/evaluation.md, "Scale-out"): a
// part folder records which part it is, everything every part must share (the options that shape
// the results, the maps' files and checksums) and each run's exact figures; the merge verifies the
// parts and rebuilds the files of a single run, byte for byte.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/evaluation.hpp"
#include "run/evaluation_part_reader.hpp"
#include "run/report.hpp"

namespace plumekit::run {

// The maps of a folder as every part must share them: file name, map name and SHA-256.
nlohmann::ordered_json map_files_json(const MapFolder& maps);

// What a part shares with the others: the summary's settings (evaluation_settings), `options`
// (every flag that shapes the results, as the command line gave it or its default) and `maps`
// (map_files_json).
struct PartIdentity {
  nlohmann::ordered_json settings, options, maps;
};

// part.json of a part's result: the identity, the part's place, the checksums of `files`
// (runs.csv, timings.csv) and every run's figures at full precision.
nlohmann::ordered_json part_json(const EvaluationResult& result, const EvaluationOptions& options,
                                 const PartIdentity& identity, const EvaluationFiles& files);

struct MergedEvaluation {
  EvaluationResult result;          // every run, in run order, with the statistics evaluate() gives
  EvaluationFiles files;            // what a single run writes (timings.json also lists the parts)
  nlohmann::ordered_json settings;  // the parts' evaluation_settings
  int parts = 0;
};
// Reads the part folders and checks them before anything is written: each holds a well-formed
// part.json whose checksums match, all share one identity and one N, and together they are the
// parts 0..N-1, each once. InputError naming the folder (and the option or part) otherwise.
MergedEvaluation merge_evaluation_parts(const std::vector<std::filesystem::path>& parts);

}  // namespace plumekit::run
