#include "run/evaluation_part_reader.hpp"

#include <limits>
#include <map>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"
#include "run/run_tracks.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// The integer `name` of part.json, in [lo, hi]. Only a JSON integer: nlohmann converts a float
// such as 1e60 to an int by a cast that is undefined behaviour (the fuzzer found it), so a float,
// or an integer out of range, is refused with the bounds.
long long whole(const ordered_json& v, const std::string& name, long long lo, long long hi) {
  if (!v.is_number_integer())
    throw InputError(name + " is " + v.dump().substr(0, 40) + ", not a whole number");
  const bool above = v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(hi);
  const long long x = above ? hi : v.get<long long>();
  if (above || x < lo || x > hi)
    throw InputError(name + " is " + v.dump() + ", outside " + std::to_string(lo) + ".." +
                     std::to_string(hi));
  return x;
}

int whole_int(const ordered_json& v, const std::string& name,
              int lo = std::numeric_limits<int>::min()) {
  return static_cast<int>(whole(v, name, lo, std::numeric_limits<int>::max()));
}

// A run row of part.json (evaluation_parts.cpp writes it: run_row), its map named from "maps".
RunRecord parse_run_row(const ordered_json& row, const ordered_json& maps) {
  RunRecord r;
  r.map_index = whole_int(row.at(0), "a run's map", 0);
  r.map = maps.at(r.map_index).at("name").get<std::string>();
  r.source_index = whole_int(row.at(1), "a run's source", 0);
  r.run = whole_int(row.at(2), "a run's number", 0);
  if (!row.at(3).is_number_unsigned())
    throw InputError("a run's seed is " + row.at(3).dump().substr(0, 40) + ", not a whole number");
  r.seed = row.at(3).get<std::uint64_t>();
  r.error_m = row.at(4).get<double>();
  r.samples = whole_int(row.at(5), "a run's samples", 0);
  r.distance_m = row.at(6).get<double>();
  r.mission_s = row.at(7).get<double>();
  r.stopped_by = row.at(8).get<std::string>();
  r.compute_s = row.at(9).get<double>();
  r.median_step_s = row.at(10).get<double>();
  if (row.size() > 12) {
    r.reached = row.at(11).get<bool>();
    if (!row.at(12).is_null()) r.distance_overhead = row.at(12).get<double>();
  }
  if (row.size() > 17) {  // the time metrics (parts written before them have none)
    const auto number = [](const ordered_json& v) {
      return v.is_null() ? MissionTimes::kNever : v.get<double>();
    };
    r.times.first_detection_s = number(row.at(13));
    r.times.within_1m_s = number(row.at(14));
    r.times.within_0_5m_s = number(row.at(15));
    r.times.declared_s = row.at(16).get<double>();
    r.times.optimum_s = number(row.at(17));
  } else {
    r.times.declared_s = r.mission_s;
  }
  r.times.ended_s = r.mission_s;
  return r;
}

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

// Throws a json exception unless part.json holds every key the merge reads, of its type, and
// InputError for a count outside what evaluate writes.
void check_shape(const ordered_json& j) {
  const ordered_json& s = j.at("settings");
  // The counts as evaluate's options bound them, so that the part's pair range and run count
  // (check_part_coverage) are computed without overflow.
  const auto count = [](const ordered_json& v, const std::string& where, const char* key,
                        long long hi) { whole(v.at(key), where + key, 0, hi); };
  count(s, "settings.", "runs_per_source", 1'000'000);  // evaluation.runs
  count(s, "settings.", "seeds", 1000);                 // evaluation.seeds
  // The summary's label: STE's plume model, or the method.
  if (s.value("method", std::string("ste")) == "ste")
    s.at("plume_model").get<std::string>();
  else
    s.at("method").get<std::string>();
  j.at("options").items();
  // (map, source) pairs: total * K stays within 63 bits for any K < N (an int).
  for (const char* key : {"first", "end", "total"})
    count(j.at("pairs"), "pairs.", key, 1LL << 31);
  whole_int(j.at("threads"), "threads");
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

}  // namespace

std::string part_body_sha256(ordered_json j) {
  j.erase("sha256");
  return sha256_hex(j.dump());
}

EvaluationPart read_evaluation_part(const fs::path& dir) {
  const fs::path file = dir / kPartFile;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError(dir.string() + ": holds no " + kPartFile +
                     "; name the --out folders of `plumekit evaluate --shard K/N`");
  EvaluationPart p;
  p.dir = dir;
  try {
    p.j = ordered_json::parse(read_file(file));
    if (p.j.at("format").get<std::string>() != kPartFormat)
      throw InputError(file.string() + ": \"format\" is not " + kPartFormat);
    if (p.j.at("sha256").get<std::string>() != part_body_sha256(p.j))
      throw InputError(file.string() +
                       ": does not match its own checksum (damaged or edited); "
                       "rerun that part");
    check_shape(p.j);
    p.k = whole_int(p.j.at("part"), "part");
    p.n = whole_int(p.j.at("parts"), "parts");
    if (p.n < 1 || p.k < 0 || p.k >= p.n)
      throw InputError(file.string() + ": part " + std::to_string(p.k) + " of " +
                       std::to_string(p.n) + " is no part");
    for (const auto& row : p.j.at("runs"))
      p.runs.push_back(parse_run_row(row, p.j.at("maps")));
    p.runs_csv = read_csv(dir, "runs.csv", p.j.at("files"), p.runs.size());
    p.timings_csv = read_csv(dir, "timings.csv", p.j.at("files"), p.runs.size());
    const std::string tracks = read_file(dir / kTracksFile);
    if (sha256_hex(tracks) != p.j.at("files").at(kTracksFile).get<std::string>())
      throw InputError((dir / kTracksFile).string() + ": does not match its checksum in " +
                       file.string() + "; rerun that part");
    p.tracks = parse_tracks(tracks, dir / kTracksFile, p.runs.size());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": not a well-formed evaluate part (" + e.what() + ")");
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind(dir.string(), 0) == 0) throw;  // names its file already
    throw InputError(file.string() + ": " + what);
  }
  return p;
}

void check_same_evaluation(const EvaluationPart& first, const EvaluationPart& p) {
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

void check_part_coverage(const std::vector<EvaluationPart>& parts) {
  const int n = parts.front().n;
  std::map<int, const EvaluationPart*> by_k;
  for (const EvaluationPart& p : parts) {
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
  for (const EvaluationPart& p : parts) {
    const ordered_json& pairs = p.j.at("pairs");
    const long long total = pairs.at("total").get<long long>();
    const long long first = total * p.k / n, end = total * (p.k + 1) / n;
    if (pairs.at("first").get<long long>() != first || pairs.at("end").get<long long>() != end ||
        static_cast<long long>(p.runs.size()) != (end - first) * per_pair)
      throw InputError((p.dir / kPartFile).string() + ": its runs are not those of part " +
                       std::to_string(p.k) + " of " + std::to_string(n));
  }
}

}  // namespace plumekit::run
