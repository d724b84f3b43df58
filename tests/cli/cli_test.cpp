// End-to-end tests of the plumekit command: exit codes, messages, outputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kData = PLUMEKIT_DATA_DIR;
const fs::path kBadMaps = fs::path(PLUMEKIT_TEST_DATA) / "bad-maps";

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

// Sources and robot starts typed in the ROS map frame land in the file as
// typed; one in an obstacle or off the map is refused, naming it, with no file.
TEST_F(Cli, ImportRosPlacesSourcesAndStartsInTheMapFrame) {
  const std::string cmd = "map import-ros " + (kData / "ros" / "office.yaml").string() +
                          " --inlet 0,1.8,0,3.4 --outlet 11.25,1.0,11.25,2.5";
  const fs::path out = dir / "office.json";
  const Result r = run(cmd + " --out " + out.string() +
                       " --source 3,1.5 --source 9,3 --start 6,3 --start 1.5,4");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(plumekit::test::slurp(out));
  EXPECT_EQ(j["sources"], nlohmann::json::parse("[[3.0, 1.5], [9.0, 3.0]]"));
  EXPECT_EQ(j["starts"], nlohmann::json::parse("[[6.0, 3.0], [1.5, 4.0]]"));
  EXPECT_EQ(run("map validate " + out.string()).code, 0);
  const fs::path bad = dir / "bad.json";
  // The flag and the value are named (not the output file's sources[0]), and the map's extent.
  const Result inside = run(cmd + " --out " + bad.string() + " --source 2,2.5");
  EXPECT_EQ(inside.code, 2);
  EXPECT_NE(inside.err.find("--source 2,2.5: lies inside obstacles["), std::string::npos)
      << inside.err;
  const Result off = run(cmd + " --out " + bad.string() + " --start 6,3 --start -3,1");
  EXPECT_EQ(off.code, 2);
  const std::string extent =
      "lies outside the imported map, which spans x from -0.4 to 11.6 m and y from -0.4 to 5.6 m "
      "in the map frame";
  EXPECT_NE(off.err.find("--start -3,1: " + extent), std::string::npos) << off.err;
  const Result far = run(cmd + " --out " + bad.string() + " --source 1000,0");
  EXPECT_EQ(far.code, 2);
  EXPECT_NE(far.err.find("--source 1000,0: " + extent), std::string::npos) << far.err;
  EXPECT_EQ(far.err.find("sources[0]"), std::string::npos) << far.err;
  EXPECT_FALSE(fs::exists(bad));
}

// A source in free space boxed in by obstacles: a valid point, but its gas never
// leaves the box. validate says so; localize refuses it, saying the same (not
// "inside an obstacle"), before any run.
TEST_F(Cli, ASourceInASealedPocketIsNamedByValidateAndLocalize) {
  const fs::path map = dir / "pocket.json";
  std::ofstream(map) << R"({"format": "plumekit-map/1", "name": "pocket", "size": [10, 4],
    "inlet": {"side": "left", "speed": 1}, "outlet": {"side": "right"},
    "obstacles": [[[3, 1], [4, 1], [4, 1.1], [3, 1.1]], [[3, 1.9], [4, 1.9], [4, 2], [3, 2]],
                  [[3, 1.1], [3.1, 1.1], [3.1, 1.9], [3, 1.9]],
                  [[3.9, 1.1], [4, 1.1], [4, 1.9], [3.9, 1.9]]],
    "sources": [[3.5, 1.5], [6, 1]]})";
  const std::string pocket =
      "lies in a pocket of free space sealed off from every opening: no air reaches it";
  const Result v = run("map validate " + map.string());
  EXPECT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.err.find("warning: sources[0] (3.5, 1.5) " + std::string(pocket)), std::string::npos)
      << v.err;
  EXPECT_EQ(v.err.find("sources[1]"), std::string::npos) << v.out;
  const fs::path out = dir / "run";
  const Result l =
      run("localize " + map.string() +
          " --source 3.5,1.5 --start 1,1 --plume-model gaussian --out " + out.string());
  EXPECT_EQ(l.code, 2);
  EXPECT_NE(l.err.find("--source: (3.5, 1.5) " + std::string(pocket)), std::string::npos) << l.err;
  EXPECT_EQ(l.err.find("inside an obstacle"), std::string::npos) << l.err;
  EXPECT_FALSE(fs::exists(out));
}

