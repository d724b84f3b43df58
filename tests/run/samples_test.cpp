// The readers of readings: a user's CSV and a localize run.json, and their faults.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "map/map.hpp"
#include "run/gdm_samples.hpp"

namespace plumekit::methods {
namespace {

// A 10 x 4 m arena whose lower-left corner is at (-1, -2) in the map frame.
Map framed_arena() {
  Map m = default_arena(10.0, 4.0);
  m.frame.origin = {-1.0, -2.0};
  return m;
}

std::string message_of(const std::string& text) {
  try {
    run::parse_samples_csv(text, "log.csv", framed_arena());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SamplesCsv, ReadsColumnsInAnyOrderInTheMapFrame) {
  const auto s = run::parse_samples_csv(
      "# a robot's log\nreading, y, x\n\n12.5, 0, 1\n0,1.5,-0.5\n", "log.csv", framed_arena());
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].position, (Vec2{2.0, 2.0}));
  EXPECT_EQ(s[0].reading, 12.5);
  EXPECT_FALSE(s[0].wind.has_value());
  EXPECT_EQ(s[1].position, (Vec2{0.5, 3.5}));
  const auto w =
      run::parse_samples_csv("x,y,reading,u,v\r\n1,0,3,0.5,-0.25\r\n", "w.csv", framed_arena());
  ASSERT_TRUE(w[0].wind.has_value());
  EXPECT_EQ(*w[0].wind, (Vec2{0.5, -0.25}));
}

TEST(SamplesCsv, FaultsNameTheFileLineAndColumn) {
  EXPECT_NE(message_of("x,y\n1,2\n").find("log.csv:1: the header names no 'reading'"),
            std::string::npos);
  EXPECT_NE(message_of("x,y,reading\n1,2,3\n1,nan,3\n").find("log.csv:3, column 'y'"),
            std::string::npos);
  EXPECT_NE(message_of("x,y,reading\n1,2,abc\n").find("'abc' is not a finite number"),
            std::string::npos);
  EXPECT_NE(message_of("x,y,reading\n1,2\n").find("log.csv:2: no value in column 'reading'"),
            std::string::npos);
  EXPECT_NE(message_of("x,y,reading,u\n").find("only one of 'u' and 'v'"), std::string::npos);
  EXPECT_NE(message_of("x,y,reading\n").find("no samples"), std::string::npos);
  EXPECT_NE(message_of("# nothing\n").find("no header"), std::string::npos);
}

TEST(SamplesCsv, AByteOrderMarkAndAnyCaseOfTheHeaderAreRead) {
  const auto s =
      run::parse_samples_csv("\xEF\xBB\xBFX,Y,Reading,U,V\n1,0,3,1,0\n", "log.csv", framed_arena());
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].position, (Vec2{2.0, 2.0}));
  EXPECT_EQ(s[0].reading, 3.0);
  EXPECT_TRUE(s[0].wind.has_value());
  EXPECT_NE(message_of("x,X,y,reading\n")
                .find("log.csv:1: the header names 'x' twice (columns 1 "
                      "and 2)"),
            std::string::npos);
  EXPECT_NE(message_of("pos_x,y,reading\n").find("it reads 'pos_x,y,reading'"), std::string::npos);
}

TEST(SamplesCsv, AbsurdValuesAreRefusedNamingTheLineAndColumn) {
  EXPECT_NE(message_of("x,y,reading\n1,1,1e308\n")
                .find("log.csv:2, column 'reading': 1e+308 is beyond +-1e+150"),
            std::string::npos);
  // The arena is 10 x 4 m from (-1, -2) in the map frame.
  EXPECT_NE(message_of("x,y,reading\n1,1,1\n1e300,1,1\n")
                .find("log.csv:3, column 'x': 1e+300 m lies more than the arena's larger side (10 "
                      "m) outside the map's arena (-1 to 9 m)"),
            std::string::npos);
  EXPECT_NE(message_of("x,y,reading,u,v\n1,1,1,0,-1e300\n").find("log.csv:2, column 'v'"),
            std::string::npos);
  // Outside the arena but within a side of it: read (the maps count it).
  EXPECT_EQ(message_of("x,y,reading\n-3,1,1\n"), "");
}

