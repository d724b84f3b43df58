#include "dataset/generator.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <tuple>

#include "cfd/flow_policy.hpp"
#include "cfd/grid_check.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "core/seed.hpp"
#include "core/sha256.hpp"
#include "core/temporary_files.hpp"
#include "core/thread_pool.hpp"
#include "dataset/dataset_reader.hpp"
#include "dataset/wind_cache.hpp"
#include "map/map_json.hpp"
#include "surrogate/features.hpp"

namespace plumekit::dataset {

namespace fs = std::filesystem;

namespace {

// The output rule for a dataset folder, which grows in place over resumable
// runs: new, empty, or holding only what generate and merge write. Both mark
// it as a "dataset" folder, so that a merged dataset is byte for byte an
// unsplit one. Returns the folder's lock, shared with the other parts of a
// split run, to hold while writing.
OutputLock claim_dataset_folder(const fs::path& out) {
  const auto own = [](const std::string& name) {
    return name == "maps" || name == "wind" || name == "shards" || name == "parameters.json" ||
           name == "manifest.json" ||
           (name.rfind("manifest.part-", 0) == 0 && fs::path(name).extension() == ".json") ||
           name.find(".plumekit-tmp-") != std::string::npos;
  };
  return claim_output_directory(out, "dataset", {"dataset"}, own, "parameters.json").lock;
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

// The map of index i (random, or given with its sources). A random map's sources are drawn once
// its flow is solved (random_sources_in).
std::pair<Map, std::string> dataset_map(const DatasetOptions& o, int i, int redraw) {
  if (!o.given_maps.empty()) return {o.given_maps[i], o.map_files[i]};
  RandomMap r = random_map(o.map, o.seed, i, redraw);
  if (o.inlet_speed_hi > 0) {
    const double u = drawn_inlet_speed(o, i, redraw);
    for (Opening& op : r.map.openings)
      if (op.is_inlet()) op.speed = u;
  }
  return {r.map, r.family};
}

// A random map's sources in the fluid cells of its solved flow: the cells the plume models work
// on, so that no model finds a source in a cell it counts as solid (a pocket the flow seals off).
std::vector<Vec2> random_sources_in(const DatasetOptions& o, int i, const Map& map,
                                    const cfd::WindField& wind) {
  const FlowCells cells{wind.shape(), wind.solid_cells()};
  return random_sources(map, o.sources, o.source_clearance, o.seed, i, &cells);
}

// The run's own options, and the memory of its worker threads: each solves
// one map's flow at a time.
void check_run_options(const DatasetOptions& o, const RunOptions& run) {
  check_count("dataset.threads", run.threads, 0, 1024, "0 is one per core; one map per thread");
  if (run.part_n <= 0 || run.part_k < 0 || run.part_k >= run.part_n)
    throw OptionError("dataset.shard", "K/N needs 0 <= K < N, got " + std::to_string(run.part_k) +
                                           "/" + std::to_string(run.part_n));
  double cells = 0.0;
  auto grid_cells = [&](const Map& m) {
    const double cell = cfd::resolved_cell(m, o.flow);  // 0: the default from the map's size
    return std::round(m.width / cell) * std::round(m.height / cell);
  };
  if (o.given_maps.empty()) cells = grid_cells(default_arena(o.map.width, o.map.height));
  for (const Map& m : o.given_maps)
    cells = std::max(cells, grid_cells(m));
  const double per_thread = cfd::flow_memory_estimate(cells);
  const int threads = resolve_threads(run.threads);
  if (threads > 1 && !fits_in_memory(threads * per_thread))
    check_memory(threads * per_thread,
                 std::to_string(threads) + " worker threads, each solving one map's flow",
                 "use fewer dataset.threads (" +
                     std::to_string(std::max(1, static_cast<int>(memory_limit() / per_thread))) +
                     " fit)");
}

// A dataset directory belongs to one set of parameters: a resumed run must
// bring the same ones. Checked before anything is written, naming each
// parameter that differs. Returns whether the dataset exists already.
bool check_resume(const fs::path& out, const nlohmann::ordered_json& params) {
  const fs::path pfile = out / "parameters.json";
  if (!fs::exists(pfile)) return false;
  const std::vector<std::string> diff = parameter_differences(params, read_parameters(pfile));
  if (diff.empty()) return true;
  std::string list;
  for (const std::string& d : diff)
    list += "\n  " + d;
  throw InputError(out.string() + " holds a dataset made with other parameters (" + pfile.string() +
                   "):" + list +
                   "\nwrite to another folder, or resume it with the dataset's parameters");
}

// Claims the folder, creates its parts and removes what interrupted runs left;
// returns the folder's lock.
OutputLock prepare_dataset_folder(const fs::path& out, const nlohmann::ordered_json& params,
                                  bool resumed) {
  OutputLock lock = claim_dataset_folder(out);
  for (const char* part : {"maps", "wind", "shards"})
    fs::create_directories(out / part);
  if (!resumed) write_file_atomic(out / "parameters.json", params.dump(2) + "\n");
  for (const char* part : {"maps", "wind", "shards"})
    remove_stale_temporaries_in(out / part);
  remove_stale_temporaries_in(out);
  return lock;
}

// One map of this run (part): its index and sample count.
struct MapJob {
  int index = 0;
  int samples = 0;
};

std::vector<MapJob> part_jobs(const DatasetOptions& o, const RunOptions& run) {
  const int maps = o.given_maps.empty() ? o.maps : static_cast<int>(o.given_maps.size());
  std::vector<MapJob> jobs;
  for (int i = run.part_k; i < maps; i += run.part_n)
    jobs.push_back(
        {i, o.given_maps.empty() ? o.sources : static_cast<int>(o.given_maps[i].sources.size())});
  return jobs;
}

// Counts finished samples from every worker and calls run.progress, one call at a time and at
// most about 5 times a second (plus the last).
class SampleProgress {
 public:
  SampleProgress(const RunOptions& run, long long total) : run_(run), total_(total) {}
  void add(long long samples) {
    const long long done = done_ += samples;
    if (!run_.progress) return;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock() || (done < total_ && since(last_) < 0.2)) return;
    last_ = Clock::now();
    run_.progress(done, total_);
  }
  void finish() {
    std::lock_guard lock(mutex_);
    if (run_.progress) run_.progress(total_, total_);
  }

 private:
  const RunOptions& run_;
  const long long total_;
  std::atomic<long long> done_{0};
  std::mutex mutex_;
  Clock::time_point last_ = Clock::now() - std::chrono::seconds(1);
};

// What one worker did with one map.
struct MapOutcome {
  ShardEntry entry;
  bool resumed = false;  // found complete and verified
  bool cached = false;   // its wind read from the cache
  long long samples = 0;
  double flow_s = 0.0, plume_s = 0.0;
};

struct MapFiles {
  fs::path shard, map, wind;
  MapFiles(const fs::path& out, int index)
      : shard(out / "shards" / shard_name(index)),
        map(out / "maps" / (map_stem(index) + ".json")),
        wind(out / "wind" / map_stem(index)) {}
};

// The family recorded for a map already on disk.
std::string family_from_file(const DatasetOptions& o, int index, const fs::path& map_file) {
  return o.given_maps.empty() ? family_of(read_map(map_file).name) : o.map_files[index];
}

struct MapAndWind {
  Map map;
  std::string family;
  cfd::WindField wind;
  bool cached = false;
};

// The map of `index` and its wind: from the files of an earlier run when they
// are whole, else drawn and solved. A map with no steady flow (vortex shedding
// behind a bluff body at Re ~ 200) cannot be used: a replacement is drawn for
// its index. The map file is written after its wind, so a map file with a wind
// cache is complete.
MapAndWind map_and_wind(const DatasetOptions& o, int index, const MapFiles& files) {
  if (fs::exists(files.map)) {
    Map map = read_map(files.map);
    if (std::optional<cfd::WindField> wind = read_wind_cache(files.wind, map))
      return {std::move(map), family_from_file(o, index, files.map), std::move(*wind), true};
  }
  for (int redraw = 0;; ++redraw) {
    auto [map, family] = dataset_map(o, index, redraw);
    cfd::FlowOptions fo = o.flow;
    fo.on_iteration = nullptr;
    fo.verbose = false;
    try {
      // The flow policy (cfd/flow_policy.hpp); wind.json records the scheme used.
      const cfd::FlowResult flow = cfd::solve_wind(map, fo).flow;
      if (o.given_maps.empty()) map.sources = random_sources_in(o, index, map, flow.wind);
      write_wind_cache(files.wind, flow, fo);
      write_map(map, files.map);
      return {std::move(map), std::move(family), flow.wind, false};
    } catch (const cfd::ConvergenceError& error) {
      if (!o.given_maps.empty()) throw InputError(o.map_files[index] + ": " + error.what());
      if (redraw >= kMaxRedraws)
        throw InputError("map " + std::to_string(index) + ": no steady flow in " +
                         std::to_string(kMaxRedraws + 1) + " draws: " + error.what());
    }
  }
}

// The samples of one map: features and plume targets of each of its sources,
// each source's randomness derived from (seed, map index, source index).
ShardArrays map_samples(const DatasetOptions& o, int index, const Map& map,
                        const cfd::WindField& wind, int samples, SampleProgress& progress) {
  const GridShape sensors = surrogate::sample_grid(map, o.feature_cell);
  std::vector<float> base = surrogate::map_features(map, sensors);
  if (o.feature_cell > 0) {
    const std::vector<float> w = surrogate::wind_features(wind, sensors);
    base.insert(base.end(), w.begin(), w.end());
  }
  const MapPlumes plumes(map, wind, sensors, o.plume);
  std::unique_ptr<surrogate::PhysicsFeature> physics;
  if (o.physics_input)
    physics =
        std::make_unique<surrogate::PhysicsFeature>(map, wind, sensors, physics_mean_options(o));
  ShardArrays a;
  a.samples = samples;
  a.channels = surrogate::input_channels(o.feature_cell, o.physics_input);
  a.nx = sensors.nx;
  a.ny = sensors.ny;
  const std::size_t cells = sensors.size();
  a.inputs.reserve(a.samples * a.channels * cells);
  a.targets.reserve(a.samples * 2 * cells);
  for (int s = 0; s < a.samples; ++s) {
    const Vec2 src = map.sources[s];
    const PlumeTargets p = plumes.run(src, derive_seed(o.seed, index, s, Stream::Filaments));
    a.inputs.insert(a.inputs.end(), base.begin(), base.end());
    if (physics)
      for (double v : (*physics)(src).values)
        a.inputs.push_back(static_cast<float>(v));
    const std::vector<float> d = surrogate::source_feature(src, sensors);
    a.inputs.insert(a.inputs.end(), d.begin(), d.end());
    for (double v : p.mean.values)
      a.targets.push_back(static_cast<float>(v));
    for (double v : p.std.values)
      a.targets.push_back(static_cast<float>(v));
    a.sources.push_back(static_cast<float>(src.x));
    a.sources.push_back(static_cast<float>(src.y));
    a.map_ids.push_back(index);
    progress.add(1);
  }
  return a;
}

// One map's shard: kept when an earlier run finished it, else made.
MapOutcome make_map_shard(const fs::path& out, const DatasetOptions& o, const MapJob& job,
                          SampleProgress& progress) {
  MapOutcome r;
  r.entry.map_index = job.index;
  r.entry.samples = job.samples;
  const MapFiles files(out, job.index);
  if (auto sums = verify_shard(files.shard); sums && fs::exists(files.map)) {
    r.entry.checksums = *sums;
    r.entry.family = family_from_file(o, job.index, files.map);
    r.resumed = true;
    progress.add(job.samples);
    return r;
  }
  const auto t = Clock::now();
  const MapAndWind m = map_and_wind(o, job.index, files);
  r.entry.family = m.family;
  r.cached = m.cached;
  r.flow_s = since(t);
  const auto t1 = Clock::now();
  const ShardArrays a = map_samples(o, job.index, m.map, m.wind, job.samples, progress);
  r.entry.checksums = write_shard(files.shard, a);
  r.samples = a.samples;
  r.plume_s = since(t1);
  return r;
}

}  // namespace

void RunOptions::set_part(const std::string& k_of_n) {
  const PartOfN part = parse_part("dataset.shard", k_of_n);
  part_k = part.k;
  part_n = part.n;
}

void use_map_dir(DatasetOptions& o, const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw OptionError("dataset.map_dir", dir.string() + ": not a directory");
  std::vector<fs::path> files;
  // Hidden files are not maps: a `maps random` folder holds its output marker,
  // .plumekit-output.json.
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".json" && e.path().filename().string()[0] != '.')
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw OptionError("dataset.map_dir", dir.string() + ": no .json maps");
  o.given_maps.clear();
  o.map_files.clear();
  for (const auto& f : files) {
    o.given_maps.push_back(read_map(f));
    o.map_files.push_back(f.filename().string());
  }
}

