#include "ste/evaluation_parts.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"

namespace plumekit::ste {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// One run's figures at full precision (JSON numbers round-trip a double exactly): what the
// summary's statistics, the box plots and timings.json are computed from.
ordered_json run_row(const RunRecord& r) {
  // The trackers' two criteria last (null: no overhead), so STE's rows keep their first 11.
  return ordered_json::array({r.map_index, r.source_index, r.run, r.seed, r.error_m, r.samples,
                              r.distance_m, r.mission_s, r.stopped_by, r.compute_s, r.median_step_s,
                              r.reached,
                              std::isfinite(r.distance_overhead) ? ordered_json(r.distance_overhead)
                                                                 : ordered_json(nullptr)});
}

RunRecord parse_run_row(const ordered_json& row, const ordered_json& maps) {
  RunRecord r;
  r.map_index = row.at(0).get<int>();
  r.map = maps.at(r.map_index).at("name").get<std::string>();
  r.source_index = row.at(1).get<int>();
  r.run = row.at(2).get<int>();
  r.seed = row.at(3).get<std::uint64_t>();
  r.error_m = row.at(4).get<double>();
  r.samples = row.at(5).get<int>();
  r.distance_m = row.at(6).get<double>();
  r.mission_s = row.at(7).get<double>();
  r.stopped_by = row.at(8).get<std::string>();
  r.compute_s = row.at(9).get<double>();
  r.median_step_s = row.at(10).get<double>();
  if (row.size() > 12) {
    r.reached = row.at(11).get<bool>();
    if (!row.at(12).is_null()) r.distance_overhead = row.at(12).get<double>();
  }
  return r;
}

// The SHA-256 of part.json's content without its own "sha256" key.
std::string body_sha256(ordered_json j) {
  j.erase("sha256");
  return sha256_hex(j.dump());
}

// A CSV file's header line and the lines after it.
struct CsvParts {
  std::string header, body;
};

struct Part {
  fs::path dir;
  ordered_json j;
  int k = 0, n = 1;
  std::vector<RunRecord> runs;
  CsvParts runs_csv, timings_csv;
};

CsvParts read_csv(const fs::path& dir, const std::string& name, const ordered_json& sums,
                  std::size_t lines) {
  const fs::path file = dir / name;
  const std::string bytes = read_file(file);
  if (sha256_hex(bytes) != sums.at(name).get<std::string>())
    throw InputError(file.string() + ": does not match its checksum in " +
                     (dir / kPartFile).string() + "; rerun that part");
  // Records, not lines: a quoted map name may hold a line break.
  const std::vector<std::vector<std::string>> records = parse_csv(bytes, file.string());
  const std::size_t eol = bytes.find('\n');  // the header names no field that needs quotes
  if (eol == std::string::npos || bytes.back() != '\n' || records.size() != lines + 1)
    throw InputError(file.string() + ": should hold a header and " + std::to_string(lines) +
                     " runs");
  for (std::size_t k = 1; k < records.size(); ++k)
    if (records[k].size() != records.front().size())
      throw InputError(file.string() + ": run " + std::to_string(k) + " has " +
                       std::to_string(records[k].size()) + " fields, the header " +
                       std::to_string(records.front().size()));
  return {bytes.substr(0, eol + 1), bytes.substr(eol + 1)};
}

// Throws a json exception unless part.json holds every key the merge reads, of its type.
void check_shape(const ordered_json& j) {
  const ordered_json& s = j.at("settings");
  s.at("runs_per_source").get<long long>();
  s.at("seeds").get<int>();
  // The summary's label: STE's plume model, or the method.
  if (s.value("method", std::string("ste")) == "ste")
    s.at("plume_model").get<std::string>();
  else
    s.at("method").get<std::string>();
  j.at("options").items();
  for (const char* key : {"first", "end", "total"})
    j.at("pairs").at(key).get<long long>();
  j.at("threads").get<int>();
  j.at("wall_s").get<double>();
  const ordered_json& maps = j.at("maps");
  if (!maps.is_array() || maps.empty() || j.at("map_times").size() != maps.size())
    throw InputError("\"maps\" and \"map_times\" must list the same maps");
  for (std::size_t i = 0; i < maps.size(); ++i) {
    maps[i].at("name").get<std::string>();
    const ordered_json& t = j.at("map_times")[i];
    t.at("ran").get<bool>();
    for (const char* key : {"wind_s", "table_build_s", "wall_s"})
      t.at(key).get<double>();
  }
}

// Reads and checks one part folder's part.json and files (its checksums, its own pair range).
Part read_part(const fs::path& dir) {
  const fs::path file = dir / kPartFile;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError(dir.string() + ": holds no " + kPartFile +
                     "; name the --out folders of `plumekit evaluate --shard K/N`");
  Part p;
  p.dir = dir;
  try {
    p.j = ordered_json::parse(read_file(file));
    if (p.j.at("format").get<std::string>() != kPartFormat)
      throw InputError(file.string() + ": \"format\" is not " + kPartFormat);
    if (p.j.at("sha256").get<std::string>() != body_sha256(p.j))
      throw InputError(file.string() +
                       ": does not match its own checksum (damaged or edited); "
                       "rerun that part");
    check_shape(p.j);
    p.k = p.j.at("part").get<int>();
    p.n = p.j.at("parts").get<int>();
    if (p.n < 1 || p.k < 0 || p.k >= p.n)
      throw InputError(file.string() + ": part " + std::to_string(p.k) + " of " +
                       std::to_string(p.n) + " is no part");
    for (const auto& row : p.j.at("runs"))
      p.runs.push_back(parse_run_row(row, p.j.at("maps")));
    p.runs_csv = read_csv(dir, "runs.csv", p.j.at("files"), p.runs.size());
    p.timings_csv = read_csv(dir, "timings.csv", p.j.at("files"), p.runs.size());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": not a well-formed evaluate part (" + e.what() + ")");
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind(dir.string(), 0) == 0) throw;  // names its file already
    throw InputError(file.string() + ": " + what);
  }
  return p;
}

