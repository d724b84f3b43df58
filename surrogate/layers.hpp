#pragma once
// The engine's operators on one sample, CHW float32 (a batch runs them per sample). Each writes
// into a buffer the caller sized, so a forward pass allocates nothing once its workspace has grown.
#include <cstdint>
#include <vector>

namespace plumekit::surrogate {

// A convolution ready to run: weights as a row-major [out, in*k*k] matrix. A stride-1 transposed
// convolution becomes one of these with its kernel flipped, in/out swapped and padding k-1-p.
struct Conv {
  int in = 0, out = 0, kernel = 0, padding = 0;
  bool relu = false;
  std::vector<float> weight;  // [out][in][k][k]
  std::vector<float> bias;    // [out]
  // The weights as the direct convolution reads them (pack()): [out / block][in][k][k][block].
  std::vector<float> packed;

  int block() const;  // output channels computed together: 4, or 1 for a single channel
  void pack();

  int out_size(int size) const { return size + 2 * padding - kernel + 1; }
};

// PyTorch Conv2d weight [out, in, k, k].
Conv make_conv2d(int in, int out, int kernel, int padding, bool relu, const std::vector<float>& w,
                 const std::vector<float>& b);
// PyTorch ConvTranspose2d (stride 1) weight [in, out, k, k].
Conv make_conv_transpose2d(int in, int out, int kernel, int padding, bool relu,
                           const std::vector<float>& w, const std::vector<float>& b);

// y[out, h', w'] = act(conv(x, W) + b), a direct convolution; `scratch` (grown as needed) holds
// the zero-padded input and the unclipped output.
void conv_forward(const Conv& conv, const float* x, int h, int w, float* y,
                  std::vector<float>& scratch);

// 2x2 stride-2 max-pool (floor of odd sizes, like PyTorch). `index` gets the argmax as y*w+x in the
// input plane; ties go to the first in row-major window order, as PyTorch's CPU kernel does.
void max_pool2x2(const float* x, int c, int h, int w, float* y, std::int32_t* index);

// Inverse of max_pool2x2 onto an h x w plane: zeros except y[index] = x.
void max_unpool2x2(const float* x, const std::int32_t* index, int c, int ph, int pw, int h, int w,
                   float* y);

}  // namespace plumekit::surrogate
