#include "dataset/dataset_reader.hpp"

#include <algorithm>
#include <set>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"
#include "dataset/manifest.hpp"
#include "map/map_json.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;

namespace {

// What to do about a damaged manifest or parameters file: both are rewritten by a resumed run.
constexpr const char* kRewrite =
    "; run the same `plumekit dataset generate` again to rewrite it (it keeps complete shards)";

// More maps than any dataset has: a bound that keeps a damaged count from allocating gigabytes.
constexpr int kMaxMaps = 10'000'000;

[[noreturn]] void fail(const std::string& name, const std::string& key, const std::string& what,
                       const char* advice = kRewrite) {
  throw InputError(name + ": " + (key.empty() ? "" : key + ": ") + what + advice);
}

std::string clip(std::string s) {
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

ordered_json parse_json(std::string_view bytes, const std::string& name,
                        const char* advice = kRewrite) {
  try {
    return ordered_json::parse(bytes.begin(), bytes.end());
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    std::string why = e.what();
    if (const auto p = why.find("] "); p != std::string::npos) why = why.substr(p + 2);
    fail(name, "", "not valid JSON (the file is truncated or damaged): " + why, advice);
  }
}

const ordered_json& member(const ordered_json& j, const char* key, const std::string& name,
                           const std::string& where) {
  if (!j.is_object() || !j.contains(key))
    fail(name, where.empty() ? key : where + "." + key, "missing");
  return j.at(key);
}

long long integer(const ordered_json& j, const char* key, const std::string& name,
                  const std::string& where, long long lo, long long hi) {
  const ordered_json& v = member(j, key, name, where);
  const std::string dotted = where.empty() ? key : where + "." + key;
  if (!v.is_number_integer()) fail(name, dotted, "expected an integer, found " + clip(v.dump()));
  const long long x = v.is_number_unsigned() && v.get<unsigned long long>() > 1ull << 62
                          ? hi + 1
                          : v.get<long long>();
  if (x < lo || x > hi)
    fail(name, dotted,
         std::to_string(x) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
  return x;
}

std::string text(const ordered_json& j, const char* key, const std::string& name,
                 const std::string& where) {
  const ordered_json& v = member(j, key, name, where);
  if (!v.is_string())
    fail(name, where.empty() ? key : where + "." + key,
         "expected a string, found " + clip(v.dump()));
  return v.get<std::string>();
}

bool is_sha256_hex(const std::string& s) {
  return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

// An object holding exactly the shard files, each a SHA-256; `where` is its key in `name`.
Checksums checksums_of(const ordered_json& j, const std::string& name, const std::string& where,
                       const char* advice) {
  if (!j.is_object()) fail(name, where, "expected an object of file checksums", advice);
  Checksums sums;
  for (const char* file : kShardFiles) {
    const std::string key = where.empty() ? file : where + "." + file;
    if (!j.contains(file)) fail(name, key, "missing", advice);
    const ordered_json& v = j.at(file);
    if (!v.is_string() || !is_sha256_hex(v.get<std::string>()))
      fail(name, key, "expected 64 lowercase hex digits (a SHA-256), found " + clip(v.dump()),
           advice);
    sums[file] = v.get<std::string>();
  }
  if (j.size() != sums.size())
    for (const auto& [file, v] : j.items())
      if (!sums.count(file)) fail(name, where, "unexpected file \"" + clip(file) + "\"", advice);
  return sums;
}

std::string shown(const json& v) {
  return v.is_null() ? std::string("none") : clip(v.dump());
}

void differences(const json& a, const json& b, const std::string& path,
                 std::vector<std::string>& out) {
  if (a.is_object() && b.is_object()) {
    const auto key = [&](const std::string& k) { return path.empty() ? k : path + "." + k; };
    for (const auto& [k, v] : a.items())
      differences(v, b.contains(k) ? b.at(k) : json(), key(k), out);
    for (const auto& [k, v] : b.items())
      if (!a.contains(k)) differences(json(), v, key(k), out);
    return;
  }
  if (a != b) out.push_back(path + ": this run " + shown(a) + ", the dataset " + shown(b));
}

// Parameters written before issue 15 named time fields `_seconds`; they read as today's `_s`
// keys, in place, so an older dataset resumes and merges.
void upgrade_parameter_keys(ordered_json& parameters) {
  if (!parameters.contains("filament") || !parameters.at("filament").is_object()) return;
  const ordered_json old = parameters.at("filament");
  if (!old.contains("record_seconds")) return;
  ordered_json renamed = ordered_json::object();
  for (const auto& [k, v] : old.items())
    renamed[k == "record_seconds" ? "record_s" : k] = v;
  parameters["filament"] = renamed;
}

}  // namespace

Manifest parse_manifest(std::string_view bytes, const std::string& name) {
  const ordered_json j = parse_json(bytes, name);
  if (!j.is_object()) fail(name, "", "expected a JSON object");
  const std::string format = text(j, "format", name, "");
  if (format != kDatasetFormat)
    fail(name, "format", "\"" + clip(format) + "\", this plumekit reads \"" + kDatasetFormat + "\"",
         "; make the dataset again with this plumekit");
  Manifest m;
  m.generator = member(j, "generator", name, "");
  if (!m.generator.is_object()) fail(name, "generator", "expected an object of parameters");
  upgrade_parameter_keys(m.generator);
  m.maps = static_cast<int>(integer(m.generator, "maps", name, "generator", 1, kMaxMaps));
  if (j.contains("part")) {
    m.part_n = static_cast<int>(integer(j.at("part"), "n", name, "part", 1, kMaxMaps));
    m.part_k = static_cast<int>(integer(j.at("part"), "k", name, "part", 0, m.part_n - 1));
  }
  const ordered_json& shards = member(j, "shards", name, "");
  if (!shards.is_array()) fail(name, "shards", "expected an array");
  std::set<int> seen;
  long long sum = 0;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const ordered_json& s = shards[i];
    const std::string where = "shards[" + std::to_string(i) + "]";
    if (!s.is_object()) fail(name, where, "expected an object");
    ManifestShard e;
    e.map_index = static_cast<int>(integer(s, "map_index", name, where, 0, m.maps - 1));
    if (e.map_index % m.part_n != m.part_k)
      fail(name, where + ".map_index",
           std::to_string(e.map_index) + " does not belong to part " + std::to_string(m.part_k) +
               " of " + std::to_string(m.part_n));
    if (!seen.insert(e.map_index).second)
      fail(name, where + ".map_index", "map " + std::to_string(e.map_index) + " is listed twice");
    // Names become paths: only the names the generator writes are accepted.
    e.name = text(s, "name", name, where);
    if (e.name != shard_name(e.map_index))
      fail(name, where + ".name",
           "\"" + clip(e.name) + "\", expected \"" + shard_name(e.map_index) + "\"");
    e.map = text(s, "map", name, where);
    const std::string map = "maps/map-" + shard_name(e.map_index).substr(6) + ".json";
    if (e.map != map)
      fail(name, where + ".map", "\"" + clip(e.map) + "\", expected \"" + map + "\"");
    e.family = text(s, "family", name, where);
    e.samples = static_cast<int>(integer(s, "samples", name, where, 0, 1'000'000'000));
    e.sha256 = checksums_of(member(s, "sha256", name, where), name, where + ".sha256", kRewrite);
    sum += e.samples;
    m.shards.push_back(std::move(e));
  }
  if (m.part_n == 1 && static_cast<int>(m.shards.size()) != m.maps)
    fail(name, "shards",
         "lists " + std::to_string(m.shards.size()) + " shards for " + std::to_string(m.maps) +
             " maps");
  m.samples = integer(j, "samples", name, "", 0, 1ll << 62);
  if (m.samples != sum)
    fail(name, "samples",
         std::to_string(m.samples) + ", but the shards hold " + std::to_string(sum));
  return m;
}

Manifest read_manifest(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec))
    fail(file.string(), "", "not found: the folder holds no finished dataset",
         "; name a dataset folder written by `plumekit dataset generate` or `dataset merge`");
  return parse_manifest(read_file(file), file.string());
}

std::vector<Manifest> read_part_manifests(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string() + ": not a directory");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("manifest.part-", 0) == 0 && e.path().extension() == ".json")
      files.push_back(e.path());
  }
  if (files.empty()) throw InputError(dir.string() + ": no manifest.part-K-of-N.json in it");
  std::sort(files.begin(), files.end());
  std::vector<Manifest> manifests;
  for (const fs::path& f : files)
    manifests.push_back(read_manifest(f));
  return manifests;
}

