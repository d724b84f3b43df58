// STE commands refuse nonsense values with exit 2 (the library's checks).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

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
    const CliResult r =
        run("localize " + map + " --source 1.5,1.0 --plume-model physics --read-while-moving " +
            "--adaptive-stops " + flag + " " + value + " --out " + (dir / "out").string());
    EXPECT_EQ(r.code, 2) << flag << ": " << r.err;
    EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << flag;
  }
}

}  // namespace
}  // namespace plumekit::test
