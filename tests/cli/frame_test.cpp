// A map with a frame (plumekit-map/2 `frame.origin`): every coordinate typed
// on the command line and every one reported is in the map's frame. The same
// map with and without a frame gives the same runs, shifted by the origin.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.hpp"

namespace plumekit::test {
namespace {

using nlohmann::json;

// The small test room, once in its own frame and once moved to (100, -50):
// every coordinate is a multiple of 1/4, so the shift is exact in doubles.
std::string room(double ox, double oy) {
  auto p = [&](double x, double y) {
    std::ostringstream s;
    s << '[' << x + ox << ", " << y + oy << ']';
    return s.str();
  };
  std::ostringstream s;
  s << R"({"format": "plumekit-map/2", "name": "room", "frame": {"origin": )" << p(0, 0)
    << R"(}, "size": [6.0, 3.0], "openings": [)"
    << R"({"kind": "inlet", "from": )" << p(0, 0) << R"(, "to": )" << p(0, 3) << R"(, "speed": 1},)"
    << R"({"kind": "outlet", "from": )" << p(6, 0) << R"(, "to": )" << p(6, 3) << "}],"
    << R"("obstacles": [[)" << p(2.5, 1) << ',' << p(3, 1) << ',' << p(3, 2) << ',' << p(2.5, 2)
    << "]], "
    << R"("sources": [)" << p(4.5, 0.5) << ',' << p(1.5, 0.75) << "]}";
  return s.str();
}

class Frame : public CliTest {
 protected:
  std::string write(const std::string& name, double ox, double oy) {
    std::filesystem::create_directories(dir / name);
    const auto path = dir / name / "room.json";
    std::ofstream(path) << room(ox, oy);
    return path.string();
  }
  static void expect_shifted(const json& framed, const json& plain, double ox, double oy) {
    ASSERT_EQ(framed.size(), 2u);
    EXPECT_NEAR(framed[0].get<double>(), plain[0].get<double>() + ox, 1e-9);
    EXPECT_NEAR(framed[1].get<double>(), plain[1].get<double>() + oy, 1e-9);
  }
};

TEST_F(Frame, LocalizeTakesAndReportsMapFramePositions) {
  const std::string plain = write("plain", 0, 0), framed = write("framed", 100, -50);
  const std::string opts = " --plume-model gaussian --max-samples 4 --json";
  const CliResult a = run("localize " + plain + " --source 4.5,0.5 --start 1,2.5" + opts);
  const CliResult b = run("localize " + framed + " --source 104.5,-49.5 --start 101,-47.5" + opts);
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const json ja = json::parse(a.out), jb = json::parse(b.out);
  for (const char* key : {"source", "start", "estimate", "map_estimate"})
    expect_shifted(jb[key], ja[key], 100, -50);
  EXPECT_DOUBLE_EQ(jb["error_m"].get<double>(), ja["error_m"].get<double>());
  ASSERT_EQ(ja["steps"].size(), jb["steps"].size());
  for (std::size_t k = 0; k < ja["steps"].size(); ++k)
    expect_shifted(jb["steps"][k]["position"], ja["steps"][k]["position"], 100, -50);
}

TEST_F(Frame, APointOutsideTheFramedArenaIsRefusedInTheMapsTerms) {
  const std::string framed = write("framed", 100, -50);
  const CliResult r = run("localize " + framed + " --source 4.5,0.5 --plume-model gaussian");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("(4.5, 0.5) is outside the arena (100...106 x -50...-47)"),
            std::string::npos)
      << r.err;
}

// predict's refusals and the surrogate's training-range notes name map-frame points too.
TEST_F(Frame, PredictSpeaksInTheMapFrame) {
  const std::string framed = write("framed", 100, -50);
  {  // an inlet faster than the v2 model's training range (0.33-1.99 m/s)
    std::string text = slurp(framed);
    text.replace(text.find(R"("speed": 1)"), 10, R"("speed": 3)");
    std::ofstream(framed) << text;
  }
  const std::string v2 = std::string(PLUMEKIT_DATA_DIR) + "/models/plume-unet-v2.pkcnn";
  const std::string out = (dir / "out").string();
  CliResult r = run("predict " + framed + " --cnn " + v2 + " --source 102.75,-48.5 --out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--source: (102.75, -48.5) is inside obstacles[0] of map room"),
            std::string::npos)
      << r.err;
  r = run("predict " + framed + " --cnn " + v2 + " --source 4.5,0.5 --out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("(4.5, 0.5) is outside the arena (100...106 x -50...-47)"),
            std::string::npos)
      << r.err;
  r = run("predict " + framed + " --cnn " + v2 + " --source 104.5,-49.5 --out " + out + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string warnings = json::parse(r.out)["warnings"].dump();
  EXPECT_NE(warnings.find("the inlet at (100, -50) blows at 3 m/s"), std::string::npos) << warnings;
}

TEST_F(Frame, PlanPathsAreInTheMapFrame) {
  const std::string plain = write("plain", 0, 0), framed = write("framed", 100, -50);
  const CliResult a = run("plan " + plain + " --from 1,1.5 --to 5,1.5 --json");
  const CliResult b = run("plan " + framed + " --from 101,-48.5 --to 105,-48.5 --json");
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const json ja = json::parse(a.out), jb = json::parse(b.out);
  ASSERT_EQ(ja["path"].size(), jb["path"].size());
  for (std::size_t k = 0; k < ja["path"].size(); ++k)
    expect_shifted(jb["path"][k], ja["path"][k], 100, -50);
  EXPECT_NEAR(jb["length_m"].get<double>(), ja["length_m"].get<double>(), 1e-9);
}

TEST_F(Frame, EvaluateWritesMapFramePositionsToRunsCsv) {
  write("plain", 0, 0);
  write("framed", 100, -50);
  const std::string opts = " --plume-model gaussian --runs 1 --max-samples 3 --threads 1";
  ASSERT_EQ(run("evaluate --map-dir " + (dir / "plain").string() + " --out " +
                (dir / "out-plain").string() + opts)
                .code,
            0);
  ASSERT_EQ(run("evaluate --map-dir " + (dir / "framed").string() + " --out " +
                (dir / "out-framed").string() + opts)
                .code,
            0);
  auto rows = [](const std::filesystem::path& csv) {
    std::ifstream in(csv);
    std::vector<std::vector<std::string>> out;
    for (std::string line; std::getline(in, line);) {
      std::vector<std::string> cells;
      std::stringstream s(line);
      for (std::string cell; std::getline(s, cell, ',');)
        cells.push_back(cell);
      out.push_back(cells);
    }
    return out;
  };
  const auto a = rows(dir / "out-plain" / "runs.csv"), b = rows(dir / "out-framed" / "runs.csv");
  ASSERT_EQ(a.size(), 3u);  // the header and one run of each of the two sources
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t r = 1; r < a.size(); ++r)
    for (int c = 3; c <= 8; ++c)  // source, start and estimate x, y
      EXPECT_NEAR(std::stod(b[r][c]), std::stod(a[r][c]) + (c % 2 ? 100 : -50), 1e-4)
          << "row " << r << " column " << a[0][c];
}

}  // namespace
}  // namespace plumekit::test