// The first key of `a` or `b` whose values differ, or "".
std::string first_difference(const ordered_json& a, const ordered_json& b) {
  for (const auto& [key, value] : a.items())
    if (!b.contains(key) || b.at(key) != value) return key;
  for (const auto& [key, value] : b.items())
    if (!a.contains(key)) return key;
  return "";
}

std::string shown(const ordered_json& j, const std::string& key) {
  return j.contains(key) ? j.at(key).dump() : std::string("absent");
}

// The parts must come from one evaluation: one split, one set of options and maps.
void check_same(const Part& first, const Part& p) {
  const auto differs = [&](const char* what, const std::string& key) {
    throw InputError(p.dir.string() + ": its " + what + " " + key + " is " +
                     shown(p.j.at(what), key) + ", " + first.dir.string() + "'s " +
                     shown(first.j.at(what), key) +
                     ": not parts of one evaluation; rerun the parts with one set of options");
  };
  if (p.n != first.n)
    throw InputError(p.dir.string() + ": part of a split into " + std::to_string(p.n) + " parts, " +
                     first.dir.string() + " of one into " + std::to_string(first.n));
  for (const char* what : {"options", "settings"})
    if (const std::string key = first_difference(first.j.at(what), p.j.at(what)); !key.empty())
      differs(what, key);
  if (first.j.at("maps") != p.j.at("maps"))
    throw InputError(p.dir.string() + ": its maps (files or their SHA-256) differ from those of " +
                     first.dir.string() + "; evaluate every part on the same map folder");
}

// Every part 0..N-1 exactly once, each with the pairs and runs its K/N gives.
void check_coverage(const std::vector<Part>& parts) {
  const int n = parts.front().n;
  std::map<int, const Part*> by_k;
  for (const Part& p : parts) {
    if (const auto it = by_k.find(p.k); it != by_k.end())
      throw InputError("evaluate merge: part " + std::to_string(p.k) + " of " + std::to_string(n) +
                       " is given twice (" + it->second->dir.string() + " and " + p.dir.string() +
                       ")");
    by_k[p.k] = &p;
  }
  for (int k = 0; k < n; ++k)
    if (!by_k.count(k))
      throw InputError("evaluate merge: part " + std::to_string(k) + " of " + std::to_string(n) +
                       " is missing (run `plumekit evaluate --shard " + std::to_string(k) + "/" +
                       std::to_string(n) + "` with the same options)");
  const ordered_json& s = parts.front().j.at("settings");
  const long long per_pair = s.at("runs_per_source").get<long long>() * s.at("seeds").get<int>();
  for (const Part& p : parts) {
    const ordered_json& pairs = p.j.at("pairs");
    const long long total = pairs.at("total").get<long long>();
    const long long first = total * p.k / n, end = total * (p.k + 1) / n;
    if (pairs.at("first").get<long long>() != first || pairs.at("end").get<long long>() != end ||
        static_cast<long long>(p.runs.size()) != (end - first) * per_pair)
      throw InputError((p.dir / kPartFile).string() + ": its runs are not those of part " +
                       std::to_string(p.k) + " of " + std::to_string(n));
  }
}

