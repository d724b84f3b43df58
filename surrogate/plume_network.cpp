#include "surrogate/plume_network.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "cfd/flow_policy.hpp"
#include "cfd/wind_file.hpp"
#include "core/error.hpp"
#include "core/thread_pool.hpp"
#include "surrogate/features.hpp"

namespace plumekit::surrogate {

namespace {

double sample(const GridShape& g, const std::vector<float>& v, const Map* map, Vec2 p) {
  if (map && map->obstacle_at(p) >= 0) return 0.0;
  const GridShape::Bilinear b = g.bilinear(p);
  const auto f = [&](int i, int j) { return static_cast<double>(v[g.index(i, j)]); };
  return (1 - b.tx) * (1 - b.ty) * f(b.i0, b.j0) + b.tx * (1 - b.ty) * f(b.i1, b.j0) +
         (1 - b.tx) * b.ty * f(b.i0, b.j1) + b.tx * b.ty * f(b.i1, b.j1);
}

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

bool same_length(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)});
}

}  // namespace

std::vector<std::string> training_warnings(const TrainingRanges& t, const Map& map) {
  std::vector<std::string> out;
  const auto range = [](const ValueRange& r) { return fmt(r.lo) + "-" + fmt(r.hi); };
  if ((t.map_width && !t.map_width->contains(map.width)) ||
      (t.map_height && !t.map_height->contains(map.height))) {
    std::string trained;
    if (t.map_width) trained += range(*t.map_width) + " m wide";
    if (t.map_height)
      trained += std::string(trained.empty() ? "" : " and ") + range(*t.map_height) + " m high";
    out.push_back("the map is " + fmt(map.width) + " x " + fmt(map.height) +
                  " m; the model was trained on maps " + trained);
  }
  const double openings = static_cast<double>(map.openings.size());
  if (t.openings && !t.openings->contains(openings))
    out.push_back("the map has " + fmt(openings) + " openings; the model was trained on " +
                  range(*t.openings));
  for (const Opening& o : map.openings) {
    if (!o.is_inlet()) continue;
    const std::string at = "the inlet at " + to_string(map.to_frame(o.from));  // the map's frame
    if (t.inlet_speed && !t.inlet_speed->contains(o.speed))
      out.push_back(at + " blows at " + fmt(o.speed) + " m/s; the model was trained on " +
                    range(*t.inlet_speed) + " m/s");
    if (t.inlet_walls.empty()) continue;
    const std::optional<Side> side = map.wall_of(o);
    const std::string wall = side ? to_string(*side) : "interior";
    if (std::find(t.inlet_walls.begin(), t.inlet_walls.end(), wall) == t.inlet_walls.end()) {
      std::string walls;
      for (const std::string& w : t.inlet_walls)
        walls += (walls.empty() ? "" : ", ") +
                 (w == "interior" ? std::string("obstacle edges (windows)") : "the " + w + " wall");
      out.push_back(at + " is " + (side ? "on the " + wall + " wall" : "not on an arena wall") +
                    "; the model was trained with inlets on " + walls);
    }
  }
  return out;
}

void check_map_size(const FeatureContract& c, const Map& map) {
  if (c.physical() || (same_length(c.width, map.width) && same_length(c.height, map.height)))
    return;
  throw MapSizeError("the surrogate model works only on maps of " + fmt(c.width) + " x " +
                     fmt(c.height) +
                     " m (a fixed-grid model, trained on that arena alone); map \"" + map.name +
                     "\" is " + fmt(map.width) + " x " + fmt(map.height) + " m");
}

cfd::WindField model_wind(const Map& map, double flow_cell, const std::filesystem::path& wind_dir) {
  if (!wind_dir.empty()) return cfd::read_wind(wind_dir, map);
  cfd::FlowOptions o;
  o.cell = flow_cell;
  return cfd::solve_wind(map, o).flow.wind;
}

double PlumePrediction::mean_at(Vec2 p) const {
  return sample(grid, mean, map.get(), p);
}
double PlumePrediction::std_at(Vec2 p) const {
  return std.empty() ? 0.0 : sample(grid, std, map.get(), p);
}