ordered_json parse_parameters(std::string_view bytes, const std::string& name) {
  constexpr const char* advice =
      "; restore it from the \"generator\" object of the dataset's manifest.json, or use "
      "another output folder";
  ordered_json j = parse_json(bytes, name, advice);
  if (!j.is_object()) fail(name, "", "expected a JSON object of parameters", advice);
  upgrade_parameter_keys(j);
  for (const char* key : {"seed", "maps"})
    if (!j.contains(key) || !j.at(key).is_number_integer())
      fail(name, key, j.contains(key) ? "expected an integer" : "missing", advice);
  return j;
}

ordered_json read_parameters(const fs::path& file) {
  return parse_parameters(read_file(file), file.string());
}

std::vector<std::string> parameter_differences(const json& this_run, const json& dataset) {
  std::vector<std::string> out;
  differences(this_run, dataset, "", out);
  return out;
}

Checksums parse_checksums(std::string_view bytes, const std::string& name) {
  constexpr const char* advice =
      "; the shard is damaged: run the same `plumekit dataset generate` again to redo it";
  return checksums_of(parse_json(bytes, name, advice), name, "", advice);
}

void check_shard(const fs::path& dir, const Checksums& expected) {
  constexpr const char* advice =
      "; the shard is damaged or was changed: run the same `plumekit dataset generate` again to "
      "redo it";
  const fs::path sums_file = dir / "checksums.json";
  std::error_code ec;
  if (!fs::is_regular_file(sums_file, ec))
    fail(sums_file.string(), "", "missing (the shard is incomplete)", advice);
  const Checksums sums = parse_checksums(read_file(sums_file), sums_file.string());
  for (const auto& [file, hex] : sums) {
    if (!expected.empty() && expected.at(file) != hex)
      fail(sums_file.string(), file, "differs from the dataset's manifest", advice);
    const fs::path p = dir / file;
    if (!fs::is_regular_file(p, ec)) fail(p.string(), "", "missing", advice);
    if (sha256_file(p) != hex) fail(p.string(), "", "checksum mismatch", advice);
  }
}

