// Resource guards from the command line: a flow that would not fit in memory
// and a map too big to rasterize at 5 cm are answered at once, with exit 2 and
// the setting that fits (flow), or a bounded check (map validate).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "support/cli_runner.hpp"

namespace plumekit::test {
namespace {

class LimitsCli : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    // The same limit on every machine (the default is half its memory).
    setenv("PLUMEKIT_MAX_MEMORY", "8G", 1);
  }
  void TearDown() override {
    unsetenv("PLUMEKIT_MAX_MEMORY");
    CliTest::TearDown();
  }
  std::string square_map(double side) {
    const auto p = dir / "square.json";
    std::ofstream(p)
        << R"({"format": "plumekit-map/1", "name": "square", "size": [)" << side << ", " << side
        << R"(], "inlet": {"side": "left", "speed": 1.0}, "outlet": {"side": "right"}})";
    return p.string();
  }
};

TEST_F(LimitsCli, FlowOnAHundredMetreMapIsRefusedAtOnceWithTheCellThatFits) {
  const std::string map = square_map(100.0);
  // 5 cm asked for: the default cell would be 0.15 m on this arena (cfd/options.hpp).
  const CliResult r = run("flow " + map + " --cell 0.05 --out " + (dir / "out").string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("2000 x 2000 cells of 0.05 m needs about"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("limit of 8.0 GiB"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" m fits)"), std::string::npos) << r.err;
}

TEST_F(LimitsCli, MapValidateOfAHugeArenaIsQuickAndBounded) {
  const std::string map = square_map(1e6);
  // Checked on a coarsened grid (map/rasterize.hpp, map_grid_check), which
  // says so; a 5 cm rasterization would need 4e14 cells.
  const CliResult r = run("map validate " + map + " --json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("too large to check at 5 cm"), std::string::npos) << r.out;
}

TEST_F(LimitsCli, RenderWithNanScaleExitsTwo) {
  const CliResult r =
      run("map render " + square_map(10.0) + " --px-per-m nan --out " + (dir / "m.png").string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.png"));
}

}  // namespace
}  // namespace plumekit::test
