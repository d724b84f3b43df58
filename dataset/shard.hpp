#pragma once
// A shard: the samples of one map, as a directory of .npy files plus
// checksums.json (SHA-256 of each file). It is written under a temporary
// name and renamed into place when complete, so a shard directory either is
// whole or does not exist; a run killed mid-shard leaves only a temporary
// directory, which the next run removes (core/temporary_files.hpp).
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace plumekit::dataset {

struct ShardArrays {
  int samples = 0;
  std::vector<float> inputs;          // [n, channels, ny, nx] (features.hpp)
  std::vector<float> targets;         // [n, 2, ny, nx]: mean, std
  std::vector<float> sources;         // [n, 2]: x, y in metres
  std::vector<std::int32_t> map_ids;  // [n]
  int channels = 3;                   // 5 on a physical grid (dataset.feature_cell)
  int nx = 64, ny = 64;
};

using Checksums = std::map<std::string, std::string>;  // file name -> SHA-256 hex

inline const char* const kShardFiles[] = {"inputs.npy", "targets.npy", "sources.npy",
                                          "map_ids.npy"};

// Writes `dir` (e.g. shards/shard-00007) atomically; returns the checksums.
Checksums write_shard(const std::filesystem::path& dir, const ShardArrays& a);

// The checksums of a complete shard whose files all match its checksums.json;
// nullopt when it is missing, incomplete or corrupt (then it is redone). To report
// the fault instead: check_shard (dataset_reader.hpp).
std::optional<Checksums> verify_shard(const std::filesystem::path& dir);

}  // namespace plumekit::dataset
