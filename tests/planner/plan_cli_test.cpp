// End-to-end tests of `plumekit plan`: exit codes, JSON, the PNG.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

using Result = plumekit::test::CliResult;
class PlanCli : public plumekit::test::CliTest {};

TEST_F(PlanCli, PlansAroundTheUShapeAndDrawsIt) {
  const fs::path png = dir / "u.png";
  const Result r = run("plan " + (kMaps / "cluttered-2.json").string() +
                       " --from 4.6,2 --to 9,2 --json --out " + png.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], true);
  EXPECT_EQ(j["planner"], "vg");
  EXPECT_EQ(j["margin"], 0.15);
  EXPECT_EQ(j["from"], nlohmann::json::array({4.6, 2.0}));
  EXPECT_FALSE(j.contains("start_moved"));  // only a moved start is reported
  const auto& path = j["path"];
  ASSERT_GE(path.size(), 3u);  // it must leave the U through its opening
  EXPECT_EQ(path.front(), nlohmann::json::array({4.6, 2.0}));
  EXPECT_EQ(path.back(), nlohmann::json::array({9.0, 2.0}));
  double length = 0.0, min_x = 1e9;
  for (std::size_t k = 0; k < path.size(); ++k) {
    min_x = std::min(min_x, path[k][0].get<double>());
    if (k)
      length += std::hypot(path[k][0].get<double>() - path[k - 1][0].get<double>(),
                           path[k][1].get<double>() - path[k - 1][1].get<double>());
  }
  EXPECT_LE(min_x, 3.85 + 1e-12);  // round the arm's tip, 0.15 m off it
  EXPECT_NEAR(j["length_m"].get<double>(), length, 1e-9);
  EXPECT_GT(j["build_ms"].get<double>(), 0.0);
  EXPECT_GT(j["query_us"].get<double>(), 0.0);
  const cv::Mat img = cv::imread(png.string());
  ASSERT_FALSE(img.empty());
  EXPECT_GT(img.cols, 1000);
}

TEST_F(PlanCli, HumanOutputListsVerticesAndReportsAMove) {
  const Result r = run("plan --from 0.05,2 --to 9,3.5");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("vg path from (0.05, 2) to (9, 3.5)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("start moved from (0.05, 2) to (0.15, 2): closer than the margin"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("length"), std::string::npos);
}

TEST_F(PlanCli, OmplPlannersRunThroughTheSameCommand) {
  for (const char* p : {"rrtstar", "prmstar"}) {
    const Result r = run("plan " + (kMaps / "cluttered-2.json").string() +
                         " --from 1,2 --to 9,2 --json --planner " + p);
    ASSERT_EQ(r.code, 0) << p << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["planner"], p);
    EXPECT_GE(j["length_m"].get<double>(), 8.0);
  }
}

TEST_F(PlanCli, GoalInsideAnObstacleExitsTwoAndLeavesNoPng) {
  const fs::path png = dir / "bad.png";
  const Result r = run("plan " + (kMaps / "cluttered-2.json").string() +
                       " --from 1,2 --to 5.5,2 --json --out " + png.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("goal (5.5, 2) lies inside obstacles[0]"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], false);
  EXPECT_EQ(j["exit_code"], 2);
  EXPECT_FALSE(fs::exists(png));
}

TEST_F(PlanCli, BadFlagsExitTwoNamingTheFlag) {
  const std::pair<std::string, std::string> cases[] = {
      {"--from 1:2 --to 9,2", "--from: expected a point X,Y"},
      {"--from 1,2 --to nine,2", "--to: expected a point X,Y"},
      {"--from 1,2 --to 9,2 --margin -1",
       "--margin: must be a finite number from 0 to 10 m, got -1"},
      {"--from 1,2 --to 9,2 --planner dijkstra", "--planner: unknown planner 'dijkstra'"},
      {"--from 1,2 --to 12,2", "goal (12, 2) lies outside the arena"},
      {"--from 1,2 --to 9,2 --margin 2.5", "no free space at margin 2.5"},
  };
  for (const auto& [args, message] : cases) {
    const Result r = run("plan " + args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
  }
  EXPECT_EQ(run("plan --to 9,2").code, 2);  // --from is required
}

TEST_F(PlanCli, UnreachableGoalExitsTwo) {
  std::ofstream(dir / "wall.json") << R"({"format": "plumekit-map/1", "size": [10, 4],
    "inlet": {"side": "left", "speed": 1}, "outlet": {"side": "right"},
    "obstacles": [[[4, 0], [5, 0], [5, 4], [4, 4]]]})";
  const Result r = run("plan " + (dir / "wall.json").string() + " --from 1,2 --to 9,2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("cannot be reached"), std::string::npos) << r.err;
}

}  // namespace
