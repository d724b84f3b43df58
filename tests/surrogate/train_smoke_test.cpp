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
  // The strict 1e-4 criterion is the golden tests' (fixed files). Here the model and its pair
  // depend on this machine's PyTorch kernels, and a max-pool near-tie may send one decoder value to
  // another pixel in one engine and not the other (surrogate/README.md, "Max-pool near-ties"); so
  // all but 1 % of the values must agree within 1e-4 of the largest, and the rest stay bounded.
  double scale = 0, err = 0;
  for (float v : want.data)
    scale = std::max(scale, std::abs(double{v}));
  ASSERT_GT(scale, 0.0);
  std::size_t off = 0;
  for (std::size_t i = 0; i < want.data.size(); ++i) {
    const double e = std::abs(double{got.data[i]} - want.data[i]) / scale;
    err = std::max(err, e);
    off += e > 1e-4;
  }
  std::printf("trained model: max relative error %.3g, %zu of %zu values beyond 1e-4\n", err, off,
              want.data.size());
  EXPECT_LE(off, want.data.size() / 100);
  EXPECT_LT(err, 0.05);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::surrogate
