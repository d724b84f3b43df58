#pragma once
// Runs in seed 004's 3-D wind tunnel (tunnel_world.hpp): its 3-D STE (ch. 11, ste_3d.hpp), its
// 3-D surge-spiral and the 2-D surge-cast baseline flown at a fixed altitude (ch. 17,
// methods/crosswind_search.hpp), each from a start to an end, scored against the true source;
// and an evaluation of many such runs. `plumekit localize tunnel` and `plumekit evaluate tunnel`
// (apps/cmd_tunnel.cpp).
//
// STE stops to sample (5 s), decides and flies straight to its goal at the world's speed, until
// its entropy falls below 2 % of the maximum (it declares its expected source) or its budget is
// spent. A tracker flies at `tracker_speed` (ch. 17: 50 mm/s) and decides every `decision_s`
// on the mean reading of the last interval; it succeeds when it is inside the box of side `box`
// (20 cm) about the source while in the plume (ch. 17's identification), and fails after
// `time_limit_s` (12 minutes).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/option_table.hpp"
#include "methods/crosswind_search.hpp"
#include "ste/ste_3d.hpp"
#include "world/simulated_world.hpp"
#include "world/tunnel_plume.hpp"

namespace plumekit::run {

class TunnelReplayRecorder;  // run/tunnel_replay.hpp
struct Replay;               // run/replay.hpp

// The tunnel's methods come from the registry (methods/registry.hpp's tunnel_method_registry):
// `name` checked there, OptionError on tunnel.method otherwise.
std::string parse_tunnel_method(const std::string& name);
// "NAME[,NAME...]" (each once) or "all".
std::vector<std::string> parse_tunnel_methods(const std::string& text);
bool is_tracker(const std::string& method);

struct TunnelOptions {
  std::string method = "ste-3d";  // a tunnel method's registry name
  world::Tunnel tunnel;
  // The world's rules (tunnel_world.hpp); its filament options are the tunnel's
  // (world::tunnel_filament_options()) with release_rate 1000 (condition "10 %").
  world::WorldOptions world = default_world();
  ste::Ste3dOptions ste;
  methods::CrosswindSearchOptions search;
  double tracker_speed = 0.05;  // m/s (ch. 17)
  double decision_s = 1.0;      // s between a tracker's decisions
  double time_limit_s = 720.0;  // ch. 17: 12 minutes
  double box = 0.2;             // m, the side of the trackers' success box
  double margin = 0.1;          // m, goals and starts stay this far inside the walls
  // Random sources: x this far from the upwind wall (ch. 5.1: 1 m), y and z uniform inside the
  // margins; random STE starts anywhere at least min_start_distance from the source; a tracker
  // starts start_downwind (ch. 17: 10 m) downwind of the source (cut to the tunnel) at a random
  // crosswind point.
  double source_x = 1.0;
  double min_start_distance = 1.0;
  double start_downwind = 10.0;
  static world::WorldOptions default_world();
  // OptionError naming the field ("tunnel.box", "tunnel.ste.step", ...).
  void validate() const;
};

// Its options table (core/option_table.hpp): validate()'s fixed ranges (the ones that depend on
// the tunnel's size are checked by hand), the tunnel commands' tracker flags, docs/options.md.
const OptionTable<TunnelOptions>& tunnel_option_table();

struct TunnelStep {
  Vec3 position;        // where the robot read (a stop, or the end of a tracker's interval)
  double gas = 0.0;     // the stop's or interval's mean reading
  double time_s = 0.0;  // since the start, at the reading's end
  double distance_m = 0.0;
  std::string phase;       // STE: "sample"; a tracker: "levy", "surge", "spiral" or "cast"
  Vec3 estimate;           // STE: the expected source after this sample
  double entropy = 0.0;    // STE: of the posterior after this sample, nats
  double compute_s = 0.0;  // STE: estimation and navigation after this sample (thread CPU)
};

struct TunnelRun {
  std::string method = "ste-3d";
  Vec3 source, start;
  std::vector<TunnelStep> steps;
  Vec3 estimate;  // STE: its declared (expected) source; a tracker: where it ended
  // "entropy", "max_samples" (STE); "found", "time_limit" (a tracker).
  std::string stopped_by;
  double distance_m = 0.0, mission_s = 0.0;
  double spinup_s = 0.0;
  double max_entropy = 0.0;  // STE
  double error_m() const { return norm(estimate - source); }
  Vec3 error() const;  // per axis, absolute
  bool found() const { return stopped_by == "found"; }
  // The closest the robot came to the source at a reading (a tracker reads every 5 cm), m.
  double closest_m() const;
  // When the robot first read within `radius` of the source, s since its start; -1: never.
  double time_within(double radius) const;
  double median_step_s() const;  // STE's median compute per sample; 0 for a tracker
};

// A source (x = source_x, y and z random) and a start for `method`, drawn from `seed`.
Vec3 random_tunnel_source(const TunnelOptions& options, std::uint64_t seed);
Vec3 random_tunnel_start(const TunnelOptions& options, Vec3 source, std::uint64_t seed);
// InputError naming `what` ("source", "start") unless p is inside the tunnel's margins.
void check_tunnel_point(const TunnelOptions& options, Vec3 p, const std::string& what);

// One run of options.method from `start` to find `source`; the world, the chain and the tracker
// draw from `seed`.
// `recorder`, when given, records the run's replay (run/tunnel_replay.hpp).
TunnelRun run_tunnel(const TunnelOptions& options, Vec3 source, Vec3 start, std::uint64_t seed,
                     TunnelReplayRecorder* recorder = nullptr);

// Run `run` of a command's `seed` (`localize tunnel` is run 0): its seed run_seed(seed, 0, 0,
// run), and the source and start given, or drawn from it (random_tunnel_source, _start).
// With `replay`, the run's replay is recorded into it (run/tunnel_replay.hpp: the same run,
// slower), titled by tunnel_replay_title with `seed`.
TunnelRun localize_tunnel(const TunnelOptions& options, std::optional<Vec3> source,
                          std::optional<Vec3> start, std::uint64_t seed, std::uint64_t run = 0,
                          std::optional<Replay>* replay = nullptr);

// `runs` runs (localize_tunnel's runs 0 .. runs - 1) from random sources and starts, on
// `threads` threads (0: one per core); progress(done, total) after each run.
// `replayed(k, run, replay)`, when given, receives run k's replay (the same run, recorded as it
// goes: slower) on the run's thread as soon as it ends (`evaluate tunnel --replays`).
using TunnelReplaySink = std::function<void(int, const TunnelRun&, const Replay&)>;
std::vector<TunnelRun> evaluate_tunnel(const TunnelOptions& options, int runs, std::uint64_t seed,
                                       int threads,
                                       const std::function<void(int, int)>& progress = {},
                                       const TunnelReplaySink& replayed = {});

}  // namespace plumekit::run
