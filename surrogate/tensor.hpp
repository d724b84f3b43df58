#pragma once
// A plain NCHW float32 tensor: four sizes and one contiguous buffer that the caller owns.
#include <cstddef>
#include <vector>

namespace plumekit::surrogate {

struct Tensor {
  int n = 0, c = 0, h = 0, w = 0;
  std::vector<float> data;  // index ((i * c + k) * h + y) * w + x

  Tensor() = default;
  Tensor(int n_, int c_, int h_, int w_)
      : n(n_), c(c_), h(h_), w(w_), data(static_cast<std::size_t>(n_) * c_ * h_ * w_, 0.0f) {}

  std::size_t plane() const { return static_cast<std::size_t>(h) * w; }
  std::size_t sample() const { return plane() * c; }
  float* sample_data(int i) { return data.data() + sample() * i; }
  const float* sample_data(int i) const { return data.data() + sample() * i; }
  float& at(int i, int k, int y, int x) {
    return data[((static_cast<std::size_t>(i) * c + k) * h + y) * w + x];
  }
  float at(int i, int k, int y, int x) const {
    return data[((static_cast<std::size_t>(i) * c + k) * h + y) * w + x];
  }
};

}  // namespace plumekit::surrogate
