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
    for (const char* f : {"runs.csv", "summary.json", "boxplot.png", "trajectory-median.png"})
      EXPECT_TRUE(fs::exists(out / m / f)) << m << "/" << f;
    const json s = json::parse(slurp(out / m / "summary.json"));
    EXPECT_EQ(s["runs"], 2);
  }
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
