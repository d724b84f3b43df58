#include "surrogate/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"

namespace plumekit::surrogate {
namespace {

using nlohmann::json;

constexpr std::size_t kPrefix = 16;  // magic, version, header length
constexpr std::size_t kDigest = 32;

std::uint32_t read_u32_le(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t{b[0]} | (std::uint32_t{b[1]} << 8) | (std::uint32_t{b[2]} << 16) |
         (std::uint32_t{b[3]} << 24);
}

float read_f32_le(const char* p) {
  const std::uint32_t bits = read_u32_le(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

std::string shape_text(const std::vector<int>& s) {
  std::ostringstream os;
  os << '[';
  for (std::size_t i = 0; i < s.size(); ++i)
    os << (i ? "," : "") << s[i];
  os << ']';
  return os.str();
}

const char* op_name(LayerOp op) {
  return op == LayerOp::kConv2d ? "conv2d" : "conv_transpose2d";
}

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw InputError(source + ": " + what);
}

// Reads key `key` of `j` as T, naming the key when it is missing or of the wrong type.
template <typename T>
T get(const json& j, const char* key, const std::string& source, const std::string& where) {
  if (!j.is_object() || !j.contains(key))
    fail(source, "header: " + where + " has no \"" + key + "\"");
  try {
    return j.at(key).get<T>();
  } catch (const json::exception&) {
    fail(source, "header: " + where + "." + key + " has the wrong type");
  }
}

Architecture parse_architecture(const json& j, const std::string& source) {
  Architecture a;
  const std::string type = get<std::string>(j, "type", source, "architecture");
  if (type != "deepcfd-unet") {
    fail(source,
         "header: architecture.type is \"" + type + "\", this engine runs \"deepcfd-unet\"");
  }
  a.in_channels = get<int>(j, "in_channels", source, "architecture");
  a.out_channels = get<int>(j, "out_channels", source, "architecture");
  a.filters = get<std::vector<int>>(j, "filters", source, "architecture");
  a.kernel = get<int>(j, "kernel", source, "architecture");
  a.padding = get<int>(j, "padding", source, "architecture");
  a.convs_per_block = get<int>(j, "convs_per_block", source, "architecture");
  bool ok = a.in_channels > 0 && a.out_channels > 0 && !a.filters.empty() && a.kernel > 0 &&
            a.kernel % 2 == 1 && a.padding == a.kernel / 2 && a.convs_per_block > 0 &&
            a.filters.size() <= 16 && a.kernel <= 15 && a.in_channels <= 4096 &&
            a.out_channels <= 64;
  for (int f : a.filters)
    ok = ok && f > 0 && f <= 4096;
  if (!ok) {
    fail(source,
         "shape mismatch: architecture needs positive channels, an odd kernel and "
         "padding = kernel/2 (kernel " +
             std::to_string(a.kernel) + ", padding " + std::to_string(a.padding) + ", filters " +
             shape_text(a.filters) + ")");
  }
  return a;
}

// The file's layer table must be exactly the one its architecture implies.
void check_layers(const json& j, const std::vector<LayerSpec>& expected,
                  const std::string& source) {
  if (!j.is_array()) fail(source, "header: \"layers\" is not an array");
  if (j.size() != expected.size()) {
    fail(source, "shape mismatch: the file lists " + std::to_string(j.size()) +
                     " layers, its architecture has " + std::to_string(expected.size()));
  }
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const LayerSpec& e = expected[i];
    const json& l = j[i];
    const std::string where = "layers[" + std::to_string(i) + "]";
    const auto name = get<std::string>(l, "name", source, where);
    const auto op = get<std::string>(l, "op", source, where);
    if (name != e.name || op != op_name(e.op)) {
      fail(source, "shape mismatch: " + where + " is " + op + " \"" + name + "\", expected " +
                       op_name(e.op) + " \"" + e.name + "\"");
    }
    const std::vector<int> weight = e.op == LayerOp::kConv2d
                                        ? std::vector<int>{e.out, e.in, e.kernel, e.kernel}
                                        : std::vector<int>{e.in, e.out, e.kernel, e.kernel};
    const auto w = get<std::vector<int>>(l, "weight_shape", source, where);
    const auto b = get<std::vector<int>>(l, "bias_shape", source, where);
    const bool same = get<int>(l, "in", source, where) == e.in &&
                      get<int>(l, "out", source, where) == e.out &&
                      get<int>(l, "kernel", source, where) == e.kernel &&
                      get<int>(l, "padding", source, where) == e.padding &&
                      get<bool>(l, "relu", source, where) == e.relu && w == weight &&
                      b == std::vector<int>{e.out};
    if (!same) {
      fail(source, "shape mismatch: layer \"" + e.name + "\" has weight " + shape_text(w) +
                       " bias " + shape_text(b) + " in the file, the architecture needs weight " +
                       shape_text(weight) + " bias [" + std::to_string(e.out) + "], padding " +
                       std::to_string(e.padding) + ", relu " + (e.relu ? "true" : "false"));
    }
  }
}

// The grid part of `features`: a physical grid (cell_size, multiple) or a fixed one (grid, arena).
void parse_grid(const json& j, int levels, const std::string& source, FeatureContract& f) {
  if (f.physical()) {
    f.multiple = get<int>(j, "multiple", source, "features");
    if (f.multiple != (1 << levels))
      fail(source, "shape mismatch: features.multiple is " + std::to_string(f.multiple) +
                       "; a network that pools " + std::to_string(levels) + " times needs " +
                       std::to_string(1 << levels));
    f.rows = f.cols = 0;
    f.width = f.height = 0.0;
    return;
  }
  const auto grid = get<std::vector<int>>(j, "grid", source, "features");
  const auto arena = get<std::vector<double>>(j, "arena", source, "features");
  if (grid.size() != 2 || grid[0] < 1 || grid[1] < 1 || grid[0] > 4096 || grid[1] > 4096) {
    fail(source, "shape mismatch: features.grid must be [rows, cols], got " + shape_text(grid));
  }
  if (arena.size() != 2 || !(arena[0] > 0) || !(arena[1] > 0)) {
    fail(source, "header: features.arena must be [width, height] in metres, both positive");
  }
  f.rows = grid[0];
  f.cols = grid[1];
  f.width = arena[0];
  f.height = arena[1];
}

// The physics_mean channel's scale and plume options. The ranges are
// cfd::AdvectionDiffusionOptions' (advection_diffusion_option_table), restated here since this
// library does not link cfd.
PhysicsChannel parse_physics(const json& c, const std::string& source, const std::string& where) {
  PhysicsChannel p;
  const auto number = [&](const char* key, bool zero_ok, double max, const char* what) {
    const double v = get<double>(c, key, source, where);
    if (!std::isfinite(v) || v < 0.0 || (v == 0.0 && !zero_ok) || v > max)
      fail(source,
           "header: " + where + "." + key + " is " + c.at(key).dump() + "; it must be " + what);
    return v;
  };
  const double huge = std::numeric_limits<double>::max();
  p.scale =
      number("scale", false, huge, "a positive finite number (input = concentration / scale)");
  p.diffusivity = number("diffusivity", false, 100.0, "in (0, 100] m^2/s");
  p.decay_rate = number("decay_rate", true, 100.0, "in [0, 100] 1/s");
  p.release_rate = number("release_rate", false, 1e9, "in (0, 1e9] concentration units * m^2/s");
  return p;
}

// What each channel's unit must be: the source channel's by its form.
std::string channel_unit(const std::string& name, bool inverse) {
  if (name == "region") return "label";
  if (name == "signed_distance") return "m";
  if (name == "physics_mean") return "concentration / scale";
  if (name == "source_distance") return inverse ? "1/m" : "m";
  return "m/s";  // wind_u, wind_v
}

std::string contract_text(bool physical, bool physics) {
  if (!physical)
    return "the feature contract is region (label), signed_distance (m), source_distance (m, or "
           "1/m in the inverse form)";
  return std::string(
             "a physical-grid model's contract is region (label), signed_distance (m), "
             "wind_u (m/s), wind_v (m/s), ") +
         (physics ? "physics_mean (concentration / scale), " : "") +
         "source_distance (m, or 1/m in the inverse form)";
}

FeatureContract parse_features(const json& j, int in_channels, int levels,
                               const std::string& source) {
  FeatureContract f;
  const bool physical = j.is_object() && j.contains("cell_size");
  if (physical) {
    if (j.contains("grid") || j.contains("arena"))
      fail(source,
           "header: features has cell_size (a physical grid) and grid or arena (a fixed "
           "one); a model has one or the other");
    f.cell_size = get<double>(j, "cell_size", source, "features");
    if (!std::isfinite(f.cell_size) || f.cell_size < 0.01 || f.cell_size > 10.0)
      fail(source, "header: features.cell_size must be a cell size in metres (0.01 .. 10)");
  }
  parse_grid(j, levels, source, f);
  const json& ch = j.contains("channels") ? j.at("channels") : json();
  if (!ch.is_array() || static_cast<int>(ch.size()) != in_channels) {
    fail(source, "shape mismatch: features.channels must list " + std::to_string(in_channels) +
                     " input channels");
  }
  // The contracts this engine's callers know how to build (surrogate/features.hpp): on a physical
  // grid, six channels are a hybrid model's (the physics plume before the source distance).
  // The source channel (the last) has a form that decides its unit: metres, or 1/m for the
  // inverse distance.
  const bool physics = physical && ch.size() == 6;
  const std::vector<std::string> names = feature_channel_names(physical, physics);
  if (ch.size() != names.size()) {
    fail(source, "shape mismatch: features.channels lists " + std::to_string(ch.size()) +
                     " channels; " +
                     (physical ? "a physical-grid model's contract has 5 (6 with physics_mean)"
                               : "the contract has 3"));
  }
  const std::size_t last = names.size() - 1;
  const std::string last_where = "features.channels[" + std::to_string(last) + "]";
  f.source_distance_form = get<std::string>(ch[last], "form", source, last_where);
  if (f.source_distance_form != "euclidean" && f.source_distance_form != "inverse") {
    fail(source, "header: source_distance form \"" + f.source_distance_form +
                     "\" is unknown; this engine builds \"euclidean\" (metres) and \"inverse\" "
                     "(1 / metres)");
  }
  const bool inverse = f.source_distance_form == "inverse";
  for (std::size_t i = 0; i < ch.size(); ++i) {
    const std::string where = "features.channels[" + std::to_string(i) + "]";
    FeatureChannel c{get<std::string>(ch[i], "name", source, where),
                     get<std::string>(ch[i], "unit", source, where)};
    if (c.name != names[i] || c.unit != channel_unit(names[i], inverse))
      fail(source, "header: " + where + " is \"" + c.name + "\" in \"" + c.unit + "\"; " +
                       contract_text(physical, physics));
    if (c.name == "physics_mean") {
      f.physics_channel = static_cast<int>(i);
      f.physics = parse_physics(ch[i], source, where);
    }
    f.channels.push_back(c);
  }
  // 1 / max(d, min_distance): by default half the smaller cell side, so the source's own cell
  // reads a finite value.
  f.source_min_distance =
      physical ? 0.5 * f.cell_size : 0.5 * std::min(f.width / f.cols, f.height / f.rows);
  if (inverse && ch[last].contains("min_distance")) {
    f.source_min_distance = get<double>(ch[last], "min_distance", source, last_where);
    if (!std::isfinite(f.source_min_distance) || f.source_min_distance <= 0.0)
      fail(source, "header: " + last_where + ".min_distance must be a positive number of metres");
  }
  return f;
}

}  // namespace

std::vector<std::string> feature_channel_names(bool physical, bool physics) {
  if (physical && physics)
    return {"region", "signed_distance", "wind_u", "wind_v", "physics_mean", "source_distance"};
  if (physical) return {"region", "signed_distance", "wind_u", "wind_v", "source_distance"};
  return {"region", "signed_distance", "source_distance"};
}

std::vector<LayerSpec> deepcfd_layers(const Architecture& a) {
  std::vector<LayerSpec> layers;
  const int levels = static_cast<int>(a.filters.size());
  const int n = a.convs_per_block;
  int prev = a.in_channels;
  for (int b = 0; b < levels; ++b) {
    for (int j = 0; j < n; ++j) {
      layers.push_back({"encoder." + std::to_string(b) + "." + std::to_string(j), LayerOp::kConv2d,
                        j == 0 ? prev : a.filters[b], a.filters[b], a.kernel, a.padding, true});
    }
    prev = a.filters[b];
  }
  for (int o = 0; o < a.out_channels; ++o) {
    for (int b = levels - 1; b >= 0; --b) {
      const int f = a.filters[b];
      const int last_out = b > 0 ? a.filters[b - 1] : 1;
      for (int j = 0; j < n; ++j) {
        const bool final_layer = b == 0 && j == n - 1;
        layers.push_back(
            {"decoder." + std::to_string(o) + "." + std::to_string(b) + "." + std::to_string(j),
             LayerOp::kConvTranspose2d, j == 0 ? 2 * f : f, j == n - 1 ? last_out : f, a.kernel,
             a.padding, !final_layer});
      }
    }
  }
  return layers;
}

std::size_t parameter_count(const std::vector<LayerSpec>& layers) {
  std::size_t n = 0;
  for (const auto& l : layers)
    n += l.parameter_count();
  return n;
}

namespace {

// The checked framing of a model file: prefix, header, tensor bytes and the trailing SHA-256.
struct Framing {
  json header;
  std::string_view header_bytes;
  std::size_t data_offset = 0;
  std::uint64_t data_bytes = 0;
  Sha256Digest digest{};
};

// The 16-byte prefix (magic, version, header length) and the header's JSON.
Framing read_prefix_and_header(std::string_view bytes, const std::string& source) {
  if (bytes.size() < kPrefix) {
    fail(source,
         "truncated: " + std::to_string(bytes.size()) + " bytes, shorter than the 16-byte prefix");
  }
  if (std::memcmp(bytes.data(), kModelMagic, sizeof kModelMagic) != 0) {
    fail(source, "wrong magic: not a plumekit-cnn model file (expected \"PLUMECNN\")");
  }
  const std::uint32_t version = read_u32_le(bytes.data() + 8);
  if (version != kModelVersion) {
    fail(source, "unknown version " + std::to_string(version) + " (this engine reads version " +
                     std::to_string(kModelVersion) + ")");
  }
  const std::size_t header_len = read_u32_le(bytes.data() + 12);
  if (bytes.size() < kPrefix + header_len) {
    fail(source, "truncated: the header needs " + std::to_string(header_len) + " bytes, " +
                     std::to_string(bytes.size() - kPrefix) + " remain");
  }
  Framing f;
  f.header_bytes = bytes.substr(kPrefix, header_len);
  try {
    f.header = json::parse(f.header_bytes);
  } catch (const json::exception& e) {
    fail(source, std::string("header is not valid JSON: ") + e.what());
  }
  const auto format = get<std::string>(f.header, "format", source, "header");
  if (format != "plumekit-cnn/1") {
    fail(source, "unknown version: header format \"" + format + "\", expected \"plumekit-cnn/1\"");
  }
  f.data_offset = (kPrefix + header_len + 15) / 16 * 16;
  return f;
}

// The file's size against the header's data_bytes, then the checksum over everything before it.
Framing read_framing(std::string_view bytes, const std::string& source) {
  Framing f = read_prefix_and_header(bytes, source);
  f.data_bytes = get<std::uint64_t>(f.header, "data_bytes", source, "header");
  if (f.data_bytes > bytes.size()) {
    fail(source, "truncated: the header announces " + std::to_string(f.data_bytes) +
                     " bytes of tensors, the file has " + std::to_string(bytes.size()));
  }
  const std::size_t expected_size = f.data_offset + f.data_bytes + kDigest;
  if (bytes.size() < expected_size) {
    fail(source, "truncated: " + std::to_string(bytes.size()) + " bytes, the header implies " +
                     std::to_string(expected_size));
  }
  if (bytes.size() > expected_size) {
    fail(source, std::to_string(bytes.size() - expected_size) +
                     " unexpected bytes after the checksum (file size " +
                     std::to_string(bytes.size()) + ", header implies " +
                     std::to_string(expected_size) + ")");
  }
  f.digest = sha256(bytes.substr(0, f.data_offset + f.data_bytes));
  if (std::memcmp(f.digest.data(), bytes.data() + f.data_offset + f.data_bytes, kDigest) != 0) {
    fail(source, "checksum mismatch: SHA-256 of the contents is " + to_hex(f.digest) +
                     ", the file says otherwise (the file is corrupt)");
  }
  return f;
}

json member_or_null(const json& header, const char* key) {
  return header.contains(key) ? header.at(key) : json();
}

// An output's "plus_input" (a residual output): only the mean's, only "physics_mean", and only
// when the model has that input channel.
std::string parse_plus_input(const json& o, const std::string& name, const FeatureContract& f,
                             const std::string& source, const std::string& where) {
  if (!o.contains("plus_input")) return "";
  const auto input = get<std::string>(o, "plus_input", source, where);
  if (input != "physics_mean")
    fail(source, "header: " + where + ".plus_input is \"" + input +
                     "\"; an output can add back only the \"physics_mean\" input");
  if (name != "mean")
    fail(source, "header: " + where + " (\"" + name +
                     "\") has plus_input; only the mean may be a residual over the physics plume");
  if (!f.has_physics())
    fail(source, "shape mismatch: " + where +
                     ".plus_input adds \"physics_mean\", which is not among the model's input "
                     "channels");
  return input;
}

std::vector<OutputSpec> parse_outputs(const json& outs, int out_channels,
                                      const FeatureContract& features, const std::string& source) {
  if (!outs.is_array() || static_cast<int>(outs.size()) != out_channels) {
    fail(source, "shape mismatch: \"outputs\" must describe " + std::to_string(out_channels) +
                     " output channels");
  }
  std::vector<OutputSpec> outputs;
  for (std::size_t i = 0; i < outs.size(); ++i) {
    const std::string where = "outputs[" + std::to_string(i) + "]";
    OutputSpec o;
    o.name = get<std::string>(outs[i], "name", source, where);
    o.unit = get<std::string>(outs[i], "unit", source, where);
    o.scale = get<float>(outs[i], "scale", source, where);
    if (!std::isfinite(o.scale)) fail(source, "header: " + where + ".scale is not finite");
    o.plus_input = parse_plus_input(outs[i], o.name, features, source, where);
    outputs.push_back(o);
  }
  return outputs;
}

// "trained_on": ranges [lo, hi] (finite, lo <= hi) and the inlets' walls.
TrainingRanges parse_trained_on(const json& j, const std::string& source) {
  TrainingRanges t;
  if (j.is_null()) return t;
  if (!j.is_object()) fail(source, "header: trained_on must be an object");
  const auto range = [&](const char* key) -> std::optional<ValueRange> {
    if (!j.contains(key)) return std::nullopt;
    const json& r = j.at(key);
    if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number() ||
        !std::isfinite(r[0].get<double>()) || !std::isfinite(r[1].get<double>()) ||
        r[0].get<double>() > r[1].get<double>())
      fail(source, std::string("header: trained_on.") + key + " must be [lo, hi], lo <= hi");
    return ValueRange{r[0].get<double>(), r[1].get<double>()};
  };
  t.map_width = range("map_width_m");
  t.map_height = range("map_height_m");
  t.inlet_speed = range("inlet_speed_m_s");
  t.openings = range("openings");
  if (j.contains("inlet_walls")) {
    const json& w = j.at("inlet_walls");
    if (!w.is_array()) fail(source, "header: trained_on.inlet_walls must be a list of walls");
    for (const json& side : w) {
      const std::string name = side.is_string() ? side.get<std::string>() : "";
      if (name != "left" && name != "right" && name != "bottom" && name != "top" &&
          name != "interior")
        fail(source, "header: trained_on.inlet_walls holds \"" + name +
                         "\"; walls are left, right, bottom, top, and interior (an inlet on an "
                         "obstacle's edge, a window)");
      t.inlet_walls.push_back(name);
    }
  }
  return t;
}

// The header's description of the network: architecture, layers, parameter count, features and
// outputs, each checked against the others.
void parse_description(const Framing& f, ModelFile& m, const std::string& source) {
  m.architecture = parse_architecture(member_or_null(f.header, "architecture"), source);
  m.layers = deepcfd_layers(m.architecture);
  check_layers(member_or_null(f.header, "layers"), m.layers, source);
  const std::size_t params = parameter_count(m.layers);
  if (get<std::uint64_t>(f.header, "parameter_count", source, "header") != params ||
      f.data_bytes != 4 * params) {
    fail(source, "shape mismatch: the architecture has " + std::to_string(params) +
                     " parameters (" + std::to_string(4 * params) + " bytes), the file holds " +
                     std::to_string(f.data_bytes) + " bytes");
  }
  const int levels = static_cast<int>(m.architecture.filters.size());
  m.features = parse_features(member_or_null(f.header, "features"), m.architecture.in_channels,
                              levels, source);
  if (!m.features.physical() &&
      ((m.features.rows >> levels) < 1 || (m.features.cols >> levels) < 1)) {
    fail(source, "shape mismatch: a " + std::to_string(m.features.rows) + "x" +
                     std::to_string(m.features.cols) + " grid cannot be pooled " +
                     std::to_string(levels) + " times");
  }
  m.outputs = parse_outputs(member_or_null(f.header, "outputs"), m.architecture.out_channels,
                            m.features, source);
  m.trained_on = parse_trained_on(member_or_null(f.header, "trained_on"), source);
}

// The tensors, in layer order: weight then bias, each value finite.
void read_tensors(const char* p, ModelFile& m, const std::string& source) {
  auto read_tensor = [&](const LayerSpec& l, std::size_t count, const char* what) {
    std::vector<float> t(count);
    for (std::size_t i = 0; i < count; ++i, p += 4) {
      t[i] = read_f32_le(p);
      if (!std::isfinite(t[i])) {
        fail(source, "NaN or infinite weight in layer \"" + l.name + "\" (" + what + " element " +
                         std::to_string(i) + ")");
      }
    }
    return t;
  };
  for (const LayerSpec& l : m.layers) {
    m.weights.push_back(read_tensor(l, l.weight_count(), "weight"));
    m.biases.push_back(read_tensor(l, static_cast<std::size_t>(l.out), "bias"));
  }
}

}  // namespace

ModelFile parse_model_file(std::string_view bytes, const std::string& source) {
  const Framing f = read_framing(bytes, source);
  ModelFile m;
  m.header_json = std::string(f.header_bytes);
  m.sha256_hex = to_hex(f.digest);
  parse_description(f, m, source);
  read_tensors(bytes.data() + f.data_offset, m, source);
  return m;
}

ModelFile read_model_file(const std::filesystem::path& path) {
  return parse_model_file(read_file(path), path.string());
}

}  // namespace plumekit::surrogate
