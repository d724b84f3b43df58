#include "surrogate/network.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>

namespace plumekit::surrogate {

// Per-thread scratch: activations of every level, pool indices and the im2col buffer.
struct Network::Workspace {
  std::vector<std::vector<float>> skips;           // encoder level outputs, [filters[b], h_b, w_b]
  std::vector<std::vector<std::int32_t>> indices;  // argmax of each pool
  std::vector<float> a, b;                         // ping-pong activations
  std::vector<float> col;
};

Network::Network(ModelFile file, EngineOptions options)
    : file_(std::move(file)), options_(options) {
  if (options_.threads < 1) throw std::invalid_argument("EngineOptions.threads must be >= 1");
  // A ModelFile from parse_model_file is consistent; one put together by hand must be too.
  const std::vector<LayerSpec> expected = deepcfd_layers(file_.architecture);
  bool consistent = expected.size() == file_.layers.size() &&
                    file_.weights.size() == expected.size() &&
                    file_.biases.size() == expected.size() &&
                    static_cast<int>(file_.outputs.size()) == file_.architecture.out_channels &&
                    file_.features.rows >= 1 && file_.features.cols >= 1;
  for (std::size_t i = 0; consistent && i < expected.size(); ++i) {
    const LayerSpec& e = expected[i];
    const LayerSpec& l = file_.layers[i];
    consistent = l.op == e.op && l.in == e.in && l.out == e.out && l.kernel == e.kernel &&
                 l.padding == e.padding && l.relu == e.relu &&
                 file_.weights[i].size() == e.weight_count() &&
                 file_.biases[i].size() == static_cast<std::size_t>(e.out);
  }
  if (!consistent) {
    throw std::invalid_argument(
        "Network: the ModelFile's layers and tensors do not fit its "
        "architecture (build it with parse_model_file)");
  }
  const std::size_t encoder_layers =
      file_.architecture.filters.size() * file_.architecture.convs_per_block;
  for (std::size_t i = 0; i < file_.layers.size(); ++i) {
    const LayerSpec& l = file_.layers[i];
    if (l.op == LayerOp::kConv2d) {
      encoder_.push_back(
          make_conv2d(l.in, l.out, l.kernel, l.padding, l.relu, file_.weights[i], file_.biases[i]));
    } else {
      decoder_.push_back(make_conv_transpose2d(l.in, l.out, l.kernel, l.padding, l.relu,
                                               file_.weights[i], file_.biases[i]));
    }
  }
  if (encoder_.size() != encoder_layers) throw std::logic_error("layer table out of order");
  // The raw tensors now live in the converted layers; drop the copies.
  file_.weights.clear();
  file_.biases.clear();
}

Network Network::load(const std::filesystem::path& path, EngineOptions options) {
  return Network(read_model_file(path), options);
}

std::size_t Network::parameter_count() const {
  return surrogate::parameter_count(file_.layers);
}

double Network::flops_per_sample() const {
  const auto& a = file_.architecture;
  const int levels = static_cast<int>(a.filters.size());
  double flops = 0;
  auto conv_flops = [](const Conv& c, int h, int w) {
    return 2.0 * c.out * c.in * c.kernel * c.kernel * h * w;
  };
  int h = file_.features.rows, w = file_.features.cols;
  std::vector<int> hs, ws;
  for (int b = 0; b < levels; ++b) {
    hs.push_back(h);
    ws.push_back(w);
    for (int j = 0; j < a.convs_per_block; ++j)
      flops += conv_flops(encoder_[b * a.convs_per_block + j], h, w);
    h /= 2;
    w /= 2;
  }
  std::size_t k = 0;
  for (int o = 0; o < a.out_channels; ++o) {
    for (int b = levels - 1; b >= 0; --b) {
      for (int j = 0; j < a.convs_per_block; ++j)
        flops += conv_flops(decoder_[k++], hs[b], ws[b]);
    }
  }
  return flops;
}

void Network::forward_sample(const float* x, float* y, Workspace& ws) const {
  const auto& a = file_.architecture;
  const int levels = static_cast<int>(a.filters.size());
  const int n = a.convs_per_block;
  const std::size_t plane0 = static_cast<std::size_t>(file_.features.rows) * file_.features.cols;
  const std::size_t widest =
      plane0 * 2 *
      static_cast<std::size_t>(
          std::max(a.in_channels, *std::max_element(a.filters.begin(), a.filters.end())));
  ws.a.resize(widest);
  ws.b.resize(widest);
  ws.skips.resize(levels);
  ws.indices.resize(levels);
  std::vector<int> hs(levels), wd(levels);

  // Encoder.
  int h = file_.features.rows, w = file_.features.cols;
  const float* in = x;
  for (int b = 0; b < levels; ++b) {
    hs[b] = h;
    wd[b] = w;
    for (int j = 0; j < n; ++j) {
      const Conv& c = encoder_[b * n + j];
      float* out = j == n - 1 ? nullptr : (in == ws.a.data() ? ws.b.data() : ws.a.data());
      if (j == n - 1) {
        ws.skips[b].resize(static_cast<std::size_t>(c.out) * h * w);
        out = ws.skips[b].data();
      }
      conv_forward(c, in, h, w, out, ws.col);
      in = out;
    }
    const int f = a.filters[b];
    ws.indices[b].resize(static_cast<std::size_t>(f) * (h / 2) * (w / 2));
    max_pool2x2(ws.skips[b].data(), f, h, w, ws.a.data(), ws.indices[b].data());
    in = ws.a.data();
    h /= 2;
    w /= 2;
  }
  // The bottleneck stays in ws.a's head; copy it out since decoders reuse a and b.
  const std::vector<float> bottom(
      ws.a.begin(), ws.a.begin() + static_cast<std::ptrdiff_t>(a.filters.back()) * h * w);

  // One decoder per output: unpool into the upper half of the concatenation [skip, unpooled].
  std::size_t k = 0;
  for (int o = 0; o < a.out_channels; ++o) {
    const float* cur = bottom.data();
    int ph = h, pw = w;
    for (int b = levels - 1; b >= 0; --b) {
      const int f = a.filters[b];
      const std::size_t plane = static_cast<std::size_t>(hs[b]) * wd[b];
      float* cat = cur == ws.a.data() ? ws.b.data() : ws.a.data();
      std::copy(ws.skips[b].begin(), ws.skips[b].end(), cat);
      max_unpool2x2(cur, ws.indices[b].data(), f, ph, pw, hs[b], wd[b], cat + f * plane);
      cur = cat;
      for (int j = 0; j < n; ++j) {
        const Conv& c = decoder_[k++];
        const bool last = b == 0 && j == n - 1;
        float* out = last ? y + o * plane : (cur == ws.a.data() ? ws.b.data() : ws.a.data());
        conv_forward(c, cur, hs[b], wd[b], out, ws.col);
        cur = out;
      }
      ph = hs[b];
      pw = wd[b];
    }
    const float scale = file_.outputs[o].scale;
    if (scale != 1.0f) {
      for (std::size_t p = 0; p < plane0; ++p)
        y[o * plane0 + p] *= scale;
    }
  }
}

Tensor Network::predict(const Tensor& input) const {
  const auto& a = file_.architecture;
  if (input.c != a.in_channels || input.h != file_.features.rows ||
      input.w != file_.features.cols || input.data.size() != input.sample() * input.n) {
    throw std::invalid_argument(
        "Network::predict: input is [" + std::to_string(input.n) + "," + std::to_string(input.c) +
        "," + std::to_string(input.h) + "," + std::to_string(input.w) + "], the model takes [n," +
        std::to_string(a.in_channels) + "," + std::to_string(file_.features.rows) + "," +
        std::to_string(file_.features.cols) + "]");
  }
  Tensor out(input.n, a.out_channels, input.h, input.w);
  const int threads = std::max(1, std::min(options_.threads, input.n));
  auto run = [&](int first, int last) {
    Workspace ws;
    for (int i = first; i < last; ++i)
      forward_sample(input.sample_data(i), out.sample_data(i), ws);
  };
  if (threads == 1) {
    run(0, input.n);
    return out;
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back(run, input.n * t / threads, input.n * (t + 1) / threads);
  }
  for (auto& t : pool)
    t.join();
  return out;
}

}  // namespace plumekit::surrogate