namespace {

// The checks of PlumeNetwork's constructor that need only the model, the map and the wind: the
// feature contract this engine builds (thesis grid 64 x 64 over the map's arena, or a physical
// grid), the channel names, the wind a physical-grid model reads. InputError prefixed by `who`.
void check_contract(const ModelFile& f, const Map& map, const cfd::WindField* wind,
                    const std::string& who) {
  const FeatureContract& c = f.features;
  if (!c.physical() && (c.rows != surrogate::kFeatureGrid || c.cols != surrogate::kFeatureGrid)) {
    throw InputError(who + "the model's grid is " + std::to_string(c.rows) + "x" +
                     std::to_string(c.cols) + ", the dataset's features are " +
                     std::to_string(surrogate::kFeatureGrid) + "x" +
                     std::to_string(surrogate::kFeatureGrid));
  }
  check_map_size(c, map);
  const std::vector<std::string> names = feature_channel_names(c.physical(), c.has_physics());
  const int n_in = static_cast<int>(names.size());
  if (f.architecture.in_channels != n_in || static_cast<int>(c.channels.size()) != n_in) {
    std::string list;
    for (const std::string& n : names)
      list += (list.empty() ? "" : ", ") + n;
    throw InputError(who + "the model takes " + std::to_string(f.architecture.in_channels) +
                     " input channels, the dataset's features are " + std::to_string(n_in) + " (" +
                     list + ")");
  }
  for (int i = 0; i < n_in; ++i) {
    if (c.channels[i].name != names[i]) {
      throw InputError(who + "input channel " + std::to_string(i) + " is \"" + c.channels[i].name +
                       "\", the dataset's is \"" + names[i] + "\"");
    }
  }
  if (c.has_wind() && !wind)
    throw InputError(who + "the model takes the map's wind as an input" +
                     (c.has_physics() ? " (and its physics plume in that wind)" : "") +
                     "; solve it first");
  if (c.has_wind() && (!same_length(wind->shape().width, map.width) ||
                       !same_length(wind->shape().height, map.height)))
    throw InputError(who + "the wind given covers " + fmt(wind->shape().width) + " x " +
                     fmt(wind->shape().height) + " m, the map is " + fmt(map.width) + " x " +
                     fmt(map.height) + " m: it is another map's");
  if (c.source_distance_form != "euclidean" && c.source_distance_form != "inverse") {
    throw InputError(who + "source_distance form \"" + c.source_distance_form +
                     "\", this engine builds \"euclidean\" and \"inverse\"");
  }
}

cfd::AdvectionDiffusionOptions physics_options(const PhysicsChannel& p) {
  cfd::AdvectionDiffusionOptions o;
  o.diffusivity = p.diffusivity;
  o.decay_rate = p.decay_rate;
  o.release_rate = p.release_rate;
  return o;
}

}  // namespace

PlumeNetwork::PlumeNetwork(std::shared_ptr<const Network> network, const Map& map,
                           const cfd::WindField* wind)
    : network_(std::move(network)), map_(std::make_shared<const Map>(map)) {
  if (!network_) throw std::invalid_argument("PlumeNetwork: null network");
  const ModelFile& f = network_->file();
  const FeatureContract& c = f.features;
  const std::string who = "the surrogate model does not fit map \"" + map.name + "\": ";
  check_contract(f, map, wind, who);
  mean_channel_ = std_channel_ = -1;
  for (std::size_t o = 0; o < f.outputs.size(); ++o) {
    if (f.outputs[o].name == "mean") mean_channel_ = static_cast<int>(o);
    if (f.outputs[o].name == "std") std_channel_ = static_cast<int>(o);
  }
  // A mean-only model (a DeepCFD network of one output) predicts no std.
  if (mean_channel_ < 0) throw InputError(who + "the model's outputs must include \"mean\"");

  warnings_ = training_warnings(f.trained_on, map);
  channels_ = static_cast<int>(c.channels.size());
  if (c.physical()) {
    grid_ = surrogate::physical_grid(map, c.cell_size);
    const auto up = [&](int n) { return (n + c.multiple - 1) / c.multiple * c.multiple; };
    rows_ = up(grid_.ny);
    cols_ = up(grid_.nx);
    if (rows_ > Network::kMaxInputSide || cols_ > Network::kMaxInputSide)
      throw InputError(who + "the map's grid of " + std::to_string(grid_.nx) + " x " +
                       std::to_string(grid_.ny) + " cells of " + fmt(c.cell_size) +
                       " m is larger than the engine's " + std::to_string(Network::kMaxInputSide) +
                       " cells a side");
  } else {
    grid_ = surrogate::feature_grid(map);
    rows_ = grid_.ny;
    cols_ = grid_.nx;
  }
  // The map's channels on its grid, then copied into the padded input planes (zeros beyond).
  std::vector<float> planes = surrogate::map_features(map, grid_);
  if (c.has_wind()) {
    const std::vector<float> w = surrogate::wind_features(*wind, grid_);
    planes.insert(planes.end(), w.begin(), w.end());
  }
  // The physics plume's operator depends on the wind alone: factored once, here.
  if (c.has_physics()) {
    physics_ =
        std::make_shared<const PhysicsFeature>(map, *wind, grid_, physics_options(c.physics));
    physics_threads_ = std::make_shared<ThreadPool>(network_->threads());
  }
  const int map_channels = static_cast<int>(planes.size() / grid_.size());
  const std::size_t plane = static_cast<std::size_t>(rows_) * cols_;
  map_features_.assign(map_channels * plane, 0.0f);
  for (int ch = 0; ch < map_channels; ++ch)
    for (int j = 0; j < grid_.ny; ++j)
      std::copy_n(planes.begin() + (ch * grid_.size() + grid_.index(0, j)), grid_.nx,
                  map_features_.begin() + (ch * plane + static_cast<std::size_t>(j) * cols_));
  obstacle_cell_.resize(grid_.size());
  for (std::size_t k = 0; k < grid_.size(); ++k)
    obstacle_cell_[k] = planes[k] == 0.0f;  // region label 0: centre inside an obstacle
}

