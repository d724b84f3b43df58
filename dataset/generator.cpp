#include "dataset/generator.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <set>
#include <thread>
#include <tuple>

#include "cfd/flow_policy.hpp"
#include "cfd/grid_check.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/map_json.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "dataset/dataset_reader.hpp"
#include "dataset/features.hpp"
#include "dataset/seed.hpp"
#include "core/sha256.hpp"
#include "dataset/wind_cache.hpp"

namespace plumekit::dataset {

namespace fs = std::filesystem;

namespace {

// The output rule for a dataset folder, which grows in place over resumable
// runs: new, empty, or holding only what generate and merge write. Both mark
// it as a "dataset" folder, so that a merged dataset is byte for byte an
// unsplit one.
void claim_dataset_folder(const fs::path& out) {
  const auto own = [](const std::string& name) {
    return name == "maps" || name == "wind" || name == "shards" || name == "parameters.json" ||
           name == "manifest.json" ||
           (name.rfind("manifest.part-", 0) == 0 && fs::path(name).extension() == ".json") ||
           name.find(".plumekit-tmp-") != std::string::npos;
  };
  claim_output_directory(out, "dataset", {"dataset"}, own, "parameters.json");
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string map_stem(int index) {
  return "map-" + shard_name(index).substr(6);
}

// Replacement draws for a random map whose steady flow does not converge.
constexpr int kMaxRedraws = 8;

// The map of index i and its sources (random, or given).
std::pair<Map, std::string> dataset_map(const DatasetOptions& o, int i, int redraw) {
  if (!o.given_maps.empty()) return {o.given_maps[i], o.map_files[i]};
  RandomMap r = random_map(o.map, o.seed, i, redraw);
  r.map.sources = random_sources(r.map, o.sources, o.source_clearance, o.seed, i);
  return {r.map, r.family};
}

// The run's own options, and the memory of its worker threads: each solves
// one map's flow at a time.
void check_run_options(const DatasetOptions& o, const RunOptions& run) {
  check_count("dataset.threads", run.threads, 1, 1024, "one map per thread");
  if (run.part_n <= 0 || run.part_k < 0 || run.part_k >= run.part_n)
    throw OptionError("dataset.shard", "K/N needs 0 <= K < N, got " + std::to_string(run.part_k) +
                                           "/" + std::to_string(run.part_n));
  double cells = 0.0;
  auto grid_cells = [&](const Map& m) {
    return std::round(m.width / o.flow.cell) * std::round(m.height / o.flow.cell);
  };
  if (o.given_maps.empty()) cells = grid_cells(default_arena(o.map.width, o.map.height));
  for (const Map& m : o.given_maps)
    cells = std::max(cells, grid_cells(m));
  const double per_thread = cfd::flow_memory_estimate(cells);
  if (run.threads > 1 && !fits_in_memory(run.threads * per_thread))
    check_memory(run.threads * per_thread,
                 std::to_string(run.threads) + " worker threads, each solving one map's flow",
                 "use fewer dataset.threads (" +
                     std::to_string(std::max(1, static_cast<int>(memory_limit() / per_thread))) +
                     " fit)");
}

}  // namespace

std::string part_manifest_name(int k, int n) {
  return "manifest.part-" + std::to_string(k) + "-of-" + std::to_string(n) + ".json";
}

DatasetSummary generate_dataset(const fs::path& out, const DatasetOptions& o,
                                const RunOptions& run) {
  const auto t0 = Clock::now();
  const int maps = o.given_maps.empty() ? o.maps : static_cast<int>(o.given_maps.size());
  // Every option is checked before anything is written (dataset/README.md).
  o.validate();
  check_run_options(o, run);

  // A dataset directory belongs to one set of parameters.
  // Checked before anything is written, naming each parameter that differs.
  const nlohmann::ordered_json params = parameters_json(o);
  const fs::path pfile = out / "parameters.json";
  const bool resumed = fs::exists(pfile);
  if (resumed) {
    const std::vector<std::string> diff = parameter_differences(params, read_parameters(pfile));
    if (!diff.empty()) {
      std::string list;
      for (const std::string& d : diff)
        list += "\n  " + d;
      throw InputError(out.string() + " holds a dataset made with other parameters (" +
                       pfile.string() + "):" + list +
                       "\nuse another --out, or the dataset's parameters to resume it");
    }
  }
  claim_dataset_folder(out);
  fs::create_directories(out / "maps");
  fs::create_directories(out / "wind");
  fs::create_directories(out / "shards");
  if (!resumed) write_file_atomic(pfile, params.dump(2) + "\n");
  remove_temporaries(out / "maps");
  remove_temporaries(out / "wind");
  remove_temporaries(out / "shards");

  std::vector<int> mine;
  for (int i = run.part_k; i < maps; i += run.part_n)
    mine.push_back(i);
  std::vector<ShardEntry> entries(mine.size());
  long long total = 0;
  std::vector<int> samples_of(mine.size());
  for (std::size_t m = 0; m < mine.size(); ++m) {
    samples_of[m] =
        o.given_maps.empty() ? o.sources : static_cast<int>(o.given_maps[mine[m]].sources.size());
    total += samples_of[m];
  }

  DatasetSummary summary;
  summary.maps = static_cast<int>(mine.size());
  std::atomic<std::size_t> next{0};
  std::atomic<long long> done{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex mutex;

  auto work = [&] {
    while (!failed) {
      const std::size_t m = next++;
      if (m >= mine.size()) return;
      try {
        const int index = mine[m];
        ShardEntry& e = entries[m];
        e.map_index = index;
        e.samples = samples_of[m];
        const fs::path shard_dir = out / "shards" / shard_name(index);
        const fs::path map_file = out / "maps" / (map_stem(index) + ".json");
        const fs::path wind_dir = out / "wind" / map_stem(index);
        auto family_from_file = [&] {
          return o.given_maps.empty() ? family_of(read_map(map_file).name) : o.map_files[index];
        };
        if (auto sums = verify_shard(shard_dir); sums && fs::exists(map_file)) {
          e.checksums = *sums;
          e.family = family_from_file();
          done += e.samples;
          std::lock_guard lock(mutex);
          ++summary.maps_resumed;
          continue;
        }
        auto t = Clock::now();
        Map map;
        std::string family;
        std::optional<cfd::WindField> wind;
        if (fs::exists(map_file)) {
          map = read_map(map_file);
          wind = read_wind_cache(wind_dir, map);  // nullopt when damaged: solved again
        }
        const bool cached = wind.has_value();
        if (cached) {
          family = family_from_file();
        } else {
          // A map with no steady flow (vortex shedding behind a bluff body
          // at Re ~ 200) cannot be used: draw a replacement for its index.
          for (int redraw = 0;; ++redraw) {
            std::tie(map, family) = dataset_map(o, index, redraw);
            cfd::FlowOptions fo = o.flow;
            fo.on_iteration = nullptr;
            fo.verbose = false;
            try {
              // The flow policy (cfd/flow_policy.hpp); wind.json records the scheme used.
              const cfd::FlowResult flow = cfd::solve_wind(map, fo).flow;
              write_wind_cache(wind_dir, flow, fo);
              wind = flow.wind;
              break;
            } catch (const cfd::ConvergenceError& error) {
              if (!o.given_maps.empty()) throw InputError(o.map_files[index] + ": " + error.what());
              if (redraw >= kMaxRedraws)
                throw InputError("map " + std::to_string(index) + ": no steady flow in " +
                                 std::to_string(kMaxRedraws + 1) + " draws: " + error.what());
            }
          }
          write_map(map, map_file);  // after its wind: a map file with a wind cache is complete
        }
        e.family = family;
        const double flow_s = since(t);
        t = Clock::now();
        const GridShape sensors = feature_grid(map);
        const std::vector<float> base = map_features(map, sensors);
        const MapPlumes plumes(map, *wind, sensors, o.plume);
        ShardArrays a;
        a.samples = e.samples;
        const std::size_t cells = sensors.size();
        a.inputs.reserve(a.samples * 3 * cells);
        a.targets.reserve(a.samples * 2 * cells);
        for (int s = 0; s < a.samples; ++s) {
          const Vec2 src = map.sources[s];
          const PlumeTargets p = plumes.run(src, derive_seed(o.seed, index, s, Stream::Filaments));
          a.inputs.insert(a.inputs.end(), base.begin(), base.end());
          const std::vector<float> d = source_feature(src, sensors);
          a.inputs.insert(a.inputs.end(), d.begin(), d.end());
          for (double v : p.mean.values)
            a.targets.push_back(static_cast<float>(v));
          for (double v : p.std.values)
            a.targets.push_back(static_cast<float>(v));
          a.sources.push_back(static_cast<float>(src.x));
          a.sources.push_back(static_cast<float>(src.y));
          a.map_ids.push_back(index);
          ++done;
        }
        e.checksums = write_shard(shard_dir, a);
        std::lock_guard lock(mutex);
        summary.samples += a.samples;
        summary.flow_seconds += flow_s;
        summary.plume_seconds += since(t);
        if (cached) ++summary.winds_cached;
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  const int threads = std::min<int>(run.threads, std::max<std::size_t>(1, mine.size()));
  for (int t = 0; t < threads; ++t)
    pool.emplace_back(work);
  while (true) {
    const long long d = done;
    if (run.progress) run.progress(d, total);
    bool finished = true;
    {
      std::lock_guard lock(mutex);
      finished = failed || d >= total;
    }
    if (finished) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  for (auto& th : pool)
    th.join();
  if (error) std::rethrow_exception(error);
  if (run.progress) run.progress(total, total);

  const std::string name =
      run.part_n > 1 ? part_manifest_name(run.part_k, run.part_n) : std::string("manifest.json");
  write_file_atomic(out / name,
                    manifest_json(params, entries, run.part_k, run.part_n).dump(2) + "\n");
  summary.seconds = since(t0);
  return summary;
}

MergeSummary merge_datasets(const fs::path& out, const std::vector<fs::path>& parts) {
  if (parts.empty()) throw InputError("dataset merge: name at least one part directory");
  std::vector<std::pair<fs::path, Manifest>> manifests;
  std::set<fs::path> seen_dirs;
  for (const fs::path& dir : parts) {
    const fs::path canon = fs::weakly_canonical(dir);
    if (!seen_dirs.insert(canon).second) continue;
    if (!fs::is_directory(dir)) throw InputError(dir.string() + ": not a directory");
    bool any = false;
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string f = e.path().filename().string();
      if (f.rfind("manifest.part-", 0) == 0 && e.path().extension() == ".json") {
        manifests.emplace_back(dir, read_manifest(e.path()));
        any = true;
      }
    }
    if (!any) throw InputError(dir.string() + ": no manifest.part-K-of-N.json in it");
  }
  const nlohmann::ordered_json& params = manifests.front().second.generator;
  const int n = manifests.front().second.part_n;
  const int maps = manifests.front().second.maps;
  std::set<int> parts_seen;
  std::vector<ShardEntry> entries(maps);
  std::vector<fs::path> from(maps);
  std::vector<bool> have(maps, false);
  MergeSummary summary;
  for (const auto& [dir, m] : manifests) {
    if (m.generator != params)
      throw InputError(dir.string() + ": its parts were made with other parameters");
    if (m.part_n != n) throw InputError(dir.string() + ": parts of different splits (N differs)");
    parts_seen.insert(m.part_k);
    for (const ManifestShard& s : m.shards) {
      const int i = s.map_index;  // in 0..maps-1: the generators are equal
      if (have[i]) throw InputError(dir.string() + ": map " + std::to_string(i) + " twice");
      have[i] = true;
      ShardEntry& e = entries[i];
      e.map_index = i;
      e.family = s.family;
      e.samples = s.samples;
      e.checksums = s.sha256;
      from[i] = dir;
      check_shard(dir / "shards" / s.name, s.sha256);
      ++summary.shards;
      summary.samples += e.samples;
    }
  }
  {
    // The parameters.json copied into `out` must be the parameters of the parts it joins.
    const fs::path pfile = manifests.front().first / "parameters.json";
    if (read_parameters(pfile) != params)
      throw InputError(pfile.string() +
                       ": differs from the \"generator\" of the part manifests beside it; "
                       "restore it from one of them");
  }
  for (int k = 0; k < n; ++k)
    if (!parts_seen.count(k))
      throw InputError("dataset merge: part " + std::to_string(k) + " of " + std::to_string(n) +
                       " is missing");
  for (int i = 0; i < maps; ++i)
    if (!have[i]) throw InputError("dataset merge: no part holds map " + std::to_string(i));
  summary.parts = static_cast<int>(parts_seen.size());

  claim_dataset_folder(out);
  fs::create_directories(out / "shards");
  fs::create_directories(out / "maps");
  fs::create_directories(out / "wind");
  for (int i = 0; i < maps; ++i) {
    if (fs::weakly_canonical(from[i]) == fs::weakly_canonical(out)) continue;
    const std::string stem = map_stem(i);
    const auto copy_dir = [](const fs::path& src, const fs::path& dst) {
      const fs::path tmp = dst.string() + ".tmp-merge";
      fs::remove_all(tmp);
      fs::copy(src, tmp, fs::copy_options::recursive);
      fs::remove_all(dst);
      fs::rename(tmp, dst);
    };
    copy_dir(from[i] / "shards" / shard_name(i), out / "shards" / shard_name(i));
    copy_dir(from[i] / "wind" / stem, out / "wind" / stem);
    write_file_atomic(out / "maps" / (stem + ".json"),
                      read_file(from[i] / "maps" / (stem + ".json")));
  }
  if (fs::weakly_canonical(manifests.front().first) != fs::weakly_canonical(out))
    write_file_atomic(out / "parameters.json",
                      read_file(manifests.front().first / "parameters.json"));
  write_file_atomic(out / "manifest.json", manifest_json(params, entries, 0, 1).dump(2) + "\n");
  return summary;
}

}  // namespace plumekit::dataset