std::string part_manifest_name(int k, int n) {
  return "manifest.part-" + std::to_string(k) + "-of-" + std::to_string(n) + ".json";
}

DatasetSummary generate_dataset(const fs::path& out, const DatasetOptions& o,
                                const RunOptions& run) {
  const auto t0 = Clock::now();
  // Every option is checked before anything is written (docs/design/dataset.md).
  o.validate();
  check_run_options(o, run);
  const nlohmann::ordered_json params = parameters_json(o);
  const OutputLock lock = prepare_dataset_folder(out, params, check_resume(out, params));

  const std::vector<MapJob> jobs = part_jobs(o, run);
  long long total = 0;
  for (const MapJob& j : jobs)
    total += j.samples;
  SampleProgress progress(run, total);
  std::vector<MapOutcome> outcomes(jobs.size());
  // One map per index: its bytes depend on (seed, index) only, never on the thread that made it.
  ThreadPool pool(
      std::min<int>(resolve_threads(run.threads), std::max<int>(1, static_cast<int>(jobs.size()))));
  pool.parallel_for(
      jobs.size(), [&](std::size_t m) { outcomes[m] = make_map_shard(out, o, jobs[m], progress); });
  progress.finish();

  DatasetSummary summary;
  summary.maps = static_cast<int>(jobs.size());
  std::vector<ShardEntry> entries;
  for (const MapOutcome& r : outcomes) {
    entries.push_back(r.entry);
    summary.maps_resumed += r.resumed;
    summary.winds_cached += r.cached;
    summary.samples += r.samples;
    summary.flow_s += r.flow_s;
    summary.plume_s += r.plume_s;
  }
  const std::string name =
      run.part_n > 1 ? part_manifest_name(run.part_k, run.part_n) : std::string("manifest.json");
  write_file_atomic(out / name,
                    manifest_json(params, entries, run.part_k, run.part_n).dump(2) + "\n");
  summary.threads = pool.size();
  summary.seconds = since(t0);
  return summary;
}

