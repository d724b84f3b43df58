#pragma once
// Google Benchmark pairs "<name>/baseline/<arg>" and "<name>/library/<arg>" and, after the usual
// table, prints each pair's ratio baseline time / library time (>1: the library is faster), so the
// two are always measured in the same run on the same machine (docs/own-code.md). With
// --benchmark_repetitions the medians are compared.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace plumekit_bench {

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  // Colours only on a terminal, so that a saved table is plain text.
  RatioReporter() : ConsoleReporter(isatty(1) ? OO_Defaults : OO_Tabular) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      // With repetitions only the median counts; without, the one run.
      if (r.run_type == Run::RT_Aggregate && r.aggregate_name != "median") continue;
      // CPU time, as the machine may be shared; wall time for benchmarks that ask for it
      // (UseRealTime: a parallel loop's CPU time is the calling thread's only).
      const double t =
          r.run_name.time_type.empty() ? r.GetAdjustedCPUTime() : r.GetAdjustedRealTime();
      const std::string& name = r.run_name.function_name;
      for (const char* side : {"/baseline", "/library"}) {
        const std::size_t at = name.find(side);
        if (at == std::string::npos) continue;
        const std::string key = name.substr(0, at) + name.substr(at + std::string(side).size()) +
                                (r.run_name.args.empty() ? "" : "/" + r.run_name.args);
        (std::string(side) == "/baseline" ? baseline_ : library_)[key] = t;
      }
    }
  }

  void Finalize() override {
    ConsoleReporter::Finalize();
    std::printf("\n%-40s %12s\n", "pair", "baseline/library");
    for (const auto& [key, base] : baseline_) {
      const auto lib = library_.find(key);
      if (lib != library_.end() && lib->second > 0)
        std::printf("%-40s %12.2f\n", key.c_str(), base / lib->second);
    }
  }

 private:
  std::map<std::string, double> baseline_, library_;
};

inline int run_with_ratios(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}

}  // namespace plumekit_bench
