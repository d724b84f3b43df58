#include "dataset/reports.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace plumekit::dataset {

Report plume_report(const PlumeRun& run, const PlumeTargets& t) {
  const double peak = *std::max_element(t.mean.values.begin(), t.mean.values.end());
  Report r;
  r.json = {{"ok", true},
            {"map", run.map},
            {"source", {run.source.x, run.source.y}},
            {"model", to_string(run.model)},
            {"out", run.out},
            {"peak_mean", peak},
            {"flow_s", run.flow_s},
            {"plume_s", run.plume_s}};
  if (run.model == PlumeSimulator::Filament)
    r.json["filament"] = {{"spinup_s", t.filament.spinup_s},
                          {"steady", t.filament.steady},
                          {"filaments_at_end", t.filament.filaments_at_end},
                          {"released", t.filament.released},
                          {"left_through_outlet", t.filament.left_through_outlet},
                          {"dropped_too_wide", t.filament.dropped_too_wide},
                          {"rejected_moves", t.filament.rejected_moves}};
  std::ostringstream text;
  text.precision(3);
  text << "wrote " << run.out << "/{mean,std}.npy, plume.png: " << to_string(run.model)
       << " plume, peak mean " << peak << "; flow " << run.flow_s << " s, plume " << run.plume_s
       << " s";
  r.text = text.str();
  return r;
}

Report generate_report(const std::string& out, PlumeSimulator model, const DatasetSummary& s) {
  Report r;
  r.json = {{"ok", true},
            {"out", out},
            {"model", to_string(model)},
            {"maps", s.maps},
            {"maps_resumed", s.maps_resumed},
            {"winds_cached", s.winds_cached},
            {"samples_computed", s.samples},
            {"seconds", s.seconds},
            {"flow_s", s.flow_s},
            {"plume_s", s.plume_s},
            {"samples_per_second", s.samples_per_second()},
            {"threads", s.threads}};
  std::ostringstream text;
  text.precision(3);
  text << "wrote " << out << ": " << s.maps << " maps (" << s.maps_resumed << " already complete), "
       << s.samples << " samples computed in " << s.seconds << " s (" << s.samples_per_second()
       << " samples/s; flow " << s.flow_s << " s, plumes " << s.plume_s
       << " s, summed over threads)";
  r.text = text.str();
  return r;
}

Report merge_report(const std::string& out, const MergeSummary& s) {
  Report r;
  r.json = {
      {"ok", true}, {"out", out}, {"parts", s.parts}, {"shards", s.shards}, {"samples", s.samples}};
  std::ostringstream text;
  text << "merged " << s.parts << " parts into " << out << ": " << s.shards << " shards, "
       << s.samples << " samples, all checksums verified";
  r.text = text.str();
  return r;
}

Report show_report(const std::string& out, const DatasetSample& s) {
  Report r;
  r.json = {{"ok", true},
            {"out", out},
            {"index", s.index},
            {"shard", s.shard.name},
            {"row", s.row},
            {"map", s.shard.map},
            {"map_index", s.shard.map_index},
            {"source", {s.source.x, s.source.y}},
            {"inputs_sha256", s.inputs_sha256},
            {"targets_sha256", s.targets_sha256}};
  std::ostringstream text;
  text << "wrote " << out << ": sample " << s.index << " (" << s.shard.name << ", source "
       << to_string(s.source) << ")";
  r.text = text.str();
  return r;
}

std::string format_duration(double s) {
  char buf[32];
  const long t = std::lround(std::max(0.0, s));
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

std::string ProgressNote::operator()(long long done, long long total) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (first_ < 0) first_ = done;
  const double rate = elapsed > 0.0 ? (done - first_) / elapsed : 0.0;
  std::ostringstream note;
  note << done << "/" << total << " samples, elapsed " << format_duration(elapsed) << ", ETA "
       << (rate > 0.0 ? format_duration((total - done) / rate) : std::string("--:--:--"));
  return note.str();
}

}  // namespace plumekit::dataset
