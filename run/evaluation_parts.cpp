#include "run/evaluation_parts.hpp"

#include <algorithm>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"
#include "run/run_tracks.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

// One run's figures at full precision (JSON numbers round-trip a double exactly): what the
// summary's statistics, the box plots and timings.json are computed from.
ordered_json run_row(const RunRecord& r) {
  // null: no overhead, or never got there. The time metrics after the trackers' two criteria,
  // so that every earlier field keeps its place.
  const MissionTimes& t = r.times;
  return ordered_json::array(
      {r.map_index, r.source_index, r.run, r.seed, r.error_m, r.samples, r.distance_m, r.mission_s,
       r.stopped_by, r.compute_s, r.median_step_s, r.reached, finite_or_null(r.distance_overhead),
       finite_or_null(t.first_detection_s), finite_or_null(t.within_1m_s),
       finite_or_null(t.within_0_5m_s), t.declared_s, finite_or_null(t.optimum_s)});
}

// The runs of all parts in run order, each map's statistics and times, and the files.
MergedEvaluation join(const std::vector<EvaluationPart>& parts) {
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
  for (const EvaluationPart& p : parts) {
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
  std::vector<ordered_json> tracks;
  for (const EvaluationPart& p : parts)
    tracks.push_back(p.tracks);
  m.files.tracks = join_tracks(tracks);
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
       {{"runs.csv", sha256_hex(files.runs_csv)},
        {"timings.csv", sha256_hex(files.timings_csv)},
        {kTracksFile, sha256_hex(files.tracks.dump() + "\n")}}},
      {"threads", res.threads},
      {"wall_s", res.wall_s},
      {"map_times", times},
      {"runs", runs}};
  j["sha256"] = part_body_sha256(j);
  return j;
}

MergedEvaluation merge_evaluation_parts(const std::vector<fs::path>& dirs) {
  if (dirs.empty()) throw InputError("evaluate merge: name the part folders");
  std::vector<EvaluationPart> parts;
  for (const fs::path& dir : dirs)
    parts.push_back(read_evaluation_part(dir));
  for (const EvaluationPart& p : parts)
    check_same_evaluation(parts.front(), p);
  check_part_coverage(parts);
  std::sort(parts.begin(), parts.end(),
            [](const EvaluationPart& a, const EvaluationPart& b) { return a.k < b.k; });
  for (const EvaluationPart& p : parts)
    if (p.runs_csv.header != parts.front().runs_csv.header ||
        p.timings_csv.header != parts.front().timings_csv.header)
      throw InputError((p.dir / "runs.csv").string() + ": its header differs from " +
                       (parts.front().dir / "runs.csv").string() + "'s");
  MergedEvaluation m = join(parts);
  m.settings = parts.front().j.at("settings");
  m.files.summary = evaluation_report(m.result, m.settings, {}).json;
  return m;
}

}  // namespace plumekit::run