// The runs of all parts in run order, each map's statistics and times, and the files.
MergedEvaluation join(const std::vector<Part>& parts) {
  MergedEvaluation m;
  EvaluationResult& res = m.result;
  const ordered_json& first = parts.front().j;
  res.seeds = first.at("settings").at("seeds").get<int>();
  res.method = first.at("settings").value("method", std::string("ste"));
  res.pairs = {0, first.at("pairs").at("total").get<long long>(),
               first.at("pairs").at("total").get<long long>()};
  for (const auto& map : first.at("maps"))
    res.maps.push_back(MapReport{map.at("name").get<std::string>(), {}, {}, 0, 0, 0});
  std::vector<bool> timed(res.maps.size(), false);
  ordered_json part_times = ordered_json::array();
  m.files.runs_csv = parts.front().runs_csv.header;
  m.files.timings_csv = parts.front().timings_csv.header;
  for (const Part& p : parts) {
    res.runs.insert(res.runs.end(), p.runs.begin(), p.runs.end());
    m.files.runs_csv += p.runs_csv.body;
    m.files.timings_csv += p.timings_csv.body;
    const ordered_json& times = p.j.at("map_times");
    for (std::size_t i = 0; i < res.maps.size(); ++i) {
      MapReport& mr = res.maps[i];
      const ordered_json& t = times.at(i);
      if (t.at("ran").get<bool>() && !timed[i]) {  // the wind and table of the map's first part
        mr.wind_s = t.at("wind_s").get<double>();
        mr.table_build_s = t.at("table_build_s").get<double>();
        timed[i] = true;
      }
      mr.wall_s += t.at("wall_s").get<double>();
    }
    res.wall_s += p.j.at("wall_s").get<double>();
    part_times.push_back(
        {{"part", p.k}, {"threads", p.j.at("threads")}, {"wall_s", p.j.at("wall_s")}});
  }
  for (std::size_t i = 0; i < res.maps.size(); ++i) {
    std::vector<const RunRecord*> runs;
    for (const RunRecord& r : res.runs)
      if (r.map_index == static_cast<int>(i)) runs.push_back(&r);
    res.maps[i].stats = summarise(runs);
  }
  std::vector<const RunRecord*> all;
  for (const RunRecord& r : res.runs)
    all.push_back(&r);
  res.overall = summarise(all);
  m.files.timings = evaluation_timings(res);
  m.files.timings.erase("threads");  // per part, below
  m.files.timings["parts"] = part_times;
  m.parts = static_cast<int>(parts.size());
  return m;
}

}  // namespace

ordered_json map_files_json(const MapFolder& maps) {
  ordered_json j = ordered_json::array();
  for (std::size_t i = 0; i < maps.files.size(); ++i)
    j.push_back({{"file", maps.files[i].filename().string()},
                 {"name", maps.maps[i].name},
                 {"sha256", sha256_file(maps.files[i])}});
  return j;
}

ordered_json part_json(const EvaluationResult& res, const EvaluationOptions& o,
                       const PartIdentity& id, const EvaluationFiles& files) {
  ordered_json runs = ordered_json::array(), times = ordered_json::array();
  for (const RunRecord& r : res.runs)
    runs.push_back(run_row(r));
  std::vector<bool> ran(res.maps.size(), false);
  for (const RunRecord& r : res.runs)
    ran.at(r.map_index) = true;
  for (std::size_t i = 0; i < res.maps.size(); ++i)
    times.push_back({{"ran", static_cast<bool>(ran[i])},
                     {"wind_s", res.maps[i].wind_s},
                     {"table_build_s", res.maps[i].table_build_s},
                     {"wall_s", res.maps[i].wall_s}});
  ordered_json j{
      {"format", kPartFormat},
      {"part", o.part_k},
      {"parts", o.part_n},
      {"pairs", {{"first", res.pairs.first}, {"end", res.pairs.end}, {"total", res.pairs.total}}},
      {"settings", id.settings},
      {"options", id.options},
      {"maps", id.maps},
      {"files",
       {{"runs.csv", sha256_hex(files.runs_csv)}, {"timings.csv", sha256_hex(files.timings_csv)}}},
      {"threads", res.threads},
      {"wall_s", res.wall_s},
      {"map_times", times},
      {"runs", runs}};
  j["sha256"] = body_sha256(j);
  return j;
}

MergedEvaluation merge_evaluation_parts(const std::vector<fs::path>& dirs) {
  if (dirs.empty()) throw InputError("evaluate merge: name the part folders");
  std::vector<Part> parts;
  for (const fs::path& dir : dirs)
    parts.push_back(read_part(dir));
  for (const Part& p : parts)
    check_same(parts.front(), p);
  check_coverage(parts);
  std::sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.k < b.k; });
  for (const Part& p : parts)
    if (p.runs_csv.header != parts.front().runs_csv.header ||
        p.timings_csv.header != parts.front().timings_csv.header)
      throw InputError((p.dir / "runs.csv").string() + ": its header differs from " +
                       (parts.front().dir / "runs.csv").string() + "'s");
  MergedEvaluation m = join(parts);
  m.settings = parts.front().j.at("settings");
  m.files.summary = evaluation_report(m.result, m.settings, {}).json;
  return m;
}

}  // namespace plumekit::ste
