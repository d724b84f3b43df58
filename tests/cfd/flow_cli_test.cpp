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
  // Central convection stalls at nu = 0.001 on 20 cm cells (cfd/README.md, "Flow policy").
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
}

}  // namespace
