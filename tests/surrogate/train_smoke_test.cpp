// End to end: a small synthetic dataset, a few training steps of surrogate/train/train.py (with
// Debian's PyTorch), then the engine loads the model file and reproduces the trainer's golden pair.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/npy.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {
namespace {

namespace fs = std::filesystem;

Tensor to_tensor(const NpyArray& a) {
  Tensor t(static_cast<int>(a.shape.at(0)), static_cast<int>(a.shape.at(1)),
           static_cast<int>(a.shape.at(2)), static_cast<int>(a.shape.at(3)));
  std::transform(a.values.begin(), a.values.end(), t.data.begin(),
                 [](double v) { return static_cast<float>(v); });
  return t;
}

TEST(TrainSmoke, TrainsAFewStepsAndTheEngineLoadsTheModel) {
  const fs::path dir =
      fs::temp_directory_path() / ("plumekit-train-smoke-" + std::to_string(getpid()));
  fs::remove_all(dir);
  const std::string py =
      std::string(PLUMEKIT_PYTHON) + " " + PLUMEKIT_SOURCE_DIR + "/surrogate/train/";
  const std::string data = (dir / "data").string(), work = (dir / "work").string();
  const std::string model = (dir / "model.pkcnn").string();
  ASSERT_EQ(std::system((py + "synthetic_dataset.py " + data + " --maps 3 --per-map 4").c_str()),
            0);
  const std::string train = py + "train.py --data " + data + " --work " + work + " --out " + model +
                            " --batch 4 --threads 2 --max-steps ";
  ASSERT_EQ(std::system((train + "4").c_str()), 0);
  // Rerunning resumes from the checkpoint and goes on to step 6.
  ASSERT_EQ(std::system((train + "6").c_str()), 0);
  EXPECT_TRUE(fs::exists(fs::path(work) / "log.csv"));

  const Network net = Network::load(model);
  EXPECT_EQ(net.parameter_count(), 600130u);
  const Tensor input = to_tensor(read_npy(dir / "model_input.npy"));
  const Tensor want = to_tensor(read_npy(dir / "model_output.npy"));
  const Tensor got = net.predict(input);
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < want.data.size(); ++i) {
    err = std::max(err, std::abs(double{got.data[i]} - want.data[i]));
    scale = std::max(scale, std::abs(double{want.data[i]}));
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(err / scale, 1e-4);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::surrogate