long long shard_samples(const fs::path& dir) {
  long long rows = -1;
  std::string first;
  for (const char* file : kShardFiles) {
    const std::vector<std::size_t> shape = read_npy_shape(dir / file);
    const long long n = shape.empty() ? -1 : static_cast<long long>(shape.front());
    if (n < 0) fail((dir / file).string(), "", "a scalar, not an array of samples", "");
    if (rows >= 0 && n != rows)
      fail((dir / file).string(), "",
           "holds " + std::to_string(n) + " samples, " + first + " " + std::to_string(rows),
           "; the shard is damaged: run the same `plumekit dataset generate` again to redo it");
    if (rows < 0) rows = n, first = file;
  }
  return rows;
}

double feature_cell(const Manifest& m) {
  const auto it = m.generator.find("feature_cell");
  if (it == m.generator.end()) return 0.0;
  if (!it->is_number() || !(it->get<double>() > 0))
    throw InputError("manifest.json: generator.feature_cell: expected a cell size > 0, found " +
                     it->dump());
  return it->get<double>();
}

bool physics_input(const Manifest& m) {
  const auto it = m.generator.find("physics_input");
  if (it == m.generator.end()) return false;
  if (!it->is_boolean())
    throw InputError("manifest.json: generator.physics_input: expected true or false, found " +
                     it->dump());
  if (it->get<bool>() && feature_cell(m) == 0.0)
    throw InputError(
        "manifest.json: generator.physics_input is true without a generator.feature_cell: the "
        "physics channel needs a physical grid");
  return it->get<bool>();
}

