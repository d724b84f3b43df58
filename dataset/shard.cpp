#include "dataset/shard.hpp"

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"

namespace plumekit::dataset {

namespace fs = std::filesystem;

Checksums write_shard(const fs::path& dir, const ShardArrays& a) {
  const std::size_t n = static_cast<std::size_t>(a.samples), ny = a.ny, nx = a.nx;
  const std::map<std::string, std::string> files{
      {"inputs.npy", npy_float32(a.inputs, {n, 3, ny, nx})},
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
  std::error_code ec;
  if (!fs::is_regular_file(dir / "checksums.json", ec)) return std::nullopt;
  try {
    const auto j = nlohmann::json::parse(read_file(dir / "checksums.json"));
    Checksums sums;
    for (const char* name : kShardFiles) {
      const std::string expected = j.at(name).get<std::string>();
      if (!fs::is_regular_file(dir / name, ec) || sha256_file(dir / name) != expected)
        return std::nullopt;
      sums[name] = expected;
    }
    return sums;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

void remove_temporaries(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  std::vector<fs::path> doomed;
  for (const auto& e : fs::directory_iterator(dir))
    if (const std::string name = e.path().filename().string();
        name.find(".tmp-") != std::string::npos || name.find(".tmp.") != std::string::npos)
      doomed.push_back(e.path());
  for (const auto& p : doomed)
    fs::remove_all(p);
}

}  // namespace plumekit::dataset