namespace {

// Which part folder holds each map, and the joined manifest's entries.
struct MergePlan {
  nlohmann::ordered_json params;
  std::vector<ShardEntry> entries;
  std::vector<fs::path> from;
  fs::path first;  // the folder whose parameters.json is copied
  MergeSummary summary;
};

// The checksums cover a shard's files, not the manifest's sample count: a count that differs from
// the shard's arrays would give a merged dataset that its readers refuse.
void check_sample_count(const fs::path& dir, const std::string& part, const ManifestShard& s) {
  const long long held = shard_samples(dir / "shards" / s.name);
  if (held != s.samples)
    throw InputError("dataset merge: " + part + " in " + dir.string() + ": its manifest gives " +
                     s.name + " " + std::to_string(s.samples) + " samples, but " +
                     (dir / "shards" / s.name).string() + " holds " + std::to_string(held) +
                     "; run that part's `plumekit dataset generate --shard` again to rewrite "
                     "its manifest");
}

// Checks that the parts share one set of parameters and one split and hold every map exactly
// once, verifying each shard against its checksums.
MergePlan plan_merge(const std::vector<std::pair<fs::path, Manifest>>& manifests) {
  MergePlan plan;
  plan.first = manifests.front().first;
  plan.params = manifests.front().second.generator;
  const int n = manifests.front().second.part_n;
  const int maps = manifests.front().second.maps;
  std::map<int, fs::path> parts_seen;  // part k -> its folder
  plan.entries.resize(maps);
  plan.from.resize(maps);
  std::vector<bool> have(maps, false);
  for (const auto& [dir, m] : manifests) {
    if (m.generator != plan.params)
      throw InputError(dir.string() + ": its parts were made with other parameters");
    if (m.part_n != n) throw InputError(dir.string() + ": parts of different splits (N differs)");
    const std::string part = "part " + std::to_string(m.part_k) + " of " + std::to_string(n);
    if (const auto [at, added] = parts_seen.emplace(m.part_k, dir); !added)
      throw InputError("dataset merge: " + part + " is given twice: in " + at->second.string() +
                       " and in " + dir.string() + "; give each part once");
    for (const ManifestShard& s : m.shards) {
      const int i = s.map_index;  // in 0..maps-1: the generators are equal
      if (have[i]) throw InputError(dir.string() + ": map " + std::to_string(i) + " twice");
      have[i] = true;
      plan.entries[i] = {i, s.family, s.samples, s.sha256};
      plan.from[i] = dir;
      check_shard(dir / "shards" / s.name, s.sha256);
      check_sample_count(dir, part, s);
      ++plan.summary.shards;
      plan.summary.samples += s.samples;
    }
  }
  // The parameters.json copied into `out` must be the parameters of the parts it joins.
  const fs::path pfile = plan.first / "parameters.json";
  if (read_parameters(pfile) != plan.params)
    throw InputError(pfile.string() +
                     ": differs from the \"generator\" of the part manifests beside it; "
                     "restore it from one of them");
  for (int k = 0; k < n; ++k)
    if (!parts_seen.count(k))
      throw InputError("dataset merge: part " + std::to_string(k) + " of " + std::to_string(n) +
                       " is missing");
  for (int i = 0; i < maps; ++i)
    if (!have[i]) throw InputError("dataset merge: no part holds map " + std::to_string(i));
  plan.summary.parts = static_cast<int>(parts_seen.size());
  return plan;
}

void copy_dir(const fs::path& src, const fs::path& dst) {
  AtomicDirectory copy(dst);
  fs::copy(src, copy.path(), fs::copy_options::recursive);
  copy.commit();
}

// Copies each map's shard, wind and map file (those not in `out` already) and
// the parameters; returns the folder's lock.
OutputLock copy_parts(const fs::path& out, const MergePlan& plan) {
  OutputLock lock = claim_dataset_folder(out);
  for (const char* part : {"shards", "maps", "wind"})
    fs::create_directories(out / part);
  for (std::size_t k = 0; k < plan.from.size(); ++k) {
    const int i = static_cast<int>(k);
    if (fs::weakly_canonical(plan.from[k]) == fs::weakly_canonical(out)) continue;
    const std::string stem = map_stem(i);
    copy_dir(plan.from[k] / "shards" / shard_name(i), out / "shards" / shard_name(i));
    copy_dir(plan.from[k] / "wind" / stem, out / "wind" / stem);
    write_file_atomic(out / "maps" / (stem + ".json"),
                      read_file(plan.from[k] / "maps" / (stem + ".json")));
  }
  if (fs::weakly_canonical(plan.first) != fs::weakly_canonical(out))
    write_file_atomic(out / "parameters.json", read_file(plan.first / "parameters.json"));
  return lock;
}

}  // namespace

