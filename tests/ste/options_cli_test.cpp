// STE commands refuse nonsense values with exit 2 (the library's checks).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"

namespace plumekit::test {
namespace {

class SteOptionsCli : public CliTest {};

TEST_F(SteOptionsCli, NanNoiseExitsTwo) {
  const auto map = std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json";
  const CliResult r =
      run("localize " + map + " --source 1.5,1.0 --plume-model gaussian --noise nan --out " +
          (dir / "out").string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("got nan"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

// Issue 47's flags: a stop of no length, a negative tolerance or a window of none are refused
// naming the flag, before any work, and nothing is written.
TEST_F(SteOptionsCli, ReadingWhileMovingAndAdaptiveStopFlagsAreChecked) {
  const auto map = std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json";
  for (const auto& [flag, value] : std::vector<std::pair<std::string, std::string>>{
           {"--stop-min-s", "0"}, {"--stop-tolerance", "-1"}, {"--passing-window", "0"}}) {
    const CliResult r = run("localize " + map + " --source 1.5,1.0 --plume-model physics " + flag +
                            " " + value + " --out " + (dir / "out").string());
    EXPECT_EQ(r.code, 2) << flag << ": " << r.err;
    EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << flag;
  }
}

// --protocol: the default is moving; thesis turns both halves off; a half given on the command
// line wins over the preset wherever it stands; an unknown name is refused naming the flag.
TEST_F(SteOptionsCli, TheProtocolPresetAndItsHalves) {
  const auto map = std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json";
  const std::string base =
      "localize " + map + " --source 1.5,1.0 --plume-model physics --max-samples 2 --json ";
  const auto sampling = [&](const std::string& flags) {
    const CliResult r = run(base + flags);
    EXPECT_EQ(r.code, 0) << flags << ": " << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    if (!j.contains("protocol")) return std::string("thesis, unrecorded");
    std::string bits;
    for (const char* key : {"read_while_moving", "adaptive_stops", "approach"})
      bits += j[key].get<bool>() ? "1" : "0";
    return j["protocol"].get<std::string>() + " " + bits +
           (j["confidence_radius"].get<double>() > 0.0 ? " confident" : "");
  };
  EXPECT_EQ(sampling(""), "moving 111 confident");
  EXPECT_EQ(sampling("--protocol thesis"), "thesis, unrecorded");
  EXPECT_EQ(sampling("--protocol thesis --adaptive-stops true"), "thesis 010");
  EXPECT_EQ(sampling("--adaptive-stops true --protocol thesis"), "thesis 010");
  EXPECT_EQ(sampling("--read-while-moving false --confidence-radius 0"), "moving 011");
  EXPECT_EQ(sampling("--protocol thesis --approach true --confidence-radius 0.5"),
            "thesis 001 confident");
  const CliResult bad = run(base + "--protocol drive-by --out " + (dir / "out").string());
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--protocol"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace plumekit::test
