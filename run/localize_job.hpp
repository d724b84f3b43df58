#pragma once
// `plumekit localize` as one call (apps/ parses its flags into a LocalizeRequest and prints the
// Report; the Python module's Scenario.run and localize share localize_once): the map read, the
// scenario built, the source and start checked or the start drawn, the run, and with an output
// folder its pictures and run.json.
#include <cstdint>
#include <filesystem>
#include <optional>

#include "core/geometry.hpp"
#include "core/report.hpp"
#include "core/seed.hpp"
#include "run/replay_recorder.hpp"
#include "run/scenario.hpp"

namespace plumekit::run {

// One run on a built scenario, points in arena coordinates: the source checked (OptionError on
// ste.source), the start checked and moved off the planner's margin, or drawn at random from the
// run's start stream when not given. The seed is the command's: run 0 of world::run_seed.
struct LocalizeRun {
  Vec2 source, start;
  LocalizationResult result;
};
LocalizeRun localize_once(const Scenario& scenario, Vec2 source, const std::optional<Vec2>& start,
                          std::uint64_t seed, ReplayRecorder* recorder = nullptr);

// The replay's title for a run of `scenario`: the map, the method (and its plume model), the
// source in the map's frame and the seed.
std::string replay_title(const Scenario& scenario, Vec2 source, std::uint64_t seed);

struct LocalizeRequest {
  std::filesystem::path map;
  Vec2 source;                // in the map's frame (its file's coordinates)
  std::optional<Vec2> start;  // in the map's frame; none: a random free start
  std::uint64_t seed = kDefaultSeed;
  SteOptions ste;
  std::filesystem::path out;  // empty: no files; else run.json, trajectory.png, posterior.png
  // A replay of the mission as a video (.mp4) or animated PNG (.png); empty: none. With `out`,
  // the run's replay files go there too (run/replay.hpp), for `plumekit replay`.
  std::filesystem::path animate;
  bool progress = false;  // a progress bar while the replay is drawn
};

// What `localize` reports: the summary (JSON and text; "out" and the "wrote" line when it wrote
// files), and the start asked for and the one used, in the map's frame, for the caller to say
// when the start was moved off an obstacle (`start_moved`).
struct LocalizeReport {
  Report report;
  std::optional<Vec2> requested_start;
  Vec2 start;
  bool start_moved = false;  // compared in arena coordinates, where the move was made
};
LocalizeReport localize_job(const LocalizeRequest& request);

}  // namespace plumekit::run
