// `plumekit gdm`: maps from a CSV, scored against the true plume; bad input writes nothing.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"
#include "support/small_map.hpp"

namespace plumekit::test {
namespace {

class GdmCli : public CliTest {};

TEST_F(GdmCli, MapsACsvAndScoresItAgainstTheTruePlume) {
  const std::string map = write_small_map(dir);
  {
    std::ofstream csv(dir / "log.csv");
    csv << "x,y,reading,u,v\n";
    for (double x = 3.5; x < 6.0; x += 0.5)
      for (double y = 0.25; y < 3.0; y += 0.5)
        csv << x << ',' << y << ',' << (y < 1.0 ? 500.0 : 0.0) << ",1,0\n";
  }
  const CliResult r = run("gdm " + map + " --samples " + (dir / "log.csv").string() +
                          " --source 4.5,0.5 --cell 0.1 --wind-stretch 0.6 --out " +
                          (dir / "out").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["samples"], 30);
  EXPECT_GT(j["score"]["kl_distance"].get<double>(), 0.0);
  EXPECT_EQ(j["source_estimates"].size(), 6u);
  for (const char* f : {"mean.npy", "variance.npy", "confidence.npy", "gdm.png", "gdm.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
}

TEST_F(GdmCli, BadReadingsExitTwoAndWriteNothing) {
  const std::string map = write_small_map(dir);
  std::ofstream(dir / "bad.csv") << "x,y,reading\n1,1,5\n2,1,nan\n";
  const CliResult r = run("gdm " + map + " --samples " + (dir / "bad.csv").string() + " --out " +
                          (dir / "out").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bad.csv:3, column 'reading'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  const CliResult none = run("gdm " + map + " --out " + (dir / "out").string());
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("--samples"), std::string::npos) << none.err;
}

}  // namespace
}  // namespace plumekit::test
