#pragma once
// Small physical-grid (v2, issue 19) model files built in C++ with random weights: the header as
// train/model_file.py writes it (features cell_size, multiple and the five channels), the tensors
// in layer order, the SHA-256 at the end. Tests edit the header and build the bytes again.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/sha256.hpp"
#include "surrogate/model_file.hpp"

namespace plumekit::surrogate::test {

struct PhysicalModel {
  nlohmann::json header;
  std::vector<float> data;  // every layer's weight then bias, in layer order

  // The plumekit-cnn/1 bytes of header and data.
  std::string bytes() const {
    nlohmann::json h = header;
    h["data_bytes"] = 4 * data.size();
    const std::string text = h.dump();
    const auto len = static_cast<std::uint32_t>(text.size());
    const std::uint32_t version = kModelVersion;
    std::string out(kModelMagic, sizeof kModelMagic);
    out += std::string(reinterpret_cast<const char*>(&version), 4);
    out += std::string(reinterpret_cast<const char*>(&len), 4);
    out += text;
    out.resize((out.size() + 15) / 16 * 16, '\0');
    out += std::string(reinterpret_cast<const char*>(data.data()), 4 * data.size());
    const Sha256Digest d = sha256(out);
    return out + std::string(d.begin(), d.end());
  }
  ModelFile parse(const std::string& name = "physical.pkcnn") const {
    return parse_model_file(bytes(), name);
  }
};

// The five channels of a physical-grid model; the source channel in the inverse form (1/m).
inline nlohmann::json physical_channels() {
  return nlohmann::json::array(
      {{{"name", "region"}, {"unit", "label"}},
       {{"name", "signed_distance"}, {"unit", "m"}},
       {{"name", "wind_u"}, {"unit", "m/s"}},
       {{"name", "wind_v"}, {"unit", "m/s"}},
       {{"name", "source_distance"}, {"unit", "1/m"}, {"form", "inverse"}}});
}

// A DeepCFD U-Net of `filters` (pooled filters.size() times, so inputs are multiples of
// 2^levels), `in_channels` inputs (the header lists the five channels whatever the count), outputs
// mean and std, weights uniform in [-0.5, 0.5) from `seed`.
inline PhysicalModel physical_model(std::vector<int> filters, int kernel = 3, int convs = 1,
                                    double cell = 0.2, unsigned seed = 1, int in_channels = 5) {
  Architecture a;
  a.in_channels = in_channels;
  a.out_channels = 2;
  a.filters = filters;
  a.kernel = kernel;
  a.padding = kernel / 2;
  a.convs_per_block = convs;
  PhysicalModel m;
  nlohmann::json& h = m.header;
  h["format"] = "plumekit-cnn/1";
  h["architecture"] = {{"type", "deepcfd-unet"},
                       {"in_channels", a.in_channels},
                       {"out_channels", a.out_channels},
                       {"filters", a.filters},
                       {"kernel", a.kernel},
                       {"padding", a.padding},
                       {"convs_per_block", a.convs_per_block}};
  const std::vector<LayerSpec> layers = deepcfd_layers(a);
  h["layers"] = nlohmann::json::array();
  for (const LayerSpec& l : layers) {
    const bool conv = l.op == LayerOp::kConv2d;
    h["layers"].push_back(
        {{"name", l.name},
         {"op", conv ? "conv2d" : "conv_transpose2d"},
         {"in", l.in},
         {"out", l.out},
         {"kernel", l.kernel},
         {"padding", l.padding},
         {"relu", l.relu},
         {"weight_shape", conv ? std::vector<int>{l.out, l.in, l.kernel, l.kernel}
                               : std::vector<int>{l.in, l.out, l.kernel, l.kernel}},
         {"bias_shape", {l.out}}});
  }
  h["parameter_count"] = parameter_count(layers);
  h["features"] = {
      {"cell_size", cell}, {"multiple", 1 << filters.size()}, {"channels", physical_channels()}};
  h["outputs"] = {{{"name", "mean"}, {"unit", "concentration"}, {"scale", 1.0}},
                  {{"name", "std"}, {"unit", "concentration"}, {"scale", 0.5}}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  m.data.resize(parameter_count(layers));
  for (float& v : m.data)
    v = u(rng);
  return m;
}

// The six channels of a hybrid model (issue 46): the five above with physics_mean (its scale and
// plume options) before the source distance.
inline nlohmann::json hybrid_channels(double scale = 250.0) {
  nlohmann::json c = physical_channels();
  const nlohmann::json physics = {{"name", "physics_mean"},   {"unit", "concentration / scale"},
                                  {"scale", scale},           {"diffusivity", 0.05},
                                  {"decay_rate", 1.0 / 28.0}, {"release_rate", 1000.0}};
  c.insert(c.begin() + 4, physics);
  return c;
}

// A hybrid residual model: six inputs, the mean adds physics_mean back (plus_input), mean and std
// scales other than the input's so a unit slip shows.
inline PhysicalModel hybrid_model(std::vector<int> filters, int kernel = 3, int convs = 1,
                                  double cell = 0.2, unsigned seed = 1) {
  PhysicalModel m = physical_model(std::move(filters), kernel, convs, cell, seed, 6);
  m.header["features"]["channels"] = hybrid_channels();
  m.header["outputs"] = {{{"name", "mean"},
                          {"unit", "concentration"},
                          {"scale", 40.0},
                          {"plus_input", "physics_mean"}},
                         {{"name", "std"}, {"unit", "concentration"}, {"scale", 20.0}}};
  return m;
}

// The file `m` makes must be refused with an InputError naming it and holding `fault`.
inline void expect_refused(const PhysicalModel& m, const std::string& fault) {
  try {
    m.parse("bad.pkcnn");
    ADD_FAILURE() << "accepted a file that should fail with \"" << fault << "\"";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.pkcnn"), std::string::npos) << what;
    EXPECT_NE(what.find(fault), std::string::npos) << what;
  }
}

}  // namespace plumekit::surrogate::test
