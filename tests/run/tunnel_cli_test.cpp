// `plumekit localize tunnel` and `plumekit evaluate tunnel`: they run, write what they say,
// refuse bad input with exit 2 naming the flag, and leave `localize` itself as it was.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"

namespace plumekit::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

class TunnelCli : public CliTest {
 protected:
  static bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  }
};

TEST_F(TunnelCli, LocalizeRunsTheThreeMethodsAndWritesTheRun) {
  const fs::path out = dir / "ste";
  const CliResult r =
      run("localize tunnel --source 1,1.5,0.6 --start 8,2.5,1.5 --seed 3 --json "
          "--out " +
          out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["method"], "ste-3d");
  EXPECT_EQ(j["stopped_by"], "entropy");
  EXPECT_LT(j["error_m"].get<double>(), 0.5);
  EXPECT_EQ(j["source"], json::array({1.0, 1.5, 0.6}));
  const json file = json::parse(slurp(out / "run.json"));
  EXPECT_EQ(file["steps"].size(), j["samples"].get<std::size_t>());
  EXPECT_EQ(file["error_m"], j["error_m"]);
  EXPECT_TRUE(fs::file_size(out / "trajectory.png") > 1000);
  // The same seed, the same run.
  const CliResult again =
      run("localize tunnel --source 1,1.5,0.6 --start 8,2.5,1.5 --seed 3 --json");
  EXPECT_EQ(json::parse(again.out)["estimate"], j["estimate"]);
  for (const char* method : {"surge-spiral", "surge-cast-2d"}) {
    const CliResult t = run(std::string("localize tunnel --method ") + method +
                            " --source 1,2,1 --time-limit 60 --json");
    ASSERT_EQ(t.code, 0) << t.err;
    const json tj = json::parse(t.out);
    EXPECT_EQ(tj["method"], method);
    EXPECT_EQ(tj["start"][0], 9.9);  // 10 m downwind, cut to the 10 m tunnel
  }
}

TEST_F(TunnelCli, EvaluateWritesEachMethodsFolder) {
  const fs::path out = dir / "eval";
  const CliResult r =
      run("evaluate tunnel --method ste-3d,surge-spiral --runs 2 --time-limit 30 "
          "--json --out " +
          out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["methods"].size(), 2u);
  for (const char* m : {"ste-3d", "surge-spiral"}) {
    for (const char* f :
         {"runs.csv", "summary.json", "boxplot.png", "trajectory-median.png", "report.html"})
      EXPECT_TRUE(fs::exists(out / m / f)) << m << "/" << f;
    const json s = json::parse(slurp(out / m / "summary.json"));
    EXPECT_EQ(s["runs"], 2);
    // tracks.json: the tunnel from above as the map, each run's way with its heights.
    const json t = json::parse(slurp(out / m / "tracks.json"));
    EXPECT_EQ(t["format"], "plumekit-tracks/1");
    EXPECT_EQ(t["maps"][0]["width"], 10.0);
    ASSERT_EQ(t["runs"].size(), 2u);
    const json& way = t["runs"][0]["robots"][0];
    EXPECT_EQ(way["path"].size(), 2 * way["path_z"].size());
    EXPECT_GE(way["path_z"].size(), 2u);
  }
  const std::string page = slurp(out / "report.html");  // both methods
  EXPECT_TRUE(has(page, "\"format\":\"plumekit-report/1\"")) << page.substr(0, 400);
  EXPECT_TRUE(has(page, "\"surge-spiral\"") && has(page, "\"ste-3d\""));
}

TEST_F(TunnelCli, ReplaysFromAboveAndTheSideChangeNoResult) {
  // A run's replay: its video, and its files drawn again by `plumekit replay`.
  const fs::path run_dir = dir / "run";
  CliResult r =
      run("localize tunnel --source 1,1.5,0.6 --start 6,2.5,1.5 --seed 3 "
          "--max-samples 6 --json --out " +
          run_dir.string() + " --animate " + (dir / "run.png").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  const int frames = j["animation"]["frames"].get<int>();
  EXPECT_EQ(frames, static_cast<int>(j["mission_s"].get<double>() + 1e-9) + 1);
  const json replay = json::parse(slurp(run_dir / "replay.json"));
  EXPECT_EQ(replay["side"]["plane_y"], 1.5);
  EXPECT_EQ(replay["source"], json::array({1.0, 1.5, 0.6}));
  EXPECT_TRUE(fs::exists(run_dir / "replay-plume-side.png"));
  r = run("replay " + run_dir.string() + " --out " + (dir / "again.png").string() +
          " --size 640x360 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["frames"].get<int>(), frames);

  // An evaluation's replays, one folder per run, and the same results without them.
  const fs::path with = dir / "with", without = dir / "without";
  const std::string eval = "evaluate tunnel --method surge-spiral --runs 2 --time-limit 20 --out ";
  r = run(eval + with.string() + " --replays");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run(eval + without.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(with / "runs.csv"), slurp(without / "runs.csv"));
  EXPECT_EQ(slurp(with / "tracks.json"), slurp(without / "tracks.json"));
  for (const char* run : {"tunnel-r0", "tunnel-r1"}) {
    const fs::path folder = with / "replays" / run;
    EXPECT_TRUE(has(slurp(folder / "replay.js"), "plumekitReplay({")) << run;
    EXPECT_TRUE(fs::exists(folder / "replay-belief-side.png")) << run;
  }
  EXPECT_TRUE(has(slurp(with / "report.html"), "\"replays\":[\"replays/tunnel-r0\""));
  EXPECT_FALSE(fs::exists(without / "replays"));
}

TEST_F(TunnelCli, BadInputExitsTwoNamingTheFlag) {
  CliResult r = run("localize tunnel --source 1,2,3");  // above the 2 m ceiling
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "source")) << r.err;
  r = run("localize tunnel --source 1,2");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--source: expected a point X,Y,Z")) << r.err;
  r = run("localize tunnel --method ste");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--method")) << r.err;
  r = run("evaluate tunnel --wind-speed -1 --runs 1");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--wind-speed")) << r.err;
  r = run("localize tunnel --tunnel 10,4,0.5");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--tunnel")) << r.err;
  // An output folder plumekit did not write is left alone.
  const fs::path mine = dir / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "keep";
  r = run("localize tunnel --out " + mine.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(slurp(mine / "notes.txt"), "keep");
  // `localize` without the subcommand still needs its --source.
  r = run("localize");
  EXPECT_NE(r.code, 0);
  EXPECT_TRUE(has(r.err, "--source is required")) << r.err;
  EXPECT_TRUE(has(run("localize tunnel --help").out, "--wind-speed FLOAT=0.9"));
}

}  // namespace
}  // namespace plumekit::test
