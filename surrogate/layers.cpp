#include "surrogate/layers.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace plumekit::surrogate {

Conv make_conv2d(int in, int out, int kernel, int padding, bool relu, const std::vector<float>& w,
                 const std::vector<float>& b) {
  Conv c{in, out, kernel, padding, relu, w, b, {}};
  c.pack();
  return c;
}

Conv make_conv_transpose2d(int in, int out, int kernel, int padding, bool relu,
                           const std::vector<float>& w, const std::vector<float>& b) {
  // y[o](p) = sum_i,k x[i](p + pad - k) W[i][o][k] equals a convolution with kernel
  // W'[o][i][k'] = W[i][o][K-1-k'] and padding K-1-pad.
  Conv c{in, out, kernel, kernel - 1 - padding, relu, std::vector<float>(w.size()), b, {}};
  const int kk = kernel * kernel;
  for (int i = 0; i < in; ++i) {
    for (int o = 0; o < out; ++o) {
      for (int k = 0; k < kk; ++k) {
        c.weight[(static_cast<std::size_t>(o) * in + i) * kk + k] =
            w[(static_cast<std::size_t>(i) * out + o) * kk + (kk - 1 - k)];
      }
    }
  }
  c.pack();
  return c;
}

namespace {

// The direct convolution's vectors: GCC/Clang vector extensions, as wide as the build's ISA allows.
// 4 output channels (Conv::block) times NV vectors of output positions stay in registers: NV = 4,
// 5 or 6 with the 32 AVX-512 registers (24 accumulators at most, chosen per layer so that the
// tiles cover the plane with little overhang), 2 with the 16 registers of AVX and SSE.
// Measured per layer (CPU time, AVX-512): 4 x 6 beat 8 x 3 by 5-25 %, and 4 x 5 at 16 x 16 (whose
// 320 positions it tiles exactly) beat 4 x 6 by 20 %.
#if defined(__AVX512F__)
constexpr int kLanes = 16;
constexpr int kVectorChoices[] = {6, 5, 4};
#elif defined(__AVX__)
constexpr int kLanes = 8;
constexpr int kVectorChoices[] = {2};
#else
constexpr int kLanes = 4;
constexpr int kVectorChoices[] = {2};
#endif
typedef float Vec __attribute__((vector_size(kLanes * sizeof(float))));

inline Vec load(const float* p) {
  Vec v;
  std::memcpy(&v, p, sizeof v);  // unaligned load
  return v;
}
inline void store(float* p, Vec v) {
  std::memcpy(p, &v, sizeof v);
}

// One tile: MB output channels times NV * kLanes consecutive output positions of the flattened
// padded plane. x points at the tile's first position in channel 0 of the padded input, w at the
// block's packed weights [in][k][k][MB], y at the block's first channel in the flat output.
template <int MB, int NV>
void conv_tile(const float* x, std::size_t x_stride, int in, int k, int wp, const float* w,
               float* y, std::size_t y_stride) {
  Vec acc[MB][NV] = {};
  for (int i = 0; i < in; ++i) {
    const float* xi = x + i * x_stride;
    for (int ky = 0; ky < k; ++ky) {
      const float* row = xi + static_cast<std::size_t>(ky) * wp;
      for (int kx = 0; kx < k; ++kx, w += MB) {
        Vec xv[NV];
#pragma GCC unroll 8
        for (int v = 0; v < NV; ++v)
          xv[v] = load(row + kx + v * kLanes);
#pragma GCC unroll 16
        for (int m = 0; m < MB; ++m) {
          const Vec wm = Vec{} + w[m];
#pragma GCC unroll 8
          for (int v = 0; v < NV; ++v)
            acc[m][v] += wm * xv[v];
        }
      }
    }
  }
  for (int m = 0; m < MB; ++m)
    for (int v = 0; v < NV; ++v)
      store(y + m * y_stride + v * kLanes, acc[m][v]);
}

template <int MB, int NV>
void conv_blocks(const Conv& c, const float* xp, std::size_t x_stride, int wp, std::size_t span,
                 float* flat) {
  constexpr int tile = NV * kLanes;
  const std::size_t kk = static_cast<std::size_t>(c.kernel) * c.kernel;
  for (int ob = 0; ob * MB < c.out; ++ob) {
    const float* w = c.packed.data() + static_cast<std::size_t>(ob) * c.in * kk * MB;
    float* y = flat + static_cast<std::size_t>(ob) * MB * span;
    for (std::size_t q = 0; q < span; q += tile)
      conv_tile<MB, NV>(xp + q, x_stride, c.in, c.kernel, wp, w, y + q, span);
  }
}

template <int MB>
void conv_blocks(int nv, const Conv& c, const float* xp, std::size_t x_stride, int wp,
                 std::size_t span, float* flat) {
  switch (nv) {
    case 6:
      conv_blocks<MB, 6>(c, xp, x_stride, wp, span, flat);
      break;
    case 5:
      conv_blocks<MB, 5>(c, xp, x_stride, wp, span, flat);
      break;
    case 4:
      conv_blocks<MB, 4>(c, xp, x_stride, wp, span, flat);
      break;
    default:
      conv_blocks<MB, 2>(c, xp, x_stride, wp, span, flat);
      break;
  }
}

// Vectors per tile for `positions` outputs: the fewest computed positions, each vector fewer than
// the widest choice counted 3 % dearer (fewer accumulators per load).
int vectors_for(std::size_t positions) {
  int best = kVectorChoices[0];
  double best_cost = 1e300;
  for (int nv : kVectorChoices) {
    const std::size_t tile = static_cast<std::size_t>(nv) * kLanes;
    const double cost = static_cast<double>((positions + tile - 1) / tile * tile) *
                        (1.0 + 0.03 * (kVectorChoices[0] - nv));
    if (cost < best_cost) best = nv, best_cost = cost;
  }
  return best;
}

}  // namespace

