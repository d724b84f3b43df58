#include "surrogate/layers.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace plumekit::surrogate {
namespace {
using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
}

Conv make_conv2d(int in, int out, int kernel, int padding, bool relu, const std::vector<float>& w,
                 const std::vector<float>& b) {
  return Conv{in, out, kernel, padding, relu, w, b};
}

Conv make_conv_transpose2d(int in, int out, int kernel, int padding, bool relu,
                           const std::vector<float>& w, const std::vector<float>& b) {
  // y[o](p) = sum_i,k x[i](p + pad - k) W[i][o][k] equals a convolution with kernel
  // W'[o][i][k'] = W[i][o][K-1-k'] and padding K-1-pad.
  Conv c{in, out, kernel, kernel - 1 - padding, relu, std::vector<float>(w.size()), b};
  const int kk = kernel * kernel;
  for (int i = 0; i < in; ++i) {
    for (int o = 0; o < out; ++o) {
      for (int k = 0; k < kk; ++k) {
        c.weight[(static_cast<std::size_t>(o) * in + i) * kk + k] =
            w[(static_cast<std::size_t>(i) * out + o) * kk + (kk - 1 - k)];
      }
    }
  }
  return c;
}

void conv_forward(const Conv& conv, const float* x, int h, int w, float* y,
                  std::vector<float>& col) {
  const int k = conv.kernel, pad = conv.padding;
  const int oh = conv.out_size(h), ow = conv.out_size(w);
  const std::size_t pixels = static_cast<std::size_t>(oh) * ow;
  const std::size_t rows = static_cast<std::size_t>(conv.in) * k * k;
  // Bands of output rows small enough that their column matrix stays in cache between im2col and
  // the GEMM. With 8 output channels each column entry is used only 8 times, so a whole-plane
  // column matrix (6.5 MB for 16 channels at 64x64) made the GEMM memory-bound. 512 KiB measured
  // best of 64 KiB..2 MiB here (2 MiB of L2 per core): 1.5x faster at batch 1.
  constexpr std::size_t kBandBytes = 512 * 1024;
  const int band = std::clamp(
      static_cast<int>(kBandBytes / (sizeof(float) * rows * std::max(ow, 1))), 1, std::max(oh, 1));
  const std::size_t band_pixels = static_cast<std::size_t>(band) * ow;
  if (col.size() < rows * band_pixels) col.resize(rows * band_pixels);
  Eigen::Map<const RowMatrix> weight(conv.weight.data(), conv.out, static_cast<Eigen::Index>(rows));

  for (int oy0 = 0; oy0 < oh; oy0 += band) {
    const int oy1 = std::min(oh, oy0 + band);
    const std::size_t cp = static_cast<std::size_t>(oy1 - oy0) * ow;
    // im2col, row (i, ky, kx) holds x[i](oy + ky - pad, ox + kx - pad) for the band's pixels:
    // each output row is one contiguous copy between zero margins.
    for (int i = 0; i < conv.in; ++i) {
      const float* plane = x + static_cast<std::size_t>(i) * h * w;
      for (int ky = 0; ky < k; ++ky) {
        for (int kx = 0; kx < k; ++kx) {
          float* dst = col.data() + ((static_cast<std::size_t>(i) * k + ky) * k + kx) * cp;
          const int x0 = std::clamp(pad - kx, 0, ow);       // first ox with ix >= 0
          const int x1 = std::clamp(w + pad - kx, x0, ow);  // one past the last ox with ix < w
          for (int oy = oy0; oy < oy1; ++oy) {
            float* row = dst + static_cast<std::size_t>(oy - oy0) * ow;
            const int iy = oy + ky - pad;
            if (iy < 0 || iy >= h) {
              std::fill(row, row + ow, 0.0f);
              continue;
            }
            std::fill(row, row + x0, 0.0f);
            if (x1 > x0) {
              std::memcpy(row + x0, plane + static_cast<std::size_t>(iy) * w + (x0 + kx - pad),
                          sizeof(float) * (x1 - x0));
            }
            std::fill(row + x1, row + ow, 0.0f);
          }
        }
      }
    }
    Eigen::Map<const RowMatrix> columns(col.data(), static_cast<Eigen::Index>(rows),
                                        static_cast<Eigen::Index>(cp));
    Eigen::Map<RowMatrix, 0, Eigen::OuterStride<>> out(
        y + static_cast<std::size_t>(oy0) * ow, conv.out, static_cast<Eigen::Index>(cp),
        Eigen::OuterStride<>(static_cast<Eigen::Index>(pixels)));
    out.noalias() = weight * columns;
  }
  for (int o = 0; o < conv.out; ++o) {
    float* r = y + static_cast<std::size_t>(o) * pixels;
    const float b = conv.bias[o];
    if (conv.relu) {
      for (std::size_t p = 0; p < pixels; ++p)
        r[p] = std::max(r[p] + b, 0.0f);
    } else {
      for (std::size_t p = 0; p < pixels; ++p)
        r[p] += b;
    }
  }
}

void max_pool2x2(const float* x, int c, int h, int w, float* y, std::int32_t* index) {
  const int ph = h / 2, pw = w / 2;
  for (int k = 0; k < c; ++k) {
    const float* in = x + static_cast<std::size_t>(k) * h * w;
    float* out = y + static_cast<std::size_t>(k) * ph * pw;
    std::int32_t* idx = index + static_cast<std::size_t>(k) * ph * pw;
    for (int py = 0; py < ph; ++py) {
      for (int px = 0; px < pw; ++px) {
        std::int32_t best = (2 * py) * w + 2 * px;
        float v = in[best];
        for (int dy = 0; dy < 2; ++dy) {
          for (int dx = 0; dx < 2; ++dx) {
            const std::int32_t i = (2 * py + dy) * w + 2 * px + dx;
            if (in[i] > v || std::isnan(in[i])) {
              if (std::isnan(v)) continue;  // the first NaN wins, as in PyTorch
              v = in[i];
              best = i;
            }
          }
        }
        out[py * pw + px] = v;
        idx[py * pw + px] = best;
      }
    }
  }
}

void max_unpool2x2(const float* x, const std::int32_t* index, int c, int ph, int pw, int h, int w,
                   float* y) {
  const std::size_t plane = static_cast<std::size_t>(h) * w;
  const std::size_t pplane = static_cast<std::size_t>(ph) * pw;
  std::fill(y, y + plane * c, 0.0f);
  for (int k = 0; k < c; ++k) {
    for (std::size_t p = 0; p < pplane; ++p)
      y[k * plane + index[k * pplane + p]] = x[k * pplane + p];
  }
}

}  // namespace plumekit::surrogate
