// End-to-end tests of `plumekit flow`: outputs, JSON, exit codes.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

class FlowCli : public plumekit::test::CliTest {};

TEST_F(FlowCli, WritesAllOutputsAndASummary) {
  const fs::path out = dir / "wind";
  const auto r = run("flow " + (kMaps / "cluttered-3.json").string() + " --cell 0.1 --out " +
                     out.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], true);
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["grid"]["nx"], 100);
  EXPECT_LT(j["mass_imbalance"].get<double>(), 1e-12);
  for (const char* f : {"u.npy", "v.npy", "p.npy", "wind.json", "wind.vti", "wind.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const cv::Mat png = cv::imread((out / "wind.png").string());
  EXPECT_GT(png.cols, 500);
}

TEST_F(FlowCli, BadInputExitsTwoAndWritesNothing) {
  const std::string map = (kMaps / "cluttered-1.json").string();
  const fs::path out = dir / "wind";
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"--nu -0.01", "--nu"},
      {"--cell 3", "at least 3 cells"},
      {"--max-iter 1", "Residual history"},
      {"--max-iter -1", "--max-iter"},
  };
  for (const Case& c : cases) {
    const auto r = run("flow " + map + " --out " + out.string() + " " + c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  const auto bad_map = run("flow " + std::string(PLUMEKIT_TEST_DATA) +
                           "/bad-maps/self-intersecting.json --out " + out.string());
  EXPECT_EQ(bad_map.code, 2);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