MergeSummary merge_datasets(const fs::path& out, const std::vector<fs::path>& parts) {
  if (parts.empty()) throw InputError("dataset merge: name at least one part directory");
  std::vector<std::pair<fs::path, Manifest>> manifests;
  std::map<fs::path, std::size_t> seen_dirs;  // folder -> its argument
  for (std::size_t a = 0; a < parts.size(); ++a) {
    const fs::path& dir = parts[a];
    // A folder given twice is a slip for another part's folder: naming both arguments says which.
    if (const auto [at, added] = seen_dirs.emplace(fs::weakly_canonical(dir), a); !added)
      throw InputError("dataset merge: part folder " + dir.string() + " is given twice (argument " +
                       std::to_string(at->second + 1) + ", " + parts[at->second].string() +
                       ", and argument " + std::to_string(a + 1) + ", " + dir.string() +
                       "); give each part folder once");
    for (Manifest& m : read_part_manifests(dir))
      manifests.emplace_back(dir, std::move(m));
  }
  const MergePlan plan = plan_merge(manifests);
  const OutputLock lock = copy_parts(out, plan);
  write_file_atomic(out / "manifest.json",
                    manifest_json(plan.params, plan.entries, 0, 1).dump(2) + "\n");
  return plan.summary;
}

}  // namespace plumekit::dataset