int Conv::block() const {
  return out == 1 ? 1 : 4;
}

void Conv::pack() {
  // [out block][in][k][k][block], zero weights for the channels a last partial block pads.
  const int mb = block(), blocks = (out + mb - 1) / mb;
  const std::size_t kk = static_cast<std::size_t>(kernel) * kernel;
  packed.assign(static_cast<std::size_t>(blocks) * mb * in * kk, 0.0f);
  for (int o = 0; o < out; ++o)
    for (int i = 0; i < in; ++i)
      for (std::size_t t = 0; t < kk; ++t)
        packed[((static_cast<std::size_t>(o / mb) * in + i) * kk + t) * mb + o % mb] =
            weight[(static_cast<std::size_t>(o) * in + i) * kk + t];
}

void conv_forward(const Conv& conv, const float* x, int h, int w, float* y,
                  std::vector<float>& scratch) {
  // Direct convolution on the flattened zero-padded input: output position q = oy * wp + ox reads
  // padded input q + ky * wp + kx, so every tap is a contiguous vector load and no column matrix is
  // built. The k - 1 positions per row with ox >= ow are computed and dropped (6 % of the work at
  // 64 x 64, a third at 8 x 8), which keeps every load a full vector.
  const int k = conv.kernel, pad = conv.padding;
  const int oh = conv.out_size(h), ow = conv.out_size(w);
  const int wp = w + 2 * pad, hp = h + 2 * pad;
  const int mb = conv.block();
  const int nv = vectors_for(static_cast<std::size_t>(oh) * wp);
  const int tile = nv * kLanes;
  const std::size_t span = (static_cast<std::size_t>(oh) * wp + tile - 1) / tile * tile;
  // Each padded plane holds every position a tile can read, zeros beyond the image.
  const std::size_t x_stride = std::max(static_cast<std::size_t>(hp) * wp,
                                        span + static_cast<std::size_t>(k - 1) * (wp + 1));
  const int blocks = (conv.out + mb - 1) / mb;
  const std::size_t need = conv.in * x_stride + static_cast<std::size_t>(blocks) * mb * span;
  if (scratch.size() < need) scratch.resize(need);
  float* xp = scratch.data();
  float* flat = xp + conv.in * x_stride;
  for (int i = 0; i < conv.in; ++i) {
    float* dst = xp + i * x_stride;
    const float* src = x + static_cast<std::size_t>(i) * h * w;
    std::fill(dst, dst + static_cast<std::size_t>(pad) * wp, 0.0f);
    for (int r = 0; r < h; ++r) {
      float* row = dst + static_cast<std::size_t>(r + pad) * wp;
      std::fill(row, row + pad, 0.0f);
      std::memcpy(row + pad, src + static_cast<std::size_t>(r) * w, sizeof(float) * w);
      std::fill(row + pad + w, row + wp, 0.0f);
    }
    std::fill(dst + static_cast<std::size_t>(h + pad) * wp, dst + x_stride, 0.0f);
  }
  if (mb == 1) {
    conv_blocks<1>(nv, conv, xp, x_stride, wp, span, flat);
  } else {
    conv_blocks<4>(nv, conv, xp, x_stride, wp, span, flat);
  }
  // Bias and ReLU on the way out of the flat layout.
  for (int o = 0; o < conv.out; ++o) {
    const float b = conv.bias[o];
    for (int oy = 0; oy < oh; ++oy) {
      const float* src = flat + o * span + static_cast<std::size_t>(oy) * wp;
      float* dst = y + (static_cast<std::size_t>(o) * oh + oy) * ow;
      if (conv.relu) {
        for (int ox = 0; ox < ow; ++ox)
          dst[ox] = std::max(src[ox] + b, 0.0f);
      } else {
        for (int ox = 0; ox < ow; ++ox)
          dst[ox] = src[ox] + b;
      }
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
