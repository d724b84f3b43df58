#include "dataset/shard.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
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

namespace {

// "<name>.plumekit-tmp-<pid>-<n>" (core/temporary_files.hpp) of a process that no longer runs: a
// live one may be another part's run (--shard K/N) writing into the same dataset.
bool is_dead_temporary(const std::string& name) {
  const std::string mark = ".plumekit-tmp-";
  const std::size_t at = name.find(mark);
  if (at == std::string::npos) return false;
  const std::string rest = name.substr(at + mark.size());
  const std::size_t dash = rest.find('-');
  if (dash == 0 || dash == std::string::npos) return false;
  pid_t pid = 0;
  for (std::size_t i = 0; i < dash; ++i) {
    if (rest[i] < '0' || rest[i] > '9') return false;
    pid = pid * 10 + (rest[i] - '0');
  }
  return pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH;
}

}  // namespace

void remove_temporaries(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  std::vector<fs::path> doomed;
  for (const auto& e : fs::directory_iterator(dir))
    if (const std::string name = e.path().filename().string();
        name.find(".tmp-") != std::string::npos || name.find(".tmp.") != std::string::npos ||
        is_dead_temporary(name))
      doomed.push_back(e.path());
  for (const auto& p : doomed)
    fs::remove_all(p, ec);
}

}  // namespace plumekit::dataset
