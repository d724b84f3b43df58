// The STE and plan commands' shared flags (issue 15): --help defaults are the
// library's, old spellings still work with a warning, a moved start is reported
// the same way by localize and plan, --cell reaches the wind, and evaluate,
// demo and localize take --threads and --seed.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"
#include "support/small_map.hpp"

namespace plumekit::test {
namespace {

using nlohmann::json;

class SteFlags : public CliTest {
 protected:
  std::string write_map() { return write_small_map(dir); }
  static bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  }
};

TEST_F(SteFlags, HelpShowsTheLibraryDefaults) {
  for (const char* command : {"localize", "demo", "evaluate"}) {
    const CliResult r = run(std::string(command) + " --help");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "--plume-model TEXT=surrogate")) << command << r.out;
    EXPECT_TRUE(has(r.out, "--seed UINT=1")) << command;
    EXPECT_TRUE(has(r.out, "--threads INT=0")) << command;
    EXPECT_TRUE(has(r.out, "--cell FLOAT=0 ")) << command;  // 0: 0.05 m up to building scale
    EXPECT_TRUE(has(r.out, "--reward TEXT=expected")) << command;
    EXPECT_TRUE(has(r.out, "--cnn TEXT=")) << command;
    EXPECT_TRUE(has(r.out, "default: 200 for the surrogate")) << command;
    EXPECT_FALSE(has(r.out, "--model ")) << command << ": a deprecated alias is hidden";
  }
  EXPECT_TRUE(has(run("evaluate --help").out, "--map-dir"));
  EXPECT_TRUE(has(run("plan --help").out, "--margin FLOAT=0.15"));
  EXPECT_TRUE(has(run("plan --help").out, "--planner TEXT=vg"));
}

TEST_F(SteFlags, OldSpellingsWarnAndStillWork) {
  const std::string map = write_map();
  CliResult r =
      run("localize " + map + " --source 4.2,1.3 --model " + (dir / "missing.pkcnn").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--model is deprecated")) << r.err;
  EXPECT_TRUE(has(r.err, "--cnn: " + (dir / "missing.pkcnn").string() + " not found")) << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --model a --cnn b");
  EXPECT_EQ(r.code, 2) << "the old and the new spelling together";
  r = run("evaluate --maps " + (dir / "maps").string() +
          " --runs 1 --sources 1 --max-samples 2 --plume-model physics --out " +
          (dir / "e").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(has(r.err, "--maps is deprecated")) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "e" / "runs.csv"));
}

TEST_F(SteFlags, LocalizeAndPlanReportAMovedStartAlike) {
  const std::string map = write_map();
  // 5 cm off the obstacle's left face: inside the 0.15 m margin.
  const std::string start = "2.45,1.5";
  CliResult r = run("localize " + map + " --source 4.5,0.5 --start " + start +
                    " --plume-model physics --max-samples 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  json j = json::parse(r.out);
  ASSERT_TRUE(j.contains("start_moved")) << r.out;
  EXPECT_EQ(j["start_moved"]["requested"], json::array({2.45, 1.5}));
  const json used = j["start_moved"]["used"];
  EXPECT_EQ(j["start"], used);
  EXPECT_NEAR(used[0].get<double>(), 2.35, 0.01);
  r = run("localize " + map + " --source 4.5,0.5 --start " + start +
          " --plume-model physics --max-samples 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "start moved from (2.45, 1.5) to (")) << r.out;
  EXPECT_TRUE(has(r.out, "): closer than the margin to an obstacle")) << r.out;

  r = run("plan " + map + " --from " + start + " --to 5,1.5 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = json::parse(r.out);
  EXPECT_EQ(j["start_moved"]["requested"], json::array({2.45, 1.5}));
  EXPECT_EQ(j["start_moved"]["used"], j["start"]);
  EXPECT_FALSE(j.contains("goal_moved"));
  r = run("plan " + map + " --from " + start + " --to 5,1.5");
  EXPECT_TRUE(has(r.out, "start moved from (2.45, 1.5) to (")) << r.out;
  EXPECT_TRUE(has(r.out, "): closer than the margin to an obstacle")) << r.out;

  // Not moved: no key at all.
  r = run("localize " + map +
          " --source 4.5,0.5 --start 1,2.5 --plume-model physics "
          "--max-samples 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(json::parse(r.out).contains("start_moved")) << r.out;
}

TEST_F(SteFlags, CellReachesTheWindAndErrorsNameTheFlag) {
  const std::string map = write_map();
  CliResult r = run("localize " + map + " --source 4.5,0.5 --plume-model physics --cell -1");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--cell: ")) << r.err;
  EXPECT_FALSE(has(r.err, "flow.cell")) << r.err;
  // A coarser wind is another wind: the run differs, and says the same cell was used.
  const std::string base = "localize " + map +
                           " --source 4.5,0.5 --start 1,2.5 --plume-model physics "
                           "--max-samples 3 --json";
  const CliResult fine = run(base), coarse = run(base + " --cell 0.1");
  ASSERT_EQ(fine.code, 0) << fine.err;
  ASSERT_EQ(coarse.code, 0) << coarse.err;
  EXPECT_NE(json::parse(fine.out)["steps"], json::parse(coarse.out)["steps"]);
}

TEST_F(SteFlags, ThreadsAndSeedDoNotChangeALocalization) {
  const std::string map = write_map();
  const std::string base =
      "localize " + map + " --source 4.5,0.5 --plume-model physics --max-samples 3 --json";
  const CliResult one = run(base + " -j 1"), two = run(base + " --threads 2"),
                  seed1 = run(base + " --seed 1");
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(two.code, 0) << two.err;
  json a = json::parse(one.out), b = json::parse(two.out), c = json::parse(seed1.out);
  EXPECT_EQ(a["estimate"], b["estimate"]);
  EXPECT_EQ(a["start"], b["start"]);
  EXPECT_EQ(a["start"], c["start"]) << "the default seed is 1";
  EXPECT_NE(a["start"], json::parse(run(base + " --seed 2").out)["start"]);
}

TEST_F(SteFlags, EvaluateRefusesAMissingFolderByItsFlag) {
  CliResult r = run("evaluate --plume-model physics");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--map-dir: ")) << r.err;
  r = run("evaluate --map-dir " + (dir / "nowhere").string() + " --threads -1");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(has(r.err, "--threads: ")) << r.err;
}

}  // namespace
}  // namespace plumekit::test
