#pragma once
// A run's replay (docs/replay.md): what its robots did, read and believed, and the plume they
// were in, recorded once while the run goes (run/replay_recorder.hpp), so that it can be drawn
// (run/replay_render.hpp) and drawn again later without running the mission again
// (`plumekit replay RUN_DIR`).
//
// Times are simulated seconds since the robots started. Frame k shows the world at k * every_s:
// every robot's true position and the plume's concentration on a grid. The belief is recorded
// after each decision: STE's posterior marginal, the particle filter's particles binned, or none
// (a plume tracker holds no belief).
//
// On disk, three files of a run's folder: replay.json (everything but the grids), replay-plume.png
// and replay-belief.png, 8-bit grey film strips of the grids (frame after frame, top to bottom;
// each frame's first image row is the arena's top), whose SHA-256 replay.json records.
//
// A run in the 3-D tunnel (run/tunnel_replay.hpp) is seen from above and from the side: its map
// is the tunnel from above, its plume and belief the views from above, and `side` adds the view
// from the side, every point's height and two more strips.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::run {

inline constexpr const char* kReplayFormat = "plumekit-replay/1";
inline constexpr const char* kReplayFile = "replay.json";
inline constexpr const char* kReplayPlumeFile = "replay-plume.png";
inline constexpr const char* kReplayBeliefFile = "replay-belief.png";
inline constexpr const char* kReplayPlumeSideFile = "replay-plume-side.png";
inline constexpr const char* kReplayBeliefSideFile = "replay-belief-side.png";

// A stop: where the robot sampled, from when to when, what it read and what it believed after.
struct ReplayStop {
  int robot = 0;
  Vec2 position;
  double arrived_s = 0.0, time_s = 0.0;
  double value = 0.0;
  Vec2 estimate;  // the method's estimate after the stop (where it stood, for a tracker)
  double z = 0.0, estimate_z = 0.0;  // in the tunnel: the heights of position and estimate
};

// A reading taken on the way between stops.
struct ReplayReading {
  int robot = 0;
  Vec2 position;
  double time_s = 0.0, value = 0.0;
  double z = 0.0;  // in the tunnel: the height of position
};

// The belief after a decision: its cells in Replay::belief_cells, scaled to `peak`.
struct ReplayBelief {
  int robot = 0;
  double time_s = 0.0;
  double peak = 0.0;  // the largest cell's value (a probability per cell)
};

// The tunnel from the side: the gas in the vertical plane through the source (y = plane_y), the
// belief's (x, z) marginal, and the heights the view from above leaves out.
struct ReplaySide {
  double height = 0.0;                  // the tunnel's, m: the view's vertical extent
  double plane_y = 0.0, plane_z = 0.0;  // this view's plane, and the view from above's (z)
  GridShape plume_grid;                 // x along the tunnel, y up (z)
  std::vector<std::uint8_t> plume;      // per frame, on the replay's log levels
  GridShape belief_grid;
  std::vector<double> belief_peaks;  // per belief (Replay::beliefs)
  std::vector<std::uint8_t> belief_cells;
  std::vector<std::vector<double>> z;  // per frame, each robot's height
  double source_z = 0.0, estimate_z = 0.0;
};

struct Replay {
  std::string title;  // the run in words: map, method, source, seed
  Map map;
  Vec2 source;
  std::string method;
  int robots = 1;
  double every_s = 1.0;
  // Per frame, each robot's true position.
  std::vector<std::vector<Vec2>> positions;
  // Per frame, the plume's concentration on plume_grid, quantized on a log scale (plume_level).
  GridShape plume_grid;
  double plume_top = 1.0;  // the concentration of level 255 (higher values are clipped to it)
  std::vector<std::uint8_t> plume;
  std::vector<ReplayStop> stops;
  std::vector<ReplayReading> readings;
  // Per decision, the belief on belief_grid, linear from 0 to its peak (level 255).
  GridShape belief_grid;
  std::vector<ReplayBelief> beliefs;
  std::vector<std::uint8_t> belief_cells;
  // Whether the method holds an estimate of the source (a plume tracker does not: a stop's
  // `estimate` is then where the robot stood).
  bool has_estimate = true;
  // How it ended: the declared estimate, when (declared_s) and why, the drive to it after (empty
  // without one) and when the mission ended.
  Vec2 estimate;
  double declared_s = 0.0, ended_s = 0.0;
  std::string stopped_by;
  std::vector<Vec2> approach;
  std::optional<ReplaySide> side;  // a tunnel run's

  int frames() const { return static_cast<int>(positions.size()); }
  double time_of(int frame) const { return frame * every_s; }
  // The plume concentration a level stands for, and back (levels 0 .. 255, c in [0, plume_top]).
  double plume_concentration(std::uint8_t level) const;
  std::uint8_t plume_level(double concentration) const;
};

// The scale of the replay's log levels, concentration units: a concentration c is level
// 255 log(1 + c / floor) / log(1 + top / floor), so that gas a tenth of the trackers' detection
// threshold (50) shows faintly and the plume's core keeps its shades.
inline constexpr double kReplayPlumeFloor = 5.0;

// Writes the replay's three files into `dir` (a folder being written; see localize_job.cpp) and
// reads each back to check it; returns replay.json's text.
std::string write_replay(const Replay& replay, const std::filesystem::path& dir);
// Reads a run folder's replay; InputError naming the file and field when anything is missing,
// malformed or does not match its recorded SHA-256.
Replay read_replay(const std::filesystem::path& dir);

}  // namespace plumekit::run
