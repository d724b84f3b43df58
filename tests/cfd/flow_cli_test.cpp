// End-to-end tests of `plumekit flow`: outputs, JSON, exit codes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "cfd/options.hpp"
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

TEST_F(FlowCli, ReportsTheSchemeUsedAndFallsBackOnlyWhenAllowed) {
  // Central convection stalls at nu = 0.001 on 20 cm cells (docs/design/flow-solver.md, "Flow
  // policy").
  const std::string args = "flow " + (kMaps / "cluttered-1.json").string() +
                           " --cell 0.2 --nu 0.001 --out " + (dir / "wind").string();
  auto r = run(args + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["convection"], "upwind");
  EXPECT_EQ(j["convection_requested"], "central");
  EXPECT_EQ(j["fell_back_to_upwind"], true);
  r = run(args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("upwind convection (central did not converge: fell back to upwind)"),
            std::string::npos)
      << r.out;
  r = run(args + " --upwind-fallback false");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("central convection"), std::string::npos) << r.err;

  r = run("flow " + (kMaps / "cluttered-1.json").string() + " --cell 0.2 --out " +
          (dir / "plain").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["convection"], "central");
  EXPECT_EQ(j["fell_back_to_upwind"], false);
}

TEST_F(FlowCli, HelpShowsTheLibraryDefaults) {
  const plumekit::cfd::FlowOptions o;
  auto shown = [](const char* flag, const char* type, auto value) {
    std::ostringstream s;
    s << flag << ' ' << type << '=' << value;
    return s.str();
  };
  const auto r = run("flow --help");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const std::string& expected :
       {shown("--cell", "FLOAT", o.cell), shown("--nu", "FLOAT", o.nu),
        shown("--turbulence", "TEXT", to_string(o.turbulence)),
        shown("--convection", "TEXT", to_string(o.convection)),
        shown("--upwind-fallback", "BOOLEAN", o.upwind_fallback ? "true" : "false"),
        shown("--tol", "FLOAT", o.tolerance), shown("--max-iter", "INT", o.max_iterations),
        shown("--linear-solver", "TEXT", to_string(o.linear_solver))})
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << " not in:\n" << r.out;
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
      {"--convection quick", "--convection: unknown name 'quick'"},
      {"--linear-solver lu", "--linear-solver: unknown name 'lu'"},
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

namespace {

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(FlowCli, PlumeAndLocalizeUseAFlowOutputAsTheirWind) {
  const std::string map = (kMaps / "cluttered-3.json").string();
  const fs::path wind = dir / "wind";
  auto r = run("flow " + map + " --cell 0.1 --out " + wind.string());
  ASSERT_EQ(r.code, 0) << r.err;
  // The wind read back is the one solved: the same plume, byte for byte.
  r = run("plume " + map + " --source 1,2 --cell 0.1 --out " + (dir / "solved").string());
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("plume " + map + " --source 1,2 --wind " + wind.string() + " --out " +
          (dir / "read").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(file_bytes(dir / "solved" / "mean.npy"), file_bytes(dir / "read" / "mean.npy"));

  const std::string localize = "localize " + map +
                               " --source 8,2 --start 1,1 --plume-model gaussian " +
                               "--max-samples 15 --json ";
  r = run(localize + "--cell 0.1");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto solved = nlohmann::json::parse(r.out);
  r = run(localize + "--wind " + wind.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto read = nlohmann::json::parse(r.out);
  EXPECT_EQ(solved["estimate"], read["estimate"]);
  EXPECT_EQ(solved["samples"], read["samples"]);

  // Another map's wind: exit 2, naming the file and the field, and no output.
  r = run("plume " + (kMaps / "cluttered-1.json").string() + " --source 1,2 --wind " +
          wind.string() + " --out " + (dir / "other").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find((wind / "wind.json").string() + ": map_sha256"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "other"));

  // A changed u.npy (listed in wind.json, not read for the wind): exit 2 naming it, no output.
  std::string u = file_bytes(wind / "u.npy");
  u[u.size() - 1] ^= 0x01;
  std::ofstream(wind / "u.npy", std::ios::binary) << u;
  r = run("plume " + map + " --source 1,2 --wind " + wind.string() + " --out " +
          (dir / "damaged").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find((wind / "u.npy").string() + ": does not match its SHA-256"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "damaged"));
}

}  // namespace

namespace {

// A 10 x 4 m arena with a 4 cm wall x in [5.06, 5.10] up to y = 3: 10 cm cells
// have no centre in it (the flow runs through it), 5 cm cells do.
const char* const kThinWallMap = R"({"format": "plumekit-map/1", "name": "thin", "size": [10, 4],
  "inlet": {"side": "left", "speed": 1}, "outlet": {"side": "right"},
  "obstacles": [[[5.06, 0], [5.1, 0], [5.1, 3], [5.06, 3]]]})";

TEST_F(FlowCli, WarnsOfAWallTheGridLetsAirThrough) {
  const fs::path map = dir / "thin.json";
  std::ofstream(map) << kThinWallMap;
  const fs::path out = dir / "wind";
  auto r = run("flow " + map.string() + " --cell 0.1 --json --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("plumekit: warning: the 0.1 m cells do not resolve 1 obstacle, so air "
                       "flows through it where the planner sees a wall: obstacles[0] at (5.1, "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("0.04 m thick (30 cell faces through it); a cell of 0.04 m or finer "
                       "resolves it"),
            std::string::npos)
      << r.err;
  for (const auto& j : {nlohmann::json::parse(r.out),
                        nlohmann::json::parse(plumekit::test::slurp(out / "wind.json"))}) {
    ASSERT_TRUE(j.contains("thin_walls")) << j.dump();
    EXPECT_EQ(j["thin_walls"]["count"], 1);
    EXPECT_EQ(j["thin_walls"]["walls"][0]["obstacle"], 0);
    EXPECT_NEAR(j["thin_walls"]["walls"][0]["thickness"].get<double>(), 0.04, 1e-12);
    EXPECT_NEAR(j["thin_walls"]["cell_resolving_them"].get<double>(), 0.04, 1e-12);
  }
  // Resolved at 5 cm: no warning, no field.
  r = run("flow " + map.string() + " --cell 0.05 --json --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_FALSE(nlohmann::json::parse(r.out).contains("thin_walls"));
}

// A huge arena's default cell is coarse: an opening shorter than a cell gets
// no cell, which is the grid's fault, not the map's.
TEST_F(FlowCli, SaysTheCellIsTooCoarseWhenAnOpeningIsShorterThanACell) {
  const fs::path map = dir / "huge.json";
  std::ofstream(map) << R"({"format": "plumekit-map/1", "name": "huge", "size": [1e6, 1e6],
    "inlet": {"side": "left", "from": 0, "to": 2, "speed": 1},
    "outlet": {"side": "right", "from": 0, "to": 2}})";
  const fs::path out = dir / "wind";
  const auto r = run("flow " + map.string() + " --out " + out.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--cell: 1500 m cells (the default on a 1e+06 x 1e+06 m arena) are too "
                       "coarse for this map: the inlet is 2 m long, shorter than a cell, so no "
                       "cell opens onto it"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("a cell of 2 m or finer opens onto every opening, but gives 2.5e+11 "
                       "cells, more than a solve here can take"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("no free path"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
