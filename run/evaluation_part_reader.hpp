#pragma once
// The reader of `plumekit evaluate --shard K/N` part folders, which `evaluate merge` joins
// (docs/design/evaluation.md, "Scale-out"): part.json with its own checksum and its files',
// runs.csv and timings.csv, and the checks that parts belong together. It needs only core, so that
// its fuzz target (fuzz/fuzz_evaluate_part.cpp) links without the rest of ste.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/evaluation.hpp"

namespace plumekit::run {

inline constexpr const char* kPartFile = "part.json";
inline constexpr const char* kPartFormat = "plumekit-evaluate-part/1";

// A CSV file's header line and the records after it.
struct CsvParts {
  std::string header, body;
};

// One part folder as read: part.json, its runs (in run order) and its two CSV files.
struct EvaluationPart {
  std::filesystem::path dir;
  nlohmann::ordered_json j;
  int k = 0, n = 1;
  std::vector<RunRecord> runs;
  CsvParts runs_csv, timings_csv;
  nlohmann::ordered_json tracks;  // its tracks.json (run/run_tracks.hpp)
};

// The SHA-256 of part.json's content without its own "sha256" key.
std::string part_body_sha256(nlohmann::ordered_json j);

// Reads and checks one part folder: a well-formed part.json that matches its own checksum, holds
// every key the merge reads and names a part K of N, and the CSV files it lists, which match their
// checksums and hold a header and one record per run, and its tracks.json, which matches its
// checksum and holds one track per run. InputError naming the file otherwise.
EvaluationPart read_evaluation_part(const std::filesystem::path& dir);

// The parts must come from one evaluation: one split, one set of options and maps. InputError
// naming `p`'s folder and the option that differs.
void check_same_evaluation(const EvaluationPart& first, const EvaluationPart& p);

// Every part 0..N-1 exactly once, each with the pairs and runs its K/N gives.
void check_part_coverage(const std::vector<EvaluationPart>& parts);

}  // namespace plumekit::run