TEST(RunSamples, ReadsTheStepsOfALocalizeRun) {
  const auto dir = std::filesystem::temp_directory_path() / "plumekit-gdm-run-samples";
  std::filesystem::create_directories(dir);
  const auto file = dir / "run.json";
  std::ofstream(file) << R"({"steps": [{"recorded_position": [1, 0], "value": 7, "wind": [1, 0]},
                                      {"recorded_position": [2, 1], "value": 0, "wind": [0.5, 0.5]}]})";
  const auto s = run::read_run_samples(file, framed_arena());
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].position, (Vec2{2.0, 2.0}));
  EXPECT_EQ(s[0].reading, 7.0);
  EXPECT_EQ(*s[1].wind, (Vec2{0.5, 0.5}));
  std::ofstream(file) << R"({"steps": [{"recorded_position": [1, 0], "wind": [1, 0]}]})";
  try {
    run::read_run_samples(file, framed_arena());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("steps[0]"), std::string::npos) << e.what();
  }
  std::ofstream(file) << "{not json";
  EXPECT_THROW(run::read_run_samples(file, framed_arena()), InputError);
  std::filesystem::remove_all(dir);
}

std::string run_message(const std::string& json) {
  try {
    run::run_samples(run::parse_run_json(json, "run.json"), "run.json", framed_arena());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RunSamples, ATeamRunGivesEveryRobotsSteps) {
  // The top-level steps are the declaring robot's; the members hold every robot's.
  const auto s = run::run_samples(run::parse_run_json(R"({"steps": [{"recorded_position": [1, 0],
      "value": 7, "wind": [1, 0]}], "team": {"robots": 2, "members": [
      {"steps": [{"recorded_position": [1, 0], "value": 7, "wind": [1, 0]}]},
      {"steps": [{"recorded_position": [3, 1], "value": 2, "wind": [0, 1]},
                 {"recorded_position": [4, 1], "value": 3, "wind": [0, 1]}]}]}})",
                                                      "run.json"),
                                  "run.json", framed_arena());
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[1].position, (Vec2{4.0, 3.0}));
  EXPECT_EQ(s[2].reading, 3.0);
  EXPECT_NE(run_message(R"({"steps": [], "team": {"members": [{"steps": [{"recorded_position":
      [1, 0], "value": 1e308, "wind": [1, 0]}]}]}})")
                .find("run.json: team.members[0].steps[0], value: 1e+308 is beyond"),
            std::string::npos);
  EXPECT_NE(run_message(R"({"steps": [{"recorded_position": [1e300, 0], "value": 1,
      "wind": [1, 0]}]})")
                .find("run.json: steps[0], recorded_position[0]: 1e+300 m lies more than"),
            std::string::npos);
  EXPECT_NE(run_message(R"({"team": {"members": 3}})").find("no \"members\" list"),
            std::string::npos);
  EXPECT_NE(run_message("[1, 2]").find("not a JSON object"), std::string::npos);
  // A number beyond a double (found by fuzz_gdm_run): nlohmann's out_of_range, not a parse error.
  EXPECT_NE(
      run_message(R"({"steps": [{"recorded_position": [1e360, 0]}]})").find("run.json: not JSON"),
      std::string::npos);
}

TEST(RunMap, TheRecordedMapIsFoundFromTheRunsFolderOrRefused) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "plumekit-gdm-run-map";
  fs::create_directories(dir / "maps");
  fs::create_directories(dir / "runs" / "r1");
  std::ofstream(dir / "maps" / "a.json") << "{}";
  const fs::path run = dir / "runs" / "r1" / "run.json";
  // Recorded relative to the folder localize ran in (dir), found from the run's folders.
  EXPECT_EQ(run::find_run_map(nlohmann::json{{"map", "maps/a.json"}}, run, {}),
            dir / "maps" / "a.json");
  // A bare name (the map lay outside that folder): among the shipped maps.
  EXPECT_EQ(run::find_run_map(nlohmann::json{{"map", "a.json"}}, run, {dir / "maps"}),
            dir / "maps" / "a.json");
  try {
    run::find_run_map(nlohmann::json{{"map", "maps/gone.json"}}, run, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the run's map 'maps/gone.json' is not a file here"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(run::find_run_map(nlohmann::json::object(), run, {}), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::methods
