// `plumekit gdm`: maps from a CSV, scored against the true plume; bad input writes nothing.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"
#include "support/small_map.hpp"

namespace plumekit::test {
namespace {

class GdmCli : public CliTest {};

TEST_F(GdmCli, MapsACsvAndScoresItAgainstTheTruePlume) {
  const std::string map = write_small_map(dir);
  {
    std::ofstream csv(dir / "log.csv");
    csv << "x,y,reading,u,v\n";
    for (double x = 3.5; x < 6.0; x += 0.5)
      for (double y = 0.25; y < 3.0; y += 0.5)
        csv << x << ',' << y << ',' << (y < 1.0 ? 500.0 : 0.0) << ",1,0\n";
  }
  const CliResult r = run("gdm " + map + " --samples " + (dir / "log.csv").string() +
                          " --source 4.5,0.5 --cell 0.1 --wind-stretch 0.6 --out " +
                          (dir / "out").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["samples"], 30);
  EXPECT_GT(j["score"]["kl_distance"].get<double>(), 0.0);
  EXPECT_EQ(j["source_estimates"].size(), 6u);
  for (const char* f : {"mean.npy", "variance.npy", "confidence.npy", "gdm.png", "gdm.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
}

TEST_F(GdmCli, BadReadingsExitTwoAndWriteNothing) {
  const std::string map = write_small_map(dir);
  std::ofstream(dir / "bad.csv") << "x,y,reading\n1,1,5\n2,1,nan\n";
  const CliResult r = run("gdm " + map + " --samples " + (dir / "bad.csv").string() + " --out " +
                          (dir / "out").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.csv:3, column 'reading'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  const CliResult none = run("gdm " + map + " --out " + (dir / "out").string());
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("--samples"), std::string::npos) << none.err;
}

// A team run.json of two robots on the small map (6 x 3 m), recorded as localize writes it:
// the map relative to the folder it ran in, the declaring robot's steps at the top.
void write_team_run(const std::filesystem::path& file, const std::string& map) {
  std::filesystem::create_directories(file.parent_path());
  const std::string r1 = R"([{"recorded_position": [1, 1], "value": 5, "wind": [1, 0]},
                             {"recorded_position": [2, 2.5], "value": 0, "wind": [1, 0]}])";
  const std::string r2 = R"([{"recorded_position": [5.5, 0.5], "value": 40, "wind": [1, 0]},
                             {"recorded_position": [5.8, 2.8], "value": 1, "wind": [1, 0]},
                             {"recorded_position": [4.5, 1.5], "value": 9, "wind": [1, 0]}])";
  std::ofstream(file) << R"({"ok": true, "map": ")" << map << R"(", "steps": )" << r1
                      << R"(, "team": {"robots": 2, "members": [{"steps": )" << r1
                      << R"(}, {"steps": )" << r2 << "}]}}";
}

TEST_F(GdmCli, ARunIsMappedOnItsOwnMapWithEveryRobotsSamples) {
  write_small_map(dir);
  write_team_run(dir / "runs" / "r1" / "run.json", "maps/small.json");
  const CliResult r = run("gdm --run " + (dir / "runs" / "r1").string() + " --out " +
                          (dir / "out").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["map"], (dir / "maps" / "small.json").string());
  EXPECT_EQ(j["grid"], nlohmann::json::array({60, 30}));  // the small map's, not the default's
  EXPECT_EQ(j["samples"], 5);
  EXPECT_EQ(j["samples_outside_arena"], 0);
}

TEST_F(GdmCli, ARunWhoseMapIsGoneIsRefused) {
  write_team_run(dir / "runs" / "r1" / "run.json", "maps/gone.json");
  const CliResult r =
      run("gdm --run " + (dir / "runs" / "r1").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("run.json: the run's map 'maps/gone.json' is not a file here"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("plumekit gdm MAP --run"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST_F(GdmCli, AbsurdReadingsAndOutsideSamplesAreNamed) {
  const std::string map = write_small_map(dir);
  std::ofstream(dir / "huge.csv") << "x,y,reading\n1,1,5\n2,1,1e308\n";
  const CliResult r = run("gdm " + map + " --samples " + (dir / "huge.csv").string() + " --out " +
                          (dir / "out").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("huge.csv:3, column 'reading': 1e+308 is beyond"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  std::ofstream(dir / "out.csv") << "\xEF\xBB\xBFX,Y,Reading\n1,1,5\n-0.5,1,3\n";
  const CliResult o = run("gdm " + map + " --samples " + (dir / "out.csv").string() + " --out " +
                          (dir / "out").string());
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("(1 of them outside the map's arena: counted"), std::string::npos) << o.out;
}

TEST_F(GdmCli, AGridBeyondTheMemoryLimitIsRefusedNamingTheFlagAndACellThatFits) {
  const std::string map = write_small_map(dir);
  std::ofstream(dir / "log.csv") << "x,y,reading\n1,1,5\n";
  const std::string args = "gdm " + map + " --samples " + (dir / "log.csv").string() + " --out " +
                           (dir / "out").string() + " --max-memory 64M --map-cell ";
  const CliResult r = run(args + "0.002");  // 4.5 million cells
  EXPECT_EQ(r.code, 2);
  const auto at = r.err.find("use a larger --map-cell (");
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  const std::string fits = r.err.substr(at + 25, r.err.find(" m fits", at) - at - 25);
  const CliResult ok = run(args + fits);
  EXPECT_EQ(ok.code, 0) << fits << ": " << ok.err;
}

}  // namespace
}  // namespace plumekit::test
