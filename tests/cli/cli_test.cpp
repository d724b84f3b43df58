// End-to-end tests of the plumekit command: exit codes, messages, outputs.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kData = PLUMEKIT_DATA_DIR;
const fs::path kBadMaps = PLUMEKIT_TEST_DATA "/bad-maps";

using Result = plumekit::test::CliResult;
class Cli : public plumekit::test::CliTest {};

TEST_F(Cli, ValidateAcceptsShippedMaps) {
  for (const auto& entry : fs::directory_iterator(kData / "maps")) {
    const Result r = run("map validate " + entry.path().string() + " --json");
    EXPECT_EQ(r.code, 0) << entry.path() << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["ok"], true);
    EXPECT_EQ(j["size"], nlohmann::json::array({10.0, 4.0}));
  }
}

TEST_F(Cli, ValidateRejectsEachMalformedCaseWithExitTwo) {
  const std::pair<const char*, const char*> cases[] = {
      {"self-intersecting.json", "obstacles[0]: polygon is not simple"},
      {"polygon-outside-arena.json", "obstacles[0][1]: vertex (10.5, 1) lies outside"},
      {"unknown-key.json", "source: unknown key"},
      {"missing-size.json", "size: missing"},
      {"nan-coordinate.json", "obstacles[0][1][1]: NaN is not allowed"},
      {"source-in-obstacle.json", "sources[0]: source (2.5, 1) lies inside obstacles[0]"},
      {"overlapping-openings.json",
       "outlet: span [2, 4] overlaps the inlet's [0, 3] on the left wall"},
      {"truncated.json", "not valid JSON: parse error at line 7"},
  };
  for (const auto& [file, message] : cases) {
    const fs::path path = kBadMaps / file;
    const Result r = run("map validate " + path.string());
    EXPECT_EQ(r.code, 2) << file;
    EXPECT_NE(r.err.find(path.string() + ": "), std::string::npos) << file << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << file << ": " << r.err;
    EXPECT_EQ(r.out, "") << file;
  }
}

TEST_F(Cli, JsonErrorsAreMachineReadable) {
  const Result r = run("map validate " + (kBadMaps / "missing-size.json").string() + " --json");
  EXPECT_EQ(r.code, 2);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], false);
  EXPECT_EQ(j["exit_code"], 2);
  EXPECT_NE(j["error"].get<std::string>().find("size: missing"), std::string::npos);
}

TEST_F(Cli, RenderWritesAPictureOfTheMap) {
  const fs::path png = dir / "map.png";
  const Result r = run("map render " + (kData / "maps" / "cluttered-1.json").string() + " --out " +
                       png.string() + " --px-per-m 50 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  // The margins follow the text they hold: the arena's place comes with the picture.
  const auto arena = nlohmann::json::parse(r.out)["arena_px"];
  const cv::Mat img = cv::imread(png.string());
  ASSERT_FALSE(img.empty());
  // Arena 10 x 4 m at 50 px/m plus margins.
  EXPECT_GT(img.cols, 500);
  EXPECT_GT(img.rows, 200);
  // cluttered-1 has an obstacle over (6.8, 3.0): the pixel there is obstacle grey,
  // and a free point (8.0, 1.0) is near-white. The arena's lower-left is at the
  // margin offset, found from the wall line's dark pixels.
  auto grey_at = [&](double x, double y) {
    const int left = arena[0], top = arena[1];
    return img.at<cv::Vec3b>(static_cast<int>(top + (4.0 - y) * 50),
                             static_cast<int>(left + x * 50));
  };
  EXPECT_LT(grey_at(6.8, 3.0)[0], 140);
  EXPECT_GT(grey_at(8.0, 1.0)[0], 230);
  // The inlet (left) is drawn blue: B > R.
  const cv::Vec3b inlet = grey_at(0.0, 2.05);
  EXPECT_GT(inlet[0], inlet[2] + 80);
}

TEST_F(Cli, BadInputLeavesNoOutputFile) {
  const fs::path png = dir / "never.png";
  const Result r = run("map render " + (kBadMaps / "self-intersecting.json").string() + " --out " +
                       png.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(fs::exists(png));
  // A missing parent folder is created, as for output folders.
  const Result missing_dir = run("map render --out " + (dir / "no" / "such" / "dir.png").string());
  EXPECT_EQ(missing_dir.code, 0) << missing_dir.err;
  EXPECT_TRUE(fs::exists(dir / "no" / "such" / "dir.png"));
  fs::remove_all(dir / "no");
  for (const auto& entry : fs::directory_iterator(dir))
    ADD_FAILURE() << "left behind: " << entry.path();
}

TEST_F(Cli, UsageErrorsExitTwoAndHelpExitsZero) {
  EXPECT_EQ(run("map render").code, 2);  // --out is required
  EXPECT_EQ(run("map frobnicate").code, 2);
  EXPECT_EQ(run("map render --out x.png --px-per-m -3").code, 2);
  for (const char* cmd : {"", "map", "map validate", "map render", "map import-ros"}) {
    const Result r = run(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("--help"), std::string::npos) << cmd;
  }
  EXPECT_NE(run("map validate --help").out.find("--json"), std::string::npos);
}

TEST_F(Cli, ValidateDefaultsToTheShippedMap) {
  const Result r = run("map validate");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("cluttered-1"), std::string::npos);
}

TEST_F(Cli, ImportRosWritesAValidMap) {
  const fs::path out = dir / "office.json";
  const Result r = run("map import-ros " + (kData / "ros" / "office.yaml").string() + " --out " +
                       out.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["obstacles"].get<int>(), 3);
  EXPECT_LT(j["raster_mismatch_pixels"].get<int>(), 0.01 * j["occupied_pixels"].get<int>());
  EXPECT_EQ(run("map validate " + out.string()).code, 0);
  const Result bad =
      run("map import-ros " + (dir / "nothing.yaml").string() + " --out " + out.string() + ".2");
  EXPECT_EQ(bad.code, 2);
  EXPECT_FALSE(fs::exists(out.string() + ".2"));
}

}  // namespace