ShardArrays read_shard(const fs::path& dataset_dir, const ManifestShard& entry, int channels) {
  const fs::path dir = dataset_dir / "shards" / entry.name;
  check_shard(dir, entry.sha256);
  const auto load = [&](const char* file, std::vector<std::size_t> shape,
                        NpyArray* keep = nullptr) {
    NpyArray a = read_npy(dir / file);
    // The grid is the map's: the inputs give it (nx, ny of 0 below), the targets must match it.
    if (a.shape.size() == 4 && shape.size() == 4 && shape[2] == 0) {
      shape[2] = a.shape[2];
      shape[3] = a.shape[3];
    }
    if (a.shape != shape || (shape.size() == 4 && (shape[2] == 0 || shape[3] == 0))) {
      std::string want, got;
      for (std::size_t d : shape)
        want += (want.empty() ? "" : ", ") + std::to_string(d);
      for (std::size_t d : a.shape)
        got += (got.empty() ? "" : ", ") + std::to_string(d);
      fail((dir / file).string(), "", "shape (" + got + "), the manifest needs (" + want + ")",
           "; the dataset is inconsistent: make it again");
    }
    if (keep) keep->shape = a.shape;
    return std::vector<float>(a.values.begin(), a.values.end());
  };
  ShardArrays a;
  a.samples = entry.samples;
  a.channels = channels;
  const std::size_t n = entry.samples;
  NpyArray shape;
  a.inputs = load("inputs.npy", {n, static_cast<std::size_t>(channels), 0, 0}, &shape);
  a.ny = static_cast<int>(shape.shape[2]);
  a.nx = static_cast<int>(shape.shape[3]);
  a.targets = load("targets.npy", {n, 2, shape.shape[2], shape.shape[3]});
  a.sources = load("sources.npy", {n, 2});
  return a;
}

namespace {

// Rows `row` of an array of [samples, channels, g] floats, one grid per channel.
std::vector<Grid<double>> channels_of(const std::vector<float>& array, int channels, int row,
                                      const GridShape& g) {
  std::vector<Grid<double>> out;
  for (int c = 0; c < channels; ++c) {
    Grid<double> f(g, 0.0);
    const std::size_t off = (static_cast<std::size_t>(row) * channels + c) * g.size();
    std::copy(array.begin() + off, array.begin() + off + g.size(), f.values.begin());
    out.push_back(std::move(f));
  }
  return out;
}

std::string rows_sha256(const std::vector<float>& array, int channels, int row, std::size_t plane) {
  const std::size_t n = channels * plane;
  const char* bytes = reinterpret_cast<const char*>(array.data() + row * n);
  return sha256_hex(std::string_view(bytes, n * sizeof(float)));
}

}  // namespace

DatasetSample read_sample(const fs::path& dir, long long index) {
  const Manifest m = read_manifest(dir / "manifest.json");
  if (index < 0 || index >= m.samples)
    throw OptionError("show.index", std::to_string(index) + ": the dataset has " +
                                        std::to_string(m.samples) + " samples");
  DatasetSample s;
  s.index = index;
  long long start = 0;
  for (const ManifestShard& e : m.shards) {
    if (index < start + e.samples) {
      s.shard = e;
      s.row = static_cast<int>(index - start);
      break;
    }
    start += e.samples;
  }
  const double cell = feature_cell(m);
  const int channels = surrogate::input_channels(cell, physics_input(m));
  const ShardArrays arrays = read_shard(dir, s.shard, channels);
  s.map = read_map(dir / s.shard.map);
  const GridShape g = surrogate::sample_grid(s.map, cell);
  if (g.nx != arrays.nx || g.ny != arrays.ny)
    throw InputError((dir / s.shard.map).string() + ": its feature grid is not the shard's");
  s.source = {arrays.sources[2 * s.row], arrays.sources[2 * s.row + 1]};
  s.inputs = channels_of(arrays.inputs, channels, s.row, g);
  s.targets = channels_of(arrays.targets, 2, s.row, g);
  s.inputs_sha256 = rows_sha256(arrays.inputs, channels, s.row, g.size());
  s.targets_sha256 = rows_sha256(arrays.targets, 2, s.row, g.size());
  return s;
}

}  // namespace plumekit::dataset
