// The direct convolution against a naive reference, one layer at a time, each with a fresh
// scratch buffer (so a tile that writes or reads past its buffer shows up, under ASan at least),
// over shapes the network meets and odd ones: 1, 3, 8, 9 and 16 output channels, kernels 3 and 5,
// planes from 1x1 to 64x64 that are not multiples of the vector width.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "surrogate/layers.hpp"

namespace plumekit::surrogate {
namespace {

// y[o](oy, ox) = act(b[o] + sum_i,ky,kx W[o][i][ky][kx] x[i](oy + ky - p, ox + kx - p)).
std::vector<float> reference(const Conv& c, const std::vector<float>& x, int h, int w) {
  const int oh = c.out_size(h), ow = c.out_size(w), k = c.kernel;
  std::vector<float> y(static_cast<std::size_t>(c.out) * oh * ow);
  for (int o = 0; o < c.out; ++o)
    for (int oy = 0; oy < oh; ++oy)
      for (int ox = 0; ox < ow; ++ox) {
        double s = c.bias[o];
        for (int i = 0; i < c.in; ++i)
          for (int ky = 0; ky < k; ++ky)
            for (int kx = 0; kx < k; ++kx) {
              const int iy = oy + ky - c.padding, ix = ox + kx - c.padding;
              if (iy < 0 || iy >= h || ix < 0 || ix >= w) continue;
              s += double{c.weight[((static_cast<std::size_t>(o) * c.in + i) * k + ky) * k + kx]} *
                   x[(static_cast<std::size_t>(i) * h + iy) * w + ix];
            }
        y[(static_cast<std::size_t>(o) * oh + oy) * ow + ox] =
            static_cast<float>(c.relu ? std::max(s, 0.0) : s);
      }
  return y;
}

TEST(Conv, DirectEqualsNaiveOnManyShapes) {
  struct Shape {
    int in, out, k, pad, h, w;
    bool relu, transposed;
  };
  const Shape shapes[] = {
      {3, 8, 5, 2, 64, 64, true, false}, {8, 1, 5, 2, 64, 64, false, true},
      {16, 8, 5, 2, 64, 64, true, true}, {8, 16, 5, 2, 32, 32, true, false},
      {64, 32, 5, 2, 8, 8, true, true},  {3, 3, 3, 1, 21, 30, true, false},
      {5, 9, 3, 1, 10, 15, true, true},  {7, 1, 3, 1, 5, 7, false, true},
      {2, 16, 5, 2, 1, 1, true, false},  {4, 8, 5, 0, 9, 11, false, false},
      {9, 1, 3, 0, 3, 3, false, false},
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (const Shape& s : shapes) {
    std::vector<float> w(static_cast<std::size_t>(s.in) * s.out * s.k * s.k), b(s.out);
    for (float& v : w)
      v = u(rng);
    for (float& v : b)
      v = u(rng);
    std::vector<float> x(static_cast<std::size_t>(s.in) * s.h * s.w);
    for (float& v : x)
      v = u(rng);
    // A transposed convolution (padding p) is the convolution make_conv_transpose2d builds.
    const Conv c = s.transposed ? make_conv_transpose2d(s.in, s.out, s.k, s.pad, s.relu, w, b)
                                : make_conv2d(s.in, s.out, s.k, s.pad, s.relu, w, b);
    const std::vector<float> want = reference(c, x, s.h, s.w);
    std::vector<float> got(want.size(), -7.0f), scratch;
    conv_forward(c, x.data(), s.h, s.w, got.data(), scratch);
    double err = 0, top = 0;
    for (std::size_t i = 0; i < want.size(); ++i) {
      err = std::max(err, std::abs(double{got[i]} - want[i]));
      top = std::max(top, std::abs(double{want[i]}));
    }
    EXPECT_LT(err, 1e-5 * std::max(1.0, top))
        << s.in << "->" << s.out << " k" << s.k << " p" << s.pad << " " << s.h << "x" << s.w;
  }
}

}  // namespace
}  // namespace plumekit::surrogate
