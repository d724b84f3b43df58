// `plumekit predict` end to end, with the randomly initialised golden model (never the shipped
// one): the files hold PlumeNetwork's prediction in the documented layout; every kind of bad input
// exits 2 and writes nothing.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/npy.hpp"
#include "map/map_json.hpp"
#include "support/cli_runner.hpp"
#include "surrogate/plume_network.hpp"

namespace plumekit::surrogate {
namespace {

namespace fs = std::filesystem;
using Result = test::CliResult;
class Predict : public test::CliTest {};

const fs::path kModel = fs::path(PLUMEKIT_TEST_DATA) / "surrogate" / "real.pkcnn";
const fs::path kOdd = fs::path(PLUMEKIT_TEST_DATA) / "surrogate" / "odd.pkcnn";
const fs::path kMap = fs::path(PLUMEKIT_DATA_DIR) / "maps" / "cluttered-1.json";

std::string predict_args(const fs::path& out, const std::string& source,
                         const fs::path& model = kModel, const fs::path& map = kMap) {
  return "predict " + map.string() + " --cnn " + model.string() + " --source " + source +
         " --out " + out.string();
}

TEST_F(Predict, WritesThePlumeNetworksPrediction) {
  const fs::path out = dir / "plume";
  const Result r = run(predict_args(out, "1.5,1.0") + " --json --threads 2");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], true);
  EXPECT_EQ(j["source"], nlohmann::json::array({1.5, 1.0}));
  EXPECT_EQ(j["grid"], nlohmann::json::array({64, 64}));

  const Map map = read_map(kMap);
  const PlumeNetwork model(std::make_shared<const Network>(Network::load(kModel)), map);
  const PlumePrediction p = model.predict({1.5, 1.0});
  const NpyArray mean = read_npy(out / "mean.npy"), std = read_npy(out / "std.npy");
  ASSERT_EQ(mean.shape, (std::vector<std::size_t>{64, 64}));
  ASSERT_EQ(std.shape, (std::vector<std::size_t>{64, 64}));
  for (std::size_t k = 0; k < p.mean.size(); ++k) {
    ASSERT_EQ(static_cast<float>(mean.values[k]), p.mean[k]) << k;
    ASSERT_EQ(static_cast<float>(std.values[k]), p.std[k]) << k;
  }
  // Row 0 at y = 0: the cell holding the peak is where the summary says the peak is.
  const auto peak = std::max_element(mean.values.begin(), mean.values.end()) - mean.values.begin();
  EXPECT_FLOAT_EQ(j["peak_mean"].get<double>(), mean.values[peak]);
  const Vec2 at = p.grid.centre(static_cast<int>(peak % 64), static_cast<int>(peak / 64));
  EXPECT_DOUBLE_EQ(j["peak_mean_at"][0].get<double>(), at.x);
  EXPECT_DOUBLE_EQ(j["peak_mean_at"][1].get<double>(), at.y);
  EXPECT_GT(j["peak_mean"].get<double>(), 0.0);

  const cv::Mat png = cv::imread((out / "plume.png").string());
  ASSERT_FALSE(png.empty());
  EXPECT_GT(png.rows, png.cols / 2);  // two panels, mean above std

  // Run again into the same directory: an earlier prediction is replaced.
  const Result again = run(predict_args(out, "2.0,3.0"));
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_NE(read_npy(out / "mean.npy").values, mean.values);
}

// A hybrid residual model (issue 46, the golden hybrid.pkcnn): the map's wind solved as the
// command solves it, the physics plume of the source in it, the mean the network's plus that
// plume: the files hold PlumeNetwork's prediction, finite, and the plume carries the peak.
TEST_F(Predict, AHybridModelPredictsThePhysicsPlumePlusItsResidual) {
  const fs::path out = dir / "hybrid";
  const fs::path map_file = fs::path(PLUMEKIT_DATA_DIR) / "test-maps" / "test-1-block.json";
  const fs::path hybrid = fs::path(PLUMEKIT_TEST_DATA) / "surrogate" / "hybrid.pkcnn";
  const Result r = run(predict_args(out, "2.0,2.0", hybrid, map_file) + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["grid"], nlohmann::json::array({20, 50}));
  const Map map = read_map(map_file);
  const cfd::WindField wind = model_wind(map);
  const PlumeNetwork model(std::make_shared<const Network>(Network::load(hybrid)), map, &wind);
  const PlumePrediction p = model.predict({2.0, 2.0});
  const NpyArray mean = read_npy(out / "mean.npy");
  ASSERT_EQ(mean.shape, (std::vector<std::size_t>{20, 50}));
  for (std::size_t k = 0; k < p.mean.size(); ++k) {
    ASSERT_TRUE(std::isfinite(mean.values[k])) << k;
    ASSERT_EQ(static_cast<float>(mean.values[k]), p.mean[k]) << k;
  }
  // The physics plume of a release of 1000 dominates the random network's residual (tens).
  EXPECT_GT(j["peak_mean"].get<double>(), 500.0);
}

TEST_F(Predict, BadInputExitsTwoAndWritesNothing) {
  fs::copy_file(kModel, dir / "truncated.pkcnn");
  fs::resize_file(dir / "truncated.pkcnn", fs::file_size(kModel) - 100);
  const std::pair<std::string, std::string> cases[] = {
      {predict_args(dir / "out", "4.5,1.6"), "--source: (4.5, 1.6) is inside obstacles[0]"},
      {predict_args(dir / "out", "10.5,1"), "--source: (10.5, 1) is outside the arena (0...10"},
      {predict_args(dir / "out", "1.5:1"), "--source: expected a point X,Y"},
      {predict_args(dir / "out", "1.5,1", dir / "truncated.pkcnn"), "truncated"},
      {predict_args(dir / "out", "1.5,1", dir / "missing.pkcnn"), "no such model file"},
      {predict_args(dir / "out", "1.5,1", kOdd), "the model's grid is 21x30"},
      {predict_args(dir / "out", "1.5,1", kModel, dir / "missing.json"), "missing.json"},
  };
  for (const auto& [args, message] : cases) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir / "out")) << args;
  }
  // Nothing else either (no temporaries left behind).
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir))
    left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"truncated.pkcnn"});
}

TEST_F(Predict, RefusesToReplaceADirectoryHoldingOtherFiles) {
  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "notes.txt") << "keep me";
  const Result r = run(predict_args(dir / "mine", "1.5,1"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("holds files plumekit did not write (notes.txt)"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(dir / "mine" / "notes.txt"));
  EXPECT_FALSE(fs::exists(dir / "mine" / "mean.npy"));
}

TEST_F(Predict, MissingDefaultModelIsAClearError) {
  // A data folder with the shipped maps but no models/.
  fs::create_directories(dir / "data");
  fs::copy(fs::path(PLUMEKIT_DATA_DIR) / "maps", dir / "data" / "maps");
  ::setenv("PLUMEKIT_DATA", (dir / "data").c_str(), 1);
  const Result r = run("predict --source 1.5,1 --out " + (dir / "out").string() + " --json");
  ::unsetenv("PLUMEKIT_DATA");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("models/plume-unet-v3.pkcnn: no such model file (the shipped model"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["exit_code"], 2);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(Predict, HelpExitsZero) {
  const Result r = run("predict --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("--source"), std::string::npos);
}

}  // namespace
}  // namespace plumekit::surrogate
