#pragma once
// `plumekit dataset generate` and `merge`: maps -> wind (cached) -> plumes ->
// shards -> manifest. One shard per map; maps are shared out to a pool of
// threads, and each map's randomness comes from (seed, map index), so the
// bytes do not depend on the thread count, the --shard split or interruptions.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "dataset/manifest.hpp"

namespace plumekit::dataset {

struct RunOptions {
  int threads = 1;
  int part_k = 0;  // --shard K/N: this run does the maps with index % N == K
  int part_n = 1;
  // Called from the calling thread about 5 times a second: (done, total samples).
  std::function<void(long long, long long)> progress;
};

struct DatasetSummary {
  int maps = 0;               // this run's (part's) maps
  int maps_resumed = 0;       // found complete and verified, not redone
  int winds_cached = 0;       // wind fields read from the cache instead of solved
  long long samples = 0;      // computed by this run
  double seconds = 0.0;       // wall time
  double flow_seconds = 0.0;  // summed over threads
  double plume_seconds = 0.0;
  double samples_per_second() const { return seconds > 0.0 ? samples / seconds : 0.0; }
};

DatasetSummary generate_dataset(const std::filesystem::path& out, const DatasetOptions& options,
                                const RunOptions& run);

struct MergeSummary {
  int parts = 0;
  int shards = 0;
  long long samples = 0;
};

// Joins the parts (directories holding manifest.part-K-of-N.json files, or
// the same directory several times) into `out`: checks that they share one
// set of parameters and together hold every map exactly once, verifies every
// checksum, copies maps, winds and shards, and writes manifest.json.
MergeSummary merge_datasets(const std::filesystem::path& out,
                            const std::vector<std::filesystem::path>& parts);

std::string part_manifest_name(int k, int n);  // manifest.part-K-of-N.json

}  // namespace plumekit::dataset