// A huge arena is checked on coarse cells; an opening shorter than one is the
// grid's fault, and validate says so instead of "the map cannot carry a flow".
TEST_F(Cli, ValidateSaysItsGridIsTooCoarseForAShortOpeningOnAHugeArena) {
  const fs::path map = dir / "huge.json";
  std::ofstream(map) << R"({"format": "plumekit-map/1", "name": "huge", "size": [1e6, 1e6],
    "inlet": {"side": "left", "from": 0, "to": 2, "speed": 1},
    "outlet": {"side": "right", "from": 0, "to": 2}})";
  const Result v = run("map validate " + map.string());
  EXPECT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.err.find("warning: no free path from the inlet to the outlet at 5e+02 m cells, "
                       "which are too coarse for this map: the inlet is 2 m long, shorter than a "
                       "cell, so no cell opens onto it; a check that sees it needs cells of at "
                       "most 2 m (2.5e+11 cells; it takes at most 4e+06)"),
            std::string::npos)
      << v.err;
  EXPECT_EQ(v.err.find("the map cannot carry a flow"), std::string::npos) << v.err;
}

TEST_F(Cli, ImportRosOfTheOfficeSaysWhyNoAirCrossesItAndValidateWarns) {
  const fs::path out = dir / "office.json";
  const Result r =
      run("map import-ros " + (kData / "ros" / "office.yaml").string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  // Warnings go to stderr (issue 44): stdout holds the result alone.
  EXPECT_NE(r.err.find("plumekit: warning: no free path from any inlet to any outlet"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("largest sealed free region (48.8 m²"), std::string::npos) << r.err;
  // The advice names the command's flags, not the library's fields.
  EXPECT_NE(r.err.find("import with --unknown free"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--inlet / --outlet"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("ros."), std::string::npos) << r.err;
  const Result v = run("map validate " + out.string());
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find("valid plumekit-map/2"), std::string::npos) << v.out;
  EXPECT_EQ(v.out.find("warning"), std::string::npos) << v.out;
  EXPECT_NE(v.err.find("plumekit: warning: no free path"), std::string::npos) << v.err;
  EXPECT_NE(v.err.find("largest sealed free region (48.8 m²"), std::string::npos) << v.err;
  // With --json, stdout is the JSON alone, the warnings in it.
  const Result j = run("map validate " + out.string() + " --json");
  EXPECT_FALSE(nlohmann::json::parse(j.out)["warnings"].empty()) << j.out;
}

TEST_F(Cli, ImportRosTakesSeveralOpeningsInTheMapFrameAndSnapsThem) {
  const fs::path out = dir / "office.json";
  const Result r =
      run("map import-ros " + (kData / "ros" / "office.yaml").string() + " --out " + out.string() +
          " --inlet 0,1.8,0,3.4,0.5,parabolic --outlet 11.25,1.0,11.25,2.5"
          " --outlet 11.25,2.6,11.25,4.2 --close-gaps 0.5 --min-area 4 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "plumekit-map/2");
  EXPECT_EQ(j["frame_origin"], nlohmann::json::array({-0.4, -0.4}));
  ASSERT_EQ(j["openings"].size(), 3u);
  EXPECT_EQ(j["openings"][0]["kind"], "inlet");
  EXPECT_EQ(j["openings"][0]["speed"], 0.5);
  EXPECT_EQ(j["openings"][0]["requested"], "0,1.8,0,3.4,0.5,parabolic");
  EXPECT_NEAR(j["openings"][0]["from"][1].get<double>(), 1.85, 1e-9);
  EXPECT_NEAR(j["openings"][1]["from"][0].get<double>(), 11.2, 1e-9);
  EXPECT_NEAR(j["openings"][2]["to"][1].get<double>(), 4.1, 1e-9);
  EXPECT_EQ(j["inlet_reaches_outlet"], true);
  EXPECT_EQ(j["warnings"].size(), 0u) << j["warnings"];
  // The office has a table 0.45 m from a wall and a one-pixel speck.
  EXPECT_GT(j["gaps"]["gaps_closed"].get<int>(), 0);
  EXPECT_GT(j["gaps"]["pixels_filled"].get<int>(), 0);
  EXPECT_GT(j["specks"]["dropped"].get<int>(), 0);
  const Result v = run("map validate " + out.string() + " --json");
  EXPECT_EQ(v.code, 0) << v.err;
  EXPECT_EQ(nlohmann::json::parse(v.out)["warnings"].size(), 0u) << v.out;
  // Text: the snapped segments and what was changed.
  const Result t =
      run("map import-ros " + (kData / "ros" / "office.yaml").string() + " --out " + out.string() +
          " --inlet 0,1.8,0,3.4 --outlet 11.25,1.0,11.25,4.2 --close-gaps 0.5");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("inlet 0,1.85,0,3.35 at 1 m/s uniform (--inlet '0,1.8,0,3.4'"),
            std::string::npos)
      << t.out;
  EXPECT_NE(t.out.find("gaps closed"), std::string::npos) << t.out;
}

TEST_F(Cli, ImportRosRefusesAnOpeningFarFromAnyBoundary) {
  const fs::path out = dir / "office.json";
  const std::string yaml = (kData / "ros" / "office.yaml").string();
  const Result r = run("map import-ros " + yaml + " --out " + out.string() +
                       " --inlet 0,1.8,0,3.4 --outlet 5,1,6,1");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--outlet: '5,1,6,1': no boundary of the free space"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
  const Result half =
      run("map import-ros " + yaml + " --out " + out.string() + " --inlet 0,1.8,0,3.4");
  EXPECT_EQ(half.code, 2);
  EXPECT_NE(half.err.find("--outlet"), std::string::npos) << half.err;
  EXPECT_FALSE(fs::exists(out));
}

// The docs' commands name files a user has: the real maps ship in data/real-maps/ (with their
// licence), and no page points outside the repository (issue 44).
TEST_F(Cli, DocsNameOnlyShippedFiles) {
  const fs::path root = kData.parent_path();
  std::vector<fs::path> pages{root / "README.md"};
  const auto add_pages = [&pages](const fs::path& folder, bool readme_in_subfolders) {
    for (const auto& e : fs::directory_iterator(folder)) {
      const fs::path p = readme_in_subfolders ? e.path() / "README.md" : e.path();
      if (p.extension() == ".md" && fs::is_regular_file(p)) pages.push_back(p);
    }
  };
  add_pages(root, true);
  add_pages(root / "docs", false);
  add_pages(root / "data", true);
  add_pages(root / "bench", true);
  for (const fs::path& page : pages)
    EXPECT_EQ(plumekit::test::slurp(page).find("../shared/"), std::string::npos) << page;
  const fs::path real = kData / "real-maps";
  EXPECT_TRUE(fs::exists(real / "LICENSE-Apache-2.0.txt"));
  for (const char* file : {"tb3_world/map.pgm", "depot/depot.yaml", "depot/depot.pgm",
                           "warehouse/warehouse.yaml", "warehouse/warehouse.pgm"})
    EXPECT_TRUE(fs::exists(real / file)) << file;
  // docs/real-maps.md's first command, on the shipped file.
  const Result r = run("map import-ros " + (real / "tb3_world" / "map.yaml").string() +
                       " --name tb3_world --out " + (dir / "tb3.json").string() +
                       " --inlet=-1,-2.5,1,-2.5 --outlet=-1,2.5,1,2.5 --json");
  EXPECT_EQ(r.code, 0) << r.err;
}

}  // namespace