void PlumeNetwork::check_source(Vec2 source) const {
  // In the map's frame, as every other message (point_fault).
  if (const std::string fault = point_fault(*map_, source); !fault.empty())
    throw InputError("source " + fault);
}

std::vector<float> PlumeNetwork::features(Vec2 source) const {
  // The map's channels come first; the physics plume (a hybrid model's) and the source distance
  // follow, in the contract's order.
  std::vector<float> x = map_features_;
  const FeatureContract& c = network_->file().features;
  const std::size_t plane = static_cast<std::size_t>(rows_) * cols_;
  x.resize(channels_ * plane, 0.0f);
  if (physics_) {
    const Grid<double> phys = (*physics_)(source);
    float* to = x.data() + c.physics_channel * plane;
    for (int j = 0; j < grid_.ny; ++j)
      for (int i = 0; i < grid_.nx; ++i)
        to[static_cast<std::size_t>(j) * cols_ + i] =
            static_cast<float>(phys.values[grid_.index(i, j)] / c.physics.scale);
  }
  const std::vector<float> d = surrogate::source_feature(source, grid_);
  const std::size_t first = (channels_ - 1) * plane;
  const bool inverse = c.source_distance_form == "inverse";
  for (int j = 0; j < grid_.ny; ++j)
    for (int i = 0; i < grid_.nx; ++i) {
      const double v = d[grid_.index(i, j)];
      x[first + static_cast<std::size_t>(j) * cols_ + i] =
          inverse ? static_cast<float>(1.0 / std::max(v, c.source_min_distance))
                  : static_cast<float>(v);
    }
  return x;
}

PlumePrediction PlumeNetwork::predict(Vec2 source) const {
  return std::move(predict_batch({source}, 1).front());
}

std::vector<PlumePrediction> PlumeNetwork::predict_batch(const std::vector<Vec2>& sources,
                                                         int batch_size) const {
  if (batch_size < 1) throw std::invalid_argument("PlumeNetwork::predict_batch: batch_size < 1");
  for (Vec2 s : sources)
    check_source(s);
  const std::size_t cells = grid_.size();
  const std::size_t plane = static_cast<std::size_t>(rows_) * cols_;
  const std::vector<OutputSpec>& outputs = network_->file().outputs;
  const FeatureContract& contract = network_->file().features;
  std::vector<PlumePrediction> out;
  out.reserve(sources.size());
  for (std::size_t first = 0; first < sources.size(); first += batch_size) {
    const int n = static_cast<int>(std::min<std::size_t>(batch_size, sources.size() - first));
    Tensor input(n, channels_, rows_, cols_);
    // Each sample's input on its own (a hybrid's physics solve is most of the batch's time): the
    // same bytes whatever the thread count.
    const auto fill = [&](std::size_t i) {
      const std::vector<float> x = features(sources[first + i]);
      std::copy(x.begin(), x.end(), input.sample_data(static_cast<int>(i)));
    };
    if (physics_threads_)
      physics_threads_->parallel_for(static_cast<std::size_t>(n), fill);
    else
      for (int i = 0; i < n; ++i)
        fill(static_cast<std::size_t>(i));
    const Tensor y = network_->predict(input);
    for (int i = 0; i < n; ++i) {
      PlumePrediction p;
      p.grid = grid_;
      p.map = map_;
      // The map's cells of the (possibly padded) output planes; a residual output adds its input
      // back first (residual_output), so the clamp applies to the sum.
      const auto crop = [&](int channel, std::vector<float>& to) {
        const float* v = y.sample_data(i) + plane * channel;
        const bool residual = !outputs[channel].plus_input.empty();
        const float* x =
            residual ? input.sample_data(i) + plane * contract.physics_channel : nullptr;
        to.resize(cells);
        for (int j = 0; j < grid_.ny; ++j)
          for (int c = 0; c < grid_.nx; ++c) {
            const std::size_t k = grid_.index(c, j), q = static_cast<std::size_t>(j) * cols_ + c;
            const float value =
                residual ? residual_output(v[q], x[q], contract.physics.scale) : v[q];
            to[k] = obstacle_cell_[k] ? 0.0f : std::max(0.0f, value);
          }
      };
      crop(mean_channel_, p.mean);
      if (std_channel_ >= 0) crop(std_channel_, p.std);
      out.push_back(std::move(p));
    }
  }
  return out;
}

}  // namespace plumekit::surrogate
