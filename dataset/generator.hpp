#pragma once
// `plumekit dataset generate` and `merge`: maps -> wind (cached) -> plumes ->
// shards -> manifest. One shard per map; maps are shared out to a pool of
// threads, and each map's randomness comes from (seed, map index), so the
// bytes do not depend on the thread count, the --shard split or interruptions.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/thread_pool.hpp"
#include "dataset/manifest.hpp"

namespace plumekit::dataset {

struct RunOptions {
  int threads = kDefaultThreads;  // 0: one per core; one map per thread
  int part_k = 0;                 // dataset.shard K/N: this run does the maps with index % N == K
  int part_n = 1;
  // (done, total samples), about 5 times a second and once at the end; from any worker thread,
  // never two calls at once.
  std::function<void(long long, long long)> progress;
  // Sets part_k and part_n from "K/N"; OptionError naming dataset.shard when it is not 0 <= K < N.
  void set_part(const std::string& k_of_n);
};

// Sets options.given_maps (and map_files) to the *.json maps of `dir`, sorted by name, each
// with its own sources: the ground truth of test maps. OptionError naming dataset.map_dir
// when the folder is missing or holds no map.
void use_map_dir(DatasetOptions& options, const std::filesystem::path& dir);

struct DatasetSummary {
  int maps = 0;           // this run's (part's) maps
  int maps_resumed = 0;   // found complete and verified, not redone
  int winds_cached = 0;   // wind fields read from the cache instead of solved
  long long samples = 0;  // computed by this run
  double seconds = 0.0;   // wall time
  double flow_s = 0.0;    // summed over threads
  double plume_s = 0.0;
  int threads = 1;  // worker threads used
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
