#include "run/localize_job.hpp"

#include <chrono>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/animation.hpp"
#include "core/atomic_file.hpp"
#include "core/output_target.hpp"
#include "map/map_json.hpp"
#include "run/replay_render.hpp"
#include "run/report.hpp"
#include "world/random_streams.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

LocalizeRun localize_once(const Scenario& sc, Vec2 source, const std::optional<Vec2>& start,
                          std::uint64_t seed, ReplayRecorder* recorder) {
  LocalizeRun r;
  r.source = sc.check_source(source);
  const std::uint64_t run = world::run_seed(seed, 0, 0, 0);
  r.start = start ? sc.check_start(*start)
                  : sc.random_start(r.source, world::stream_seed(run, world::SteStream::Start));
  r.result = sc.run(r.source, r.start, run, recorder);
  return r;
}

std::string replay_title(const Scenario& sc, Vec2 source, std::uint64_t seed) {
  const SteOptions& o = sc.options();
  const Vec2 s = sc.map().to_frame(source);
  std::ostringstream t;
  t << std::fixed << std::setprecision(2) << (sc.map().name.empty() ? "map" : sc.map().name) << ": "
    << o.method.name;
  if (o.method.name == "ste" || o.method.name == "ste-local")
    t << " (" << to_string(o.model) << ")";
  if (o.team.robots > 1) t << ", " << o.team.robots << " robots";
  t << ", source (" << s.x << ", " << s.y << "), seed " << seed;
  return t.str();
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// run.json into the open output `out`, committed, and where the files went in the report.
void write_run_files(OutputDirectory& out, const fs::path& o, bool posterior, Report& rep) {
  write_file_atomic(out.open() / "run.json", rep.json.dump(2) + "\n");
  out.commit();
  rep.json["out"] = {{"run", (o / "run.json").string()},
                     {"trajectory", (o / "trajectory.png").string()}};
  rep.text += "\nwrote " + (o / "trajectory.png").string() + ", ";
  if (posterior) {
    rep.json["out"]["posterior"] = (o / "posterior.png").string();
    rep.text += (o / "posterior.png").string() + ", ";
  }
  rep.text += (o / "run.json").string();
}

}  // namespace

LocalizeReport localize_job(const LocalizeRequest& q) {
  const auto t_start = std::chrono::steady_clock::now();  // the summary accounts for all of it
  q.ste.validate();
  const Map map = read_map(q.map);
  std::optional<Vec2> requested;
  if (q.start) requested = map.from_frame(*q.start);
  std::optional<OutputDirectory> out;
  if (!q.out.empty())
    out.emplace(q.out, "localize", std::vector<fs::path>{q.map, q.ste.table_cache, q.ste.wind_dir});
  if (!q.animate.empty()) check_animation_target(q.animate, "--animate");
  // One run, one plume: its steps on every core (the plume does not depend on the count).
  SteOptions options = q.ste;
  options.world.filament.threads = 0;
  const Scenario sc(map, options);
  const std::unique_ptr<ReplayRecorder> recorder =
      q.animate.empty() ? nullptr : replay_recorder_for(sc);
  const LocalizeRun r =
      localize_once(sc, map.from_frame(q.source), requested, q.seed, recorder.get());
  // The pictures first, so that the time they take is in the summary's total.
  RunPictures pictures;
  if (out) pictures = write_run_pictures(sc, r.source, r.result, out->open());
  std::optional<AnimationWriter::Written> animation;
  if (recorder) {
    const Replay replay = recorder->finish(r.result, r.source, replay_title(sc, r.source, q.seed));
    if (out) write_replay(replay, out->open());
    AnimateOptions a;
    a.progress = q.progress;
    animation = animate_replay(replay, q.animate, "--animate", a);
  }
  Report rep = run_report(sc, r.source, r.result, seconds_since(t_start));
  ordered_json j{{"ok", true},
                 {"map", provenance_path(q.map)},
                 {"plume_model", to_string(q.ste.model)},
                 {"seed", q.seed}};
  sampling_json(q.ste, j);
  if (q.ste.uses_cnn())
    j["cnn"] = provenance_path(q.ste.model_path);  // which network, for a result to be remade
  j.update(rep.json);
  rep.json = j;
  if (out) write_run_files(*out, q.out, !pictures.posterior.empty(), rep);
  if (animation) report_animation(*animation, rep.json, rep.text);
  LocalizeReport result{rep, std::nullopt, map.to_frame(r.start)};
  if (requested) {
    result.requested_start = map.to_frame(*requested);
    result.start_moved = requested->x != r.start.x || requested->y != r.start.y;
  }
  return result;
}

}  // namespace plumekit::run
