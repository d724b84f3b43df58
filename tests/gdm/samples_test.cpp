// The readers of readings: a user's CSV and a localize run.json, and their faults.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/map.hpp"
#include "gdm/samples.hpp"

namespace plumekit::gdm {
namespace {

// A 10 x 4 m arena whose lower-left corner is at (-1, -2) in the map frame.
Map framed_arena() {
  Map m = default_arena(10.0, 4.0);
  m.frame.origin = {-1.0, -2.0};
  return m;
}

std::string message_of(const std::string& text) {
  try {
    parse_samples_csv(text, "log.csv", framed_arena());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SamplesCsv, ReadsColumnsInAnyOrderInTheMapFrame) {
  const auto s = parse_samples_csv("# a robot's log\nreading, y, x\n\n12.5, 0, 1\n0,1.5,-0.5\n",
                                   "log.csv", framed_arena());
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].position, (Vec2{2.0, 2.0}));
  EXPECT_EQ(s[0].reading, 12.5);
  EXPECT_FALSE(s[0].wind.has_value());
  EXPECT_EQ(s[1].position, (Vec2{0.5, 3.5}));
  const auto w =
      parse_samples_csv("x,y,reading,u,v\r\n1,0,3,0.5,-0.25\r\n", "w.csv", framed_arena());
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

TEST(RunSamples, ReadsTheStepsOfALocalizeRun) {
  const auto dir = std::filesystem::temp_directory_path() / "plumekit-gdm-run-samples";
  std::filesystem::create_directories(dir);
  const auto file = dir / "run.json";
  std::ofstream(file) << R"({"steps": [{"recorded_position": [1, 0], "value": 7, "wind": [1, 0]},
                                      {"recorded_position": [2, 1], "value": 0, "wind": [0.5, 0.5]}]})";
  const auto s = read_run_samples(file, framed_arena());
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].position, (Vec2{2.0, 2.0}));
  EXPECT_EQ(s[0].reading, 7.0);
  EXPECT_EQ(*s[1].wind, (Vec2{0.5, 0.5}));
  std::ofstream(file) << R"({"steps": [{"recorded_position": [1, 0], "wind": [1, 0]}]})";
  try {
    read_run_samples(file, framed_arena());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("steps[0]"), std::string::npos) << e.what();
  }
  std::ofstream(file) << "{not json";
  EXPECT_THROW(read_run_samples(file, framed_arena()), InputError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::gdm
