// A tunnel run's replay (run/tunnel_replay.hpp): recording changes nothing of the run; the robot
// stands where it read; the views from above and the side read back with every point's height,
// and a replay whose side is altered or malformed is refused naming the file and the field; the
// side view is drawn below the view from above.
#include <gtest/gtest.h>

#include <filesystem>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/atomic_file.hpp"
#include "run/replay_render.hpp"
#include "run/tunnel_replay.hpp"
#include "support/replay_refusal.hpp"

namespace plumekit::run {
namespace {

namespace fs = std::filesystem;

const Vec3 kSource{1.0, 1.5, 0.8};
const Vec3 kStart{6.0, 2.5, 1.4};

TunnelOptions quick_options() {
  TunnelOptions o;
  o.ste.max_samples = 6;
  return o;
}

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("plumekit-tunnel-replay-test-" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

struct Recorded {
  TunnelRun run;
  Replay replay;
};

Recorded recorded(const TunnelOptions& o) {
  TunnelReplayRecorder recorder = tunnel_replay_recorder(o, kSource);
  TunnelRun run = run_tunnel(o, kSource, kStart, 3, &recorder);
  Replay replay = recorder.finish(run, "a tunnel run");
  return {std::move(run), std::move(replay)};
}

TEST(TunnelReplay, RecordingChangesNothingOfTheRun) {
  const TunnelOptions o = quick_options();
  const TunnelRun bare = run_tunnel(o, kSource, kStart, 3);
  const TunnelRun watched = recorded(o).run;
  ASSERT_EQ(bare.steps.size(), watched.steps.size());
  for (std::size_t k = 0; k < bare.steps.size(); ++k) {
    EXPECT_EQ(norm(bare.steps[k].position - watched.steps[k].position), 0.0) << k;
    EXPECT_EQ(bare.steps[k].gas, watched.steps[k].gas) << k;
    EXPECT_EQ(bare.steps[k].time_s, watched.steps[k].time_s) << k;
  }
  EXPECT_EQ(norm(bare.estimate - watched.estimate), 0.0);
  EXPECT_EQ(bare.mission_s, watched.mission_s);
}

TEST(TunnelReplay, TheRobotStandsWhereItReadAndEveryDecisionHasItsBelief) {
  const Recorded r = recorded(quick_options());
  const Replay& p = r.replay;
  ASSERT_TRUE(p.side);
  // A frame a second from the start to the end of the mission.
  EXPECT_EQ(p.frames(), static_cast<int>(r.run.mission_s + 1e-9) + 1);
  ASSERT_EQ(p.side->z.size(), static_cast<std::size_t>(p.frames()));
  ASSERT_EQ(p.stops.size(), r.run.steps.size());
  int checked = 0;
  for (const ReplayStop& s : p.stops) {
    // A frame inside the stop's sampling shows the robot at the stop, in 3-D.
    const int f = static_cast<int>(std::ceil(s.arrived_s + 1e-9));
    if (f > s.time_s - 1e-9 || f >= p.frames()) continue;
    EXPECT_NEAR(norm(p.positions[f][0] - s.position), 0.0, 1e-9) << f;
    EXPECT_NEAR(p.side->z[f][0], s.z, 1e-9) << f;
    ++checked;
  }
  EXPECT_GE(checked, 5);
  EXPECT_EQ(p.positions[0][0], (Vec2{kStart.x, kStart.y}));
  EXPECT_EQ(p.side->z[0][0], kStart.z);
  EXPECT_EQ(p.beliefs.size(), r.run.steps.size());
  EXPECT_EQ(p.side->belief_peaks.size(), p.beliefs.size());
  EXPECT_EQ(p.side->plume.size(), p.side->plume_grid.size() * p.frames());
  EXPECT_EQ(p.plume.size(), p.plume_grid.size() * p.frames());
  // The plane through the source holds its gas: the last frame's densest cell is near it.
  const std::size_t cells = p.plume_grid.size(), last = (p.frames() - 1) * cells;
  const auto top = std::max_element(p.plume.begin() + last, p.plume.begin() + last + cells);
  const int at = static_cast<int>(top - (p.plume.begin() + last));
  const Vec2 densest = p.plume_grid.centre(at % p.plume_grid.nx, at / p.plume_grid.nx);
  EXPECT_LT(norm(densest - Vec2{kSource.x, kSource.y}), 1.0);
}

TEST(TunnelReplay, WritesAndReadsBackEveryHeight) {
  const Replay a = recorded(quick_options()).replay;
  const fs::path dir = scratch("round-trip");
  write_replay(a, dir);
  const Replay b = read_replay(dir);
  ASSERT_TRUE(b.side);
  EXPECT_EQ(b.side->height, a.side->height);
  EXPECT_EQ(b.side->plane_y, kSource.y);
  EXPECT_EQ(b.side->plane_z, kSource.z);
  EXPECT_EQ(b.side->source_z, kSource.z);
  EXPECT_EQ(b.side->estimate_z, a.side->estimate_z);
  EXPECT_EQ(b.side->z, a.side->z);
  EXPECT_EQ(b.side->plume, a.side->plume);
  EXPECT_EQ(b.side->belief_cells, a.side->belief_cells);
  EXPECT_EQ(b.side->belief_peaks, a.side->belief_peaks);
  EXPECT_EQ(b.plume, a.plume);
  ASSERT_EQ(b.stops.size(), a.stops.size());
  for (std::size_t k = 0; k < a.stops.size(); ++k) {
    EXPECT_EQ(b.stops[k].z, a.stops[k].z);
    EXPECT_EQ(b.stops[k].estimate_z, a.stops[k].estimate_z);
  }
  EXPECT_EQ(b.map.width, 10.0);
  EXPECT_EQ(b.map.height, 4.0);
  fs::remove_all(dir);
}

TEST(TunnelReplay, RefusesAnAlteredOrMalformedSideNamingTheFileAndField) {
  const fs::path dir = scratch("refusals");
  write_replay(recorded(quick_options()).replay, dir);
  const std::string json = read_file(dir / kReplayFile);
  const std::string side = read_file(dir / kReplayPlumeSideFile);
  std::string flipped = side;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  write_file_atomic(dir / kReplayPlumeSideFile, flipped);
  EXPECT_NE(replay_refusal(dir).find("replay-plume-side.png: does not match the SHA-256"),
            std::string::npos)
      << replay_refusal(dir);
  write_file_atomic(dir / kReplayPlumeSideFile, side);
  auto with = [&](const std::string& from, const std::string& to) {
    return replay_refusal_with(dir, json, from, to);
  };
  EXPECT_NE(with("\"peaks\": [", "\"peaks\": [1, ").find("side.belief.peaks"), std::string::npos);
  EXPECT_NE(with("\"plane_y\":", "\"plane_x\":").find("side.plane_y is missing"),
            std::string::npos);
  // Without its side, a tunnel replay's points have a coordinate too many.
  EXPECT_NE(with("\"side\":", "\"aside\":").find("is not a point [x, y]"), std::string::npos);
  write_file_atomic(dir / kReplayFile, json);
  EXPECT_EQ(replay_refusal(dir), "(accepted)");
  fs::remove_all(dir);
}

TEST(TunnelReplay, TheSideViewIsDrawnBelowTheViewFromAbove) {
  Replay r = recorded(quick_options()).replay;
  const int k = r.frames() - 1;
  const cv::Mat with_gas = ReplayPainter(r).frame(k);
  std::fill(r.side->plume.begin(), r.side->plume.end(), 0);
  const cv::Mat without = ReplayPainter(r).frame(k);
  cv::Mat diff;
  cv::absdiff(with_gas, without, diff);
  cv::Mat grey;
  cv::extractChannel(diff, grey, 0);
  const cv::Rect changed = cv::boundingRect(grey > 0);
  // Only the side view changed: in the left (the world's) column, below its top third.
  EXPECT_GT(changed.area(), 10000);
  EXPECT_LE(changed.br().x, with_gas.cols / 2);
  EXPECT_GE(changed.y, with_gas.rows / 3);
}

}  // namespace
}  // namespace plumekit::run
