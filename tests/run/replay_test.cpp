// A run's replay (run/replay.hpp, run/replay_recorder.hpp): recording changes nothing of the run;
// each frame's plume is the world's, computed again here from the run's seed; the robots stand
// where the run's stops say; the file reads back what was written and refuses what was not.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.hpp"
#include "map/map_json.hpp"
#include "run/replay.hpp"
#include "run/replay_recorder.hpp"
#include "run/scenario.hpp"
#include "support/replay_refusal.hpp"
#include "world/filament_model.hpp"

namespace plumekit::run {
namespace {

namespace fs = std::filesystem;

Map block_map() {
  return read_map(fs::path(PLUMEKIT_DATA_DIR) / "test-maps" / "test-1-block.json");
}

// Physics STE in the faithful world with a short spin-up, the moving protocol (readings on the
// way), a small budget: a run of a few seconds.
SteOptions quick_options(int robots = 1) {
  SteOptions o;
  o.model = PlumeModelKind::Physics;
  set_protocol(o, SamplingProtocol::Moving);
  o.world.filament.min_spinup = 5.0;
  o.world.filament.max_spinup = 20.0;
  o.stop.max_samples = 12;
  o.team.robots = robots;
  return o;
}

const Vec2 kSource{7.0, 1.5};
const Vec2 kStart{1.0, 2.5};

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("plumekit-replay-test-" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

void expect_same_run(const LocalizationResult& a, const LocalizationResult& b) {
  ASSERT_EQ(a.steps.size(), b.steps.size());
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    EXPECT_EQ(a.steps[k].position, b.steps[k].position) << k;
    EXPECT_EQ(a.steps[k].value, b.steps[k].value) << k;
    EXPECT_EQ(a.steps[k].time_s, b.steps[k].time_s) << k;
    EXPECT_EQ(a.steps[k].on_the_way.size(), b.steps[k].on_the_way.size()) << k;
  }
  EXPECT_EQ(a.estimate, b.estimate);
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_EQ(a.stopped_by, b.stopped_by);
}

TEST(Replay, RecordingChangesNothingOfTheRun) {
  for (int robots : {1, 2}) {
    const Scenario sc(block_map(), quick_options(robots));
    const LocalizationResult plain = sc.run(kSource, kStart, 11);
    ReplayRecorder recorder(sc.map(), robots, 1.0, sc.options().world.filament.dt);
    const LocalizationResult watched = sc.run(kSource, kStart, 11, &recorder);
    expect_same_run(plain, watched);
    if (robots > 1) {
      ASSERT_EQ(plain.team.size(), watched.team.size());
      for (std::size_t k = 0; k < plain.team.size(); ++k)
        EXPECT_EQ(plain.team[k].steps.size(), watched.team[k].steps.size());
    }
  }
}

TEST(Replay, FramesAreTheWorldsPlumeAndTheRobotsStandWhereTheirStopsWere) {
  const SteOptions o = quick_options();
  const Scenario sc(block_map(), o);
  const double dt = o.world.filament.dt;
  ReplayRecorder recorder(sc.map(), 1, 1.0, dt);
  const LocalizationResult r = sc.run(kSource, kStart, 5, &recorder);
  const Replay replay = recorder.finish(r, kSource, "test");
  // A frame a second from the start to the mission's end.
  EXPECT_EQ(replay.frames(), static_cast<int>(std::floor(r.time_s + 1e-9)) + 1);
  EXPECT_EQ(replay.positions.front().front(), kStart);
  // During each stop the robot stands at it.
  for (const ReplayStop& s : replay.stops)
    for (int f = 0; f < replay.frames(); ++f) {
      if (replay.time_of(f) >= s.arrived_s + 1e-6 && replay.time_of(f) <= s.time_s - 1e-6) {
        EXPECT_NEAR(norm(replay.positions[f][0] - s.position), 0.0, 1e-9) << "frame " << f;
      }
    }
  // Every stop and reading of the run, in time order.
  EXPECT_EQ(replay.stops.size(), r.steps.size());
  std::size_t readings = 0;
  for (const Step& s : r.steps)
    readings += s.on_the_way.size();
  EXPECT_EQ(replay.readings.size(), readings);
  EXPECT_GT(readings, 0u);
  // Frame k's plume is the world's after k seconds: the same plume stepped again here.
  world::FilamentSimulation sim(sc.map(), sc.wind(), kSource, o.world.filament, 5);
  world::spin_up(sim, o.world.filament);
  const long long every = std::llround(1.0 / dt);
  const GridShape& g = replay.plume_grid;
  int compared = 0, with_gas = 0;
  for (int f = 0; f < replay.frames(); ++f) {
    if (f > 0)
      for (long long s = 0; s < every; ++s)
        sim.step();
    if (f % 7 != 0) continue;  // a few frames suffice
    std::vector<double> c(g.size(), 0.0);
    sim.concentration(g, c);
    for (std::size_t k = 0; k < g.size(); ++k) {
      ASSERT_EQ(replay.plume[f * g.size() + k], replay.plume_level(c[k])) << f << " " << k;
      with_gas += replay.plume[f * g.size() + k] > 0;
    }
    ++compared;
  }
  EXPECT_GE(compared, 2);
  EXPECT_GT(with_gas, 100);
  // A belief per decision, the last one the run's posterior.
  ASSERT_EQ(replay.beliefs.size(), r.steps.size());
  const std::vector<double>& last = r.posterior.marginal.values;
  const std::size_t peak = std::max_element(last.begin(), last.end()) - last.begin();
  const std::size_t cells = replay.belief_grid.size();
  EXPECT_EQ(replay.belief_cells[(replay.beliefs.size() - 1) * cells + peak], 255);
  EXPECT_DOUBLE_EQ(replay.beliefs.back().peak, last[peak]);
}

TEST(Replay, TheLogScaleKeepsTheLevelsOrderAndItsEnds) {
  Replay r;
  r.plume_top = 4000.0;
  EXPECT_EQ(r.plume_level(0.0), 0);
  EXPECT_EQ(r.plume_level(-3.0), 0);
  EXPECT_EQ(r.plume_level(4000.0), 255);
  EXPECT_EQ(r.plume_level(1e9), 255);
  EXPECT_LT(r.plume_level(10.0), r.plume_level(100.0));
  for (int level : {1, 64, 200, 255})
    EXPECT_EQ(r.plume_level(r.plume_concentration(static_cast<std::uint8_t>(level))), level);
}

TEST(Replay, WritesAndReadsBackEveryField) {
  const SteOptions o = quick_options(2);
  Map map = block_map();
  map.format_version = 2;  // a framed map
  map.frame.origin = {3.0,
                      -1.0};  // points are written in the map's frame, read back in the arena's
  const Scenario sc(map, o);
  ReplayRecorder recorder(sc.map(), 2, 1.0, o.world.filament.dt);
  const LocalizationResult r = sc.run(kSource, kStart, 3, &recorder);
  const Replay a = recorder.finish(r, kSource, "a team's replay");
  const fs::path dir = scratch("round-trip");
  write_replay(a, dir);
  const Replay b = read_replay(dir);
  EXPECT_EQ(b.title, a.title);
  EXPECT_EQ(b.method, a.method);
  EXPECT_EQ(b.robots, 2);
  EXPECT_EQ(b.every_s, a.every_s);
  EXPECT_EQ(b.map.width, a.map.width);
  EXPECT_EQ(b.map.obstacles.size(), a.map.obstacles.size());
  EXPECT_NEAR(norm(b.source - a.source), 0.0, 1e-12);
  ASSERT_EQ(b.frames(), a.frames());
  for (int f = 0; f < a.frames(); ++f)
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(norm(b.positions[f][k] - a.positions[f][k]), 0.0, 1e-12);
  EXPECT_EQ(b.plume, a.plume);
  EXPECT_EQ(b.plume_top, a.plume_top);
  EXPECT_EQ(b.belief_cells, a.belief_cells);
  ASSERT_EQ(b.beliefs.size(), a.beliefs.size());
  for (std::size_t k = 0; k < a.beliefs.size(); ++k) {
    EXPECT_EQ(b.beliefs[k].robot, a.beliefs[k].robot);
    EXPECT_EQ(b.beliefs[k].peak, a.beliefs[k].peak);
  }
  ASSERT_EQ(b.stops.size(), a.stops.size());
  for (std::size_t k = 0; k < a.stops.size(); ++k) {
    EXPECT_EQ(b.stops[k].robot, a.stops[k].robot);
    EXPECT_EQ(b.stops[k].value, a.stops[k].value);
    EXPECT_NEAR(norm(b.stops[k].estimate - a.stops[k].estimate), 0.0, 1e-12);
  }
  EXPECT_EQ(b.readings.size(), a.readings.size());
  EXPECT_EQ(b.stopped_by, a.stopped_by);
  EXPECT_EQ(b.ended_s, a.ended_s);
  fs::remove_all(dir);
}

TEST(Replay, RefusesAMissingAlteredOrMalformedReplayNamingTheFileAndField) {
  const SteOptions o = quick_options();
  const Scenario sc(block_map(), o);
  ReplayRecorder recorder(sc.map(), 1, 1.0, o.world.filament.dt);
  const LocalizationResult r = sc.run(kSource, kStart, 3, &recorder);
  const fs::path dir = scratch("refusals");
  write_replay(recorder.finish(r, kSource, "x"), dir);
  const std::string json = read_file(dir / kReplayFile);
  const std::string plume = read_file(dir / kReplayPlumeFile);

  EXPECT_NE(replay_refusal(dir / "none").find("holds no replay.json"), std::string::npos);
  std::string flipped = plume;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  write_file_atomic(dir / kReplayPlumeFile, flipped);
  EXPECT_NE(replay_refusal(dir).find("replay-plume.png: does not match the SHA-256"),
            std::string::npos)
      << replay_refusal(dir);
  write_file_atomic(dir / kReplayPlumeFile, plume);
  auto with = [&](const std::string& from, const std::string& to) {
    return replay_refusal_with(dir, json, from, to);
  };
  EXPECT_NE(with("plumekit-replay/1", "plumekit-replay/9").find("format"), std::string::npos);
  EXPECT_NE(with("\"every_s\":", "\"every_z\":").find("every_s is missing"), std::string::npos);
  EXPECT_NE(with("\"robots\": 1", "\"robots\": \"one\"").find("robots is not a number"),
            std::string::npos);
  EXPECT_NE(with("{", "[").find("is not JSON"), std::string::npos);
  write_file_atomic(dir / kReplayFile, json);
  EXPECT_EQ(replay_refusal(dir), "(accepted)");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::run
