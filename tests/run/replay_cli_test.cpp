// `localize --animate` and `plumekit replay` from the command line: a run's video and its replay
// files, drawn again later to the same frames, the animated PNG when no encoder is there, and the
// refusals (exit 2, nothing written).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"
#include "support/small_map.hpp"

namespace plumekit::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

class ReplayCli : public CliTest {
 protected:
  // A short physics run on the small map, with its replay.
  CliResult localize(const std::string& extra) {
    return run("localize " + write_small_map(dir) +
               " --source 4.5,0.5 --start 1,2.5 --plume-model physics --max-samples 8 --seed 3 " +
               extra);
  }
};

TEST_F(ReplayCli, ARunsVideoAndItsReplayDrawnAgain) {
  const fs::path out = dir / "run", video = dir / "run.mp4";
  CliResult r = localize("--out " + out.string() + " --animate " + video.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_TRUE(j.contains("animation")) << r.out;
  EXPECT_EQ(j["animation"]["format"], "mp4");
  const int frames = j["animation"]["frames"].get<int>();
  // A frame a second, from the start to the end of the mission.
  EXPECT_EQ(frames, static_cast<int>(j["mission_s"].get<double>() + 1e-9) + 1);
  EXPECT_TRUE(fs::exists(video));
  for (const char* f : {"replay.json", "replay-plume.png", "replay-belief.png", "run.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;

  // Drawn again from the files, as a video and as an animated PNG, with the same frames.
  r = run("replay " + out.string() + " --out " + (dir / "again.mp4").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["frames"].get<int>(), frames);
  r = run("replay " + out.string() + " --out " + (dir / "again.png").string() +
          " --size 640x360 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json again = json::parse(r.out);
  EXPECT_EQ(again["format"], "apng");
  EXPECT_EQ(again["frames"].get<int>(), frames);
  EXPECT_EQ(again["width"].get<int>(), 640);
  // Its own earlier output may be replaced.
  r = run("replay " + out.string() + " --out " + (dir / "again.png").string() + " --json");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(ReplayCli, WithoutAnEncoderAVideoBecomesAnAnimatedPng) {
  ::setenv("PLUMEKIT_VIDEO_MODULE", (dir / "no-such-module.so").c_str(), 1);
  const CliResult r = localize("--animate " + (dir / "run.mp4").string() + " --json");
  ::unsetenv("PLUMEKIT_VIDEO_MODULE");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["animation"]["format"], "apng");
  EXPECT_EQ(j["animation"]["file"], (dir / "run.png").string());
  EXPECT_FALSE(fs::exists(dir / "run.mp4"));
  EXPECT_TRUE(fs::exists(dir / "run.png"));
}

TEST_F(ReplayCli, BadInputExitsTwoAndWritesNothing) {
  // A user's file in the animation's place: refused before the run, nothing else written.
  const fs::path mine = dir / "mine.mp4";
  std::ofstream(mine) << "my video";
  CliResult r = localize("--out " + (dir / "run").string() + " --animate " + mine.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("mine.mp4"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "run"));
  std::ifstream in(mine);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "my video");
  r = localize("--animate " + (dir / "run.gif").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--animate"), std::string::npos) << r.err;
  // A folder without a replay, a bad frame size.
  fs::create_directories(dir / "empty");
  r = run("replay " + (dir / "empty").string() + " --out " + (dir / "x.mp4").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("holds no replay.json"), std::string::npos) << r.err;
  r = run("replay " + (dir / "empty").string() + " --out " + (dir / "x.mp4").string() +
          " --size 641x360");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.mp4"));
}

// `plume --animate --series`: the filament plume as it moves, a frame a second, as a video and as
// a ParaView time series; the steady advection-diffusion plume is refused.
TEST_F(ReplayCli, APlumeOverTimeAsAnAnimationAndAParaViewSeries) {
  const std::string map = write_small_map(dir);
  CliResult r =
      run("plume " + map + " --source 4.5,0.5 --seconds 5 --series --animate " +
          (dir / "plume.png").string() + " --out " + (dir / "plume").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["animation"]["frames"], 6);
  EXPECT_EQ(j["animation"]["format"], "apng");
  const std::string pvd = slurp(dir / "plume" / "plume.pvd");
  std::string first, last;
  for (int k = 0; k <= 5; ++k) {
    const std::string name = "series/plume-000" + std::to_string(k) + ".vti";
    EXPECT_NE(pvd.find("timestep=\"" + std::to_string(k) + "\" group=\"\" part=\"0\" file=\"" +
                       name + "\""),
              std::string::npos)
        << pvd;
    const std::string vti = slurp(dir / "plume" / name);
    EXPECT_NE(vti.find("Name=\"concentration\""), std::string::npos) << name;
    (k == 0 ? first : last) = vti;
  }
  EXPECT_NE(first, last);  // the plume moves
  EXPECT_FALSE(fs::exists(dir / "plume" / "series" / "plume-0006.vti"));
  r = run("plume " + map + " --source 4.5,0.5 --simulator advection-diffusion --series --out " +
          (dir / "steady").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--simulator filament"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "steady"));
}

}  // namespace
}  // namespace plumekit::test
