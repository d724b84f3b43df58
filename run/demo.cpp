#include "run/demo.hpp"

#include <chrono>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/output_target.hpp"
#include "map/map_json.hpp"
#include "run/report.hpp"
#include "world/random_streams.hpp"

namespace plumekit::run {

std::string choose_demo_model(SteOptions& o) {
  std::error_code ec;
  if (o.model != PlumeModelKind::Surrogate || std::filesystem::is_regular_file(o.model_path, ec))
    return "";
  o.model = PlumeModelKind::Physics;
  return "note: " + o.model_path +
         " is not there yet, so this demo uses the physics plume model; with the trained CNN "
         "it uses the surrogate.";
}

LocalizeReport demo_job(const DemoOptions& d, const std::filesystem::path& maps_dir,
                        const std::filesystem::path& out_dir, const std::string& note) {
  const auto t_start = std::chrono::steady_clock::now();  // the summary accounts for all of it
  d.ste.validate();
  const std::filesystem::path map_file = maps_dir / d.map_file;
  const Map map = read_map(map_file);
  OutputDirectory out(out_dir, "demo", {map_file});
  const Scenario sc(map, d.ste);
  const Vec2 source = map.sources.at(d.source_index);
  const Vec2 requested = map.from_frame(d.start);
  const Vec2 start = sc.check_start(requested);
  const LocalizationResult r = sc.run(source, start, world::run_seed(d.seed, 0, 0, 0));
  const bool posterior = !write_run_pictures(sc, source, r, out.open()).posterior.empty();
  out.commit();
  const std::filesystem::path traj = out_dir / "trajectory.png", post = out_dir / "posterior.png";
  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  Report rep = run_report(sc, source, r, total_s);
  nlohmann::ordered_json j{
      {"ok", true}, {"map", provenance_path(map_file)}, {"plume_model", to_string(d.ste.model)}};
  if (!note.empty()) j["note"] = note;
  j.update(rep.json);
  j["out"] = {{"trajectory", traj.string()}};
  rep.text += "\npictures: " + traj.string() + " (trajectory)";
  if (posterior) {
    j["out"]["posterior"] = post.string();
    rep.text += ", " + post.string() + " (posterior)";
  }
  rep.json = j;
  return {rep, map.to_frame(requested), map.to_frame(start),
          requested.x != start.x || requested.y != start.y};
}

}  // namespace plumekit::run
