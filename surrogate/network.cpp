#include "surrogate/network.hpp"

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <string>

#include "core/option_check.hpp"

namespace plumekit::surrogate {

// Per-thread scratch: activations of every level, pool indices and the im2col buffer.
struct Network::Workspace {
  std::vector<std::vector<float>> skips;           // encoder level outputs, [filters[b], h_b, w_b]
  std::vector<std::vector<std::int32_t>> indices;  // argmax of each pool
  std::vector<float> a, b;                         // ping-pong activations
  std::vector<float> col;                          // conv_forward's scratch
  std::vector<float> bottom;                       // the encoder's output
  std::vector<int> hs, ws;                         // each level's plane size
};

// Free workspaces, taken and given back under a lock; predict() may run on many threads at once.
struct Network::WorkspacePool {
  std::mutex mutex;
  std::vector<std::unique_ptr<Workspace>> free;

  std::unique_ptr<Workspace> take() {
    std::lock_guard lock(mutex);
    if (free.empty()) return std::make_unique<Workspace>();
    auto ws = std::move(free.back());
    free.pop_back();
    return ws;
  }
  void give(std::unique_ptr<Workspace> ws) {
    std::lock_guard lock(mutex);
    free.push_back(std::move(ws));
  }
};

Network::~Network() = default;
Network::Network(Network&&) noexcept = default;
Network& Network::operator=(Network&&) noexcept = default;

void EngineOptions::validate() const {
  check_count("engine.threads", threads, 0, 1024, "0 is one per core");
}

Network::Network(ModelFile file, EngineOptions options)
    : file_(std::move(file)), options_(options), pool_(std::make_unique<WorkspacePool>()) {
  options_.validate();
  threads_ = std::make_unique<ThreadPool>(options_.threads);
  // A ModelFile from parse_model_file is consistent; one put together by hand must be too.
  const std::vector<LayerSpec> expected = deepcfd_layers(file_.architecture);
  bool consistent =
      expected.size() == file_.layers.size() && file_.weights.size() == expected.size() &&
      file_.biases.size() == expected.size() &&
      static_cast<int>(file_.outputs.size()) == file_.architecture.out_channels &&
      (file_.features.physical() || (file_.features.rows >= 1 && file_.features.cols >= 1));
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

int Network::threads() const {
  return threads_->size();
}

std::size_t Network::parameter_count() const {
  return surrogate::parameter_count(file_.layers);
}

double Network::flops_per_sample() const {
  if (file_.features.physical())
    throw std::logic_error("flops_per_sample(): a physical-grid model needs the input's size");
  return flops_per_sample(file_.features.rows, file_.features.cols);
}

double Network::flops_per_sample(int rows, int cols) const {
  const auto& a = file_.architecture;
  const int levels = static_cast<int>(a.filters.size());
  double flops = 0;
  auto conv_flops = [](const Conv& c, int h, int w) {
    return 2.0 * c.out * c.in * c.kernel * c.kernel * h * w;
  };
  int h = rows, w = cols;
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

void Network::encode(const float* x, int rows, int cols, Workspace& ws,
                     const std::int32_t* const* forced) const {
  const auto& a = file_.architecture;
  const int levels = static_cast<int>(a.filters.size());
  const int n = a.convs_per_block;
  const std::size_t plane0 = static_cast<std::size_t>(rows) * cols;
  const std::size_t widest =
      plane0 * 2 *
      static_cast<std::size_t>(
          std::max(a.in_channels, *std::max_element(a.filters.begin(), a.filters.end())));
  ws.a.resize(widest);
  ws.b.resize(widest);
  ws.skips.resize(levels);
  ws.indices.resize(levels);
  ws.hs.resize(levels);
  ws.ws.resize(levels);

  int h = rows, w = cols;
  const float* in = x;
  for (int b = 0; b < levels; ++b) {
    ws.hs[b] = h;
    ws.ws[b] = w;
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
    if (forced) {
      const std::size_t pooled = static_cast<std::size_t>(h / 2) * (w / 2);
      for (int c = 0; c < f; ++c)
        for (std::size_t p = 0; p < pooled; ++p) {
          const std::size_t q = c * pooled + p;
          ws.indices[b][q] = forced[b][q];
          ws.a[q] = ws.skips[b][static_cast<std::size_t>(c) * h * w + forced[b][q]];
        }
    }
    in = ws.a.data();
    h /= 2;
    w /= 2;
  }
  ws.bottom.assign(ws.a.begin(),
                   ws.a.begin() + static_cast<std::ptrdiff_t>(a.filters.back()) * h * w);
}

void Network::decode(int o, const Workspace& enc, Workspace& ws, float* y) const {
  const auto& a = file_.architecture;
  const int levels = static_cast<int>(a.filters.size());
  const int n = a.convs_per_block;
  const std::size_t plane0 = static_cast<std::size_t>(enc.hs[0]) * enc.ws[0];
  ws.a.resize(enc.a.size());
  ws.b.resize(enc.b.size());
  // Unpool into the upper half of the concatenation [skip, unpooled].
  std::size_t k = static_cast<std::size_t>(o) * levels * n;
  const float* cur = enc.bottom.data();
  int ph = enc.hs[levels - 1] / 2, pw = enc.ws[levels - 1] / 2;
  for (int b = levels - 1; b >= 0; --b) {
    const int f = a.filters[b];
    const int h = enc.hs[b], w = enc.ws[b];
    const std::size_t plane = static_cast<std::size_t>(h) * w;
    float* cat = cur == ws.a.data() ? ws.b.data() : ws.a.data();
    std::copy(enc.skips[b].begin(), enc.skips[b].end(), cat);
    max_unpool2x2(cur, enc.indices[b].data(), f, ph, pw, h, w, cat + f * plane);
    cur = cat;
    for (int j = 0; j < n; ++j) {
      const Conv& c = decoder_[k++];
      const bool last = b == 0 && j == n - 1;
      float* out = last ? y : (cur == ws.a.data() ? ws.b.data() : ws.a.data());
      conv_forward(c, cur, h, w, out, ws.col);
      cur = out;
    }
    ph = h;
    pw = w;
  }
  const float scale = file_.outputs[o].scale;
  if (scale != 1.0f) {
    for (std::size_t p = 0; p < plane0; ++p)
      y[p] *= scale;
  }
}

void Network::check_input(const Tensor& input) const {
  const auto& a = file_.architecture;
  const FeatureContract& f = file_.features;
  const auto shape = [](const Tensor& t) {
    return "[" + std::to_string(t.n) + "," + std::to_string(t.c) + "," + std::to_string(t.h) + "," +
           std::to_string(t.w) + "]";
  };
  const bool sizes = input.c == a.in_channels && input.data.size() == input.sample() * input.n &&
                     (f.physical() ? input.h >= f.multiple && input.w >= f.multiple &&
                                         input.h % f.multiple == 0 && input.w % f.multiple == 0 &&
                                         input.h <= kMaxInputSide && input.w <= kMaxInputSide
                                   : input.h == f.rows && input.w == f.cols);
  if (!sizes) {
    throw std::invalid_argument(
        "Network::predict: input is " + shape(input) + ", the model takes [n," +
        std::to_string(a.in_channels) + "," +
        (f.physical() ? "rows,cols] with rows and cols multiples of " + std::to_string(f.multiple) +
                            " up to " + std::to_string(kMaxInputSide)
                      : std::to_string(f.rows) + "," + std::to_string(f.cols) + "]"));
  }
}

Tensor Network::predict_with_pool_indices(const Tensor& input, const PoolIndices& indices) const {
  check_input(input);
  const auto& a = file_.architecture;
  const int levels = static_cast<int>(a.filters.size());
  if (static_cast<int>(indices.size()) != levels)
    throw std::invalid_argument("predict_with_pool_indices: one index array per level needed");
  std::vector<std::size_t> per_sample(levels);
  int h = input.h, w = input.w;
  for (int b = 0; b < levels; ++b) {
    const int ph = h / 2, pw = w / 2;
    per_sample[b] = static_cast<std::size_t>(a.filters[b]) * ph * pw;
    if (indices[b].size() != per_sample[b] * input.n)
      throw std::invalid_argument("predict_with_pool_indices: level " + std::to_string(b) +
                                  " has " + std::to_string(indices[b].size()) + " indices, needs " +
                                  std::to_string(per_sample[b] * input.n));
    for (std::size_t q = 0; q < indices[b].size(); ++q) {
      const std::size_t p = q % (static_cast<std::size_t>(ph) * pw);
      const int py = static_cast<int>(p / pw), px = static_cast<int>(p % pw);
      const std::int32_t i = indices[b][q];
      if (i < 0 || i / w / 2 != py || i % w / 2 != px)
        throw std::invalid_argument("predict_with_pool_indices: level " + std::to_string(b) +
                                    " index " + std::to_string(q) + " lies outside its window");
    }
    h = ph;
    w = pw;
  }
  Tensor out(input.n, a.out_channels, input.h, input.w);
  const std::size_t plane = static_cast<std::size_t>(input.h) * input.w;
  Workspace ws;
  std::vector<const std::int32_t*> forced(levels);
  for (int i = 0; i < input.n; ++i) {
    for (int b = 0; b < levels; ++b)
      forced[b] = indices[b].data() + per_sample[b] * i;
    encode(input.sample_data(i), input.h, input.w, ws, forced.data());
    for (int o = 0; o < a.out_channels; ++o)
      decode(o, ws, ws, out.sample_data(i) + o * plane);
  }
  return out;
}

Tensor Network::predict(const Tensor& input) const {
  check_input(input);
  const auto& a = file_.architecture;
  Tensor out(input.n, a.out_channels, input.h, input.w);
  const std::size_t plane = static_cast<std::size_t>(input.h) * input.w;
  if (threads_->size() > input.n && a.out_channels > 1) {
    // Fewer samples than threads: each sample's encoder, then its decoders side by side.
    std::unique_ptr<Workspace> enc = pool_->take();
    for (int i = 0; i < input.n; ++i) {
      encode(input.sample_data(i), input.h, input.w, *enc);
      threads_->parallel_for(a.out_channels, [&](std::size_t o) {
        std::unique_ptr<Workspace> ws = pool_->take();
        decode(static_cast<int>(o), *enc, *ws, out.sample_data(i) + o * plane);
        pool_->give(std::move(ws));
      });
    }
    pool_->give(std::move(enc));
    return out;
  }
  threads_->parallel_for(input.n, [&](std::size_t i) {
    std::unique_ptr<Workspace> ws = pool_->take();
    encode(input.sample_data(static_cast<int>(i)), input.h, input.w, *ws);
    for (int o = 0; o < a.out_channels; ++o)
      decode(o, *ws, *ws, out.sample_data(static_cast<int>(i)) + o * plane);
    pool_->give(std::move(ws));
  });
  return out;
}

}  // namespace plumekit::surrogate
