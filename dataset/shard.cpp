#include "dataset/shard.hpp"

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"
#include "dataset/dataset_reader.hpp"

namespace plumekit::dataset {

namespace fs = std::filesystem;

Checksums write_shard(const fs::path& dir, const ShardArrays& a) {
  const std::size_t n = static_cast<std::size_t>(a.samples), ny = a.ny, nx = a.nx;
  const std::map<std::string, std::string> files{
      {"inputs.npy", npy_float32(a.inputs, {n, static_cast<std::size_t>(a.channels), ny, nx})},
      {"targets.npy", npy_float32(a.targets, {n, 2, ny, nx})},
      {"sources.npy", npy_float32(a.sources, {n, 2})},
      {"map_ids.npy", npy_int32(a.map_ids, {n})},
  };
  AtomicDirectory out(dir);
  const fs::path& tmp = out.path();
  Checksums sums;
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [name, bytes] : files) {
    write_file_atomic(tmp / name, bytes);
    sums[name] = sha256_hex(bytes);
    j[name] = sums[name];
  }
  write_file_atomic(tmp / "checksums.json", j.dump(2) + "\n");
  out.commit();
  return sums;
}

std::optional<Checksums> verify_shard(const fs::path& dir) {
  try {
    check_shard(dir, {});
    return parse_checksums(read_file(dir / "checksums.json"), (dir / "checksums.json").string());
  } catch (const InputError&) {
    return std::nullopt;  // redone by the caller
  }
}

}  // namespace plumekit::dataset
