#pragma once
// What `plume` and `dataset generate|merge|show` report when they finish (the JSON summary and
// the human line), and generate's progress note. Assembled here so that apps/ only prints.
#include <chrono>
#include <string>

#include "core/geometry.hpp"
#include "core/report.hpp"
#include "dataset/dataset_reader.hpp"
#include "dataset/generator.hpp"
#include "dataset/plume.hpp"

namespace plumekit::dataset {

// One plume (`plumekit plume`): where and how it was made, its peak and its timings.
struct PlumeRun {
  std::string map, out;
  Vec2 source;  // in the map's frame, as reported
  PlumeSimulator model = PlumeSimulator::Filament;
  double flow_s = 0.0, plume_s = 0.0;
};
Report plume_report(const PlumeRun& run, const PlumeTargets& targets);

Report generate_report(const std::string& out, PlumeSimulator model, const DatasetSummary& s);
Report merge_report(const std::string& out, const MergeSummary& s);
// `dataset show`: the sample drawn, with the SHA-256 of its stored rows.
Report show_report(const std::string& out, const DatasetSample& sample);

// "H:MM:SS"
std::string format_duration(double seconds);

// generate's progress note: "done/total samples, elapsed H:MM:SS, ETA H:MM:SS". The rate counts
// only samples computed since the first call, so the ETA of a resumed run ignores the shards
// it found complete.
class ProgressNote {
 public:
  ProgressNote() : start_(std::chrono::steady_clock::now()) {}
  std::string operator()(long long done, long long total);

 private:
  std::chrono::steady_clock::time_point start_;
  long long first_ = -1;
};

}  // namespace plumekit::dataset
