// STE commands refuse nonsense values with exit 2 (the library's checks).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace plumekit::test
