#pragma once
// plumekit-cnn/1 model files: the one place that reads them (the format is in
// docs/design/surrogate.md; the writer is train/model_file.py). Reading either returns a complete,
// checked model or throws InputError naming the file and the fault, so no caller ever sees a
// half-loaded model.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace plumekit::surrogate {

inline constexpr char kModelMagic[8] = {'P', 'L', 'U', 'M', 'E', 'C', 'N', 'N'};
inline constexpr unsigned kModelVersion = 1;

// DeepCFD U-Net hyper-parameters; the network of docs/design/surrogate.md, "Architecture" is the
// default.
struct Architecture {
  int in_channels = 3;
  int out_channels = 2;
  std::vector<int> filters = {8, 16, 32, 32};
  int kernel = 5;
  int padding = 2;
  int convs_per_block = 3;
};

enum class LayerOp { kConv2d, kConvTranspose2d };

// One convolution. Weights as PyTorch stores them: conv2d [out, in, k, k], conv_transpose2d
// [in, out, k, k]; bias [out].
struct LayerSpec {
  std::string name;
  LayerOp op = LayerOp::kConv2d;
  int in = 0;
  int out = 0;
  int kernel = 0;
  int padding = 0;
  bool relu = true;

  std::size_t weight_count() const { return static_cast<std::size_t>(in) * out * kernel * kernel; }
  std::size_t parameter_count() const { return weight_count() + out; }
};

// The layers of `arch` in execution order, which is also their order in the file: encoder levels
// 0..L-1, then for each output its decoder from level L-1 down to 0.
std::vector<LayerSpec> deepcfd_layers(const Architecture& arch);
std::size_t parameter_count(const std::vector<LayerSpec>& layers);

// What the inputs must hold: the engine's callers build features by this contract. Two kinds:
// - the thesis's (v1): a fixed grid of rows x cols over a fixed arena, channels region,
//   signed_distance, source_distance;
// - a physical grid (v2, issue 19; cell_size > 0): nominal cells of cell_size metres over any map,
//   padded with zeros to a multiple of `multiple` (2^levels) on the high side, channels region,
//   signed_distance, wind_u, wind_v, [physics_mean,] source_distance. rows, cols, width and
//   height are 0.
struct FeatureChannel {
  std::string name;  // region, signed_distance, [wind_u, wind_v, [physics_mean,]] source_distance
  std::string unit;
};
// The physics_mean channel of a hybrid model (issue 46): the steady advection-diffusion plume of
// the source in the map's wind (surrogate::PhysicsFeature), divided by `scale`. Plain numbers,
// the cfd::AdvectionDiffusionOptions of that plume, so this engine library needs no cfd.
struct PhysicsChannel {
  double scale = 1.0;            // input value = concentration / scale
  double diffusivity = 0.05;     // m^2/s
  double decay_rate = 0.0;       // 1/s
  double release_rate = 1000.0;  // concentration units * m^2/s
};
struct FeatureContract {
  int rows = 64;           // grid rows (along y), row 0 at y = 0, cell-centred
  int cols = 64;           // grid columns (along x)
  double width = 10.0;     // arena size in metres (x)
  double height = 4.0;     // (y)
  double cell_size = 0.0;  // m; > 0: a physical-grid model
  int multiple = 1;        // input sides: multiples of it (physical grids)
  std::vector<FeatureChannel> channels;
  // "euclidean": metres from each cell centre to the source; "inverse": 1 / max(that,
  // source_min_distance), in 1/m (the thesis's code and DeepCFD-style inputs).
  std::string source_distance_form;
  double source_min_distance = 0.0;  // m, the inverse form's floor (header min_distance)
  int physics_channel = -1;          // physics_mean's index; -1: none (not a hybrid model)
  PhysicsChannel physics;            // its scale and plume options, when there is one

  bool physical() const { return cell_size > 0; }
  bool has_wind() const { return physical(); }
  bool has_physics() const { return physics_channel >= 0; }
  int source_channel() const { return static_cast<int>(channels.size()) - 1; }
};

// The input channels of a contract, in order: region, signed_distance, [wind_u, wind_v,
// [physics_mean,]] source_distance (the wind on a physical grid, the physics plume on a hybrid
// model's).
std::vector<std::string> feature_channel_names(bool physical, bool physics = false);

struct OutputSpec {
  std::string name;  // mean, std
  std::string unit;
  float scale = 1.0f;  // network output times scale = value in `unit`
  // A residual output (the mean of a hybrid model): "physics_mean", the input channel added back,
  // so value = scale * network output + that channel's scale * its input (residual_output()).
  // Empty: none.
  std::string plus_input;
};

// The value of a residual output in its unit, from the network's output already times its scale
// (`scaled_output`) and the added channel's input value and scale: the one place that sums them,
// for PlumeNetwork and the tests against PyTorch alike.
inline float residual_output(float scaled_output, float input, double input_scale) {
  return static_cast<float>(static_cast<double>(scaled_output) + input_scale * input);
}

// What the network was trained on (header "trained_on", optional; every part optional): the
// callers warn when a map lies outside it (PlumeNetwork::warnings), they do not refuse it.
struct ValueRange {
  double lo = 0.0, hi = 0.0;
  bool contains(double v) const { return v >= lo && v <= hi; }
};
struct TrainingRanges {
  std::optional<ValueRange> map_width, map_height;  // m (map_width_m, map_height_m)
  std::optional<ValueRange> inlet_speed;            // m/s, every inlet (inlet_speed_m_s)
  std::optional<ValueRange> openings;               // inlets and outlets counted together
  // "left", "right", "bottom", "top", "interior" (an inlet on an obstacle's edge: a window);
  // empty: any.
  std::vector<std::string> inlet_walls;
};

struct ModelFile {
  Architecture architecture;
  std::vector<LayerSpec> layers;
  std::vector<std::vector<float>> weights;  // per layer, PyTorch layout (see LayerSpec)
  std::vector<std::vector<float>> biases;
  FeatureContract features;
  std::vector<OutputSpec> outputs;
  TrainingRanges trained_on;
  std::string header_json;  // the whole header, for what the engine does not interpret
  std::string sha256_hex;
};

// `source` names the bytes in messages (usually the file path).
ModelFile parse_model_file(std::string_view bytes, const std::string& source);
ModelFile read_model_file(const std::filesystem::path& path);

}  // namespace plumekit::surrogate
