#pragma once
// The surrogate as the rest of plumekit sees it: a network plus one map gives the plume of any
// source in that map's free space. The input features are built by the dataset module's own
// functions (surrogate/features.hpp), so the network sees exactly what it was trained on.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/error.hpp"
#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {

// One source's plume on the model's grid over the map: 64 x 64 cells over the arena (a thesis
// model), or the physical grid of the model's cell size (surrogate::physical_grid).
struct PlumePrediction {
  GridShape grid;
  // [ny][nx], row 0 at y = 0, in the model's output units (model file `outputs[].unit`). Cells
  // whose centre is inside an obstacle are 0 (as the dataset's targets), negative network outputs
  // are clamped to 0 (a concentration and its std are never negative).
  // std is empty for a mean-only model (PlumeNetwork::has_std).
  std::vector<float> mean, std;
  // The map, to answer 0 inside obstacles; shared by every prediction of one PlumeNetwork.
  std::shared_ptr<const Map> map;

  // Bilinear between cell centres (GridShape::bilinear; constant beyond the outermost centres),
  // 0 for a point inside (or on the boundary of) an obstacle.
  double mean_at(Vec2 p) const;
  double std_at(Vec2 p) const;  // 0 for a mean-only model
};

// Where `map` lies outside what the model was trained on (ModelFile::trained_on): one sentence
// each ("the map is 20 x 20 m; the model was trained on maps 6-12 m wide"), empty when inside it
// or when the file states no ranges.
std::vector<std::string> training_warnings(const TrainingRanges& trained_on, const Map& map);

// The wind a model that takes it is given: the map's steady flow (cfd::solve_wind, upwind if
// Newton stalls) on cells of `flow_cell` m, by default the v2 training data's 0.1 m; or, when
// `wind_dir` is given, the wind of that `plumekit flow` output for this map (cfd/wind_file.hpp).
inline constexpr double kModelWindCell = 0.1;
cfd::WindField model_wind(const Map& map, double flow_cell = kModelWindCell,
                          const std::filesystem::path& wind_dir = {});

// A fixed-grid model (a thesis model: 64 x 64 cells over the one arena size it was trained on)
// given a map of another size. Its own type, so that a caller that knows the alternatives (a
// physical-grid model, which fits any map, or another plume model) can name them.
class MapSizeError : public InputError {
 public:
  using InputError::InputError;
};

// MapSizeError when `contract` is a fixed-grid model's and its arena is not `map`'s size. Cheap:
// callers check it before a long build (the wind) as well as PlumeNetwork does.
void check_map_size(const FeatureContract& contract, const Map& map);

class PhysicsFeature;

class PlumeNetwork {
 public:
  // Builds the map-only feature channels once. Checks the model's feature contract against the map
  // and the dataset's features (a thesis model: grid 64 x 64 and the arena's size; channel names,
  // the source channel's form: euclidean or inverse, an output named mean, and optionally std);
  // InputError naming what disagrees. A model that takes the wind (a physical-grid model) needs
  // the map's steady wind (`wind`, used only here); InputError without it. A hybrid model (its
  // inputs hold physics_mean) gets its physics plume operator factored here, once, in that wind.
  PlumeNetwork(std::shared_ptr<const Network> network, const Map& map,
               const cfd::WindField* wind = nullptr);

  // InputError if `source` is not in the map's free space.
  PlumePrediction predict(Vec2 source) const;
  // The same results as predict() on each source, run `batch_size` samples per Network::predict
  // call (the network splits each batch among its threads).
  std::vector<PlumePrediction> predict_batch(const std::vector<Vec2>& sources,
                                             int batch_size = 32) const;

  const GridShape& grid() const { return grid_; }
  const Network& network() const { return *network_; }
  const Map& map() const { return *map_; }
  // training_warnings() for this map: the callers print them (predict, localize, evaluate).
  const std::vector<std::string>& warnings() const { return warnings_; }
  // Whether the model predicts the std of the readings (not a mean-only model).
  bool has_std() const { return std_channel_ >= 0; }
  // The network's input for one source, [channels][rows][cols] (channels as in
  // surrogate/features.hpp; the source channel in the model's form; a hybrid model's physics
  // plume divided by its channel's scale). For a physical-grid model, the map's grid padded with
  // zeros to input_rows() x input_cols().
  std::vector<float> features(Vec2 source) const;
  int input_rows() const { return rows_; }
  int input_cols() const { return cols_; }
  // Whether the model's inputs include the wind (it then needs one; see the constructor).
  static bool takes_wind(const Network& network) { return network.file().features.has_wind(); }

 private:
  void check_source(Vec2 source) const;

  std::shared_ptr<const Network> network_;
  std::shared_ptr<const Map> map_;
  GridShape grid_;
  int rows_ = 0, cols_ = 0;  // the network's input size (grid_, or padded)
  int channels_ = 0;         // input channels
  // The map's channels (all but the source's and the physics plume's), padded, in input order.
  std::vector<float> map_features_;
  // A hybrid model's physics plume, one forward solve per source; null for other models. Its
  // solves, the most of a batch's cost, run on threads of their own, as many as the engine's.
  std::shared_ptr<const PhysicsFeature> physics_;
  std::shared_ptr<ThreadPool> physics_threads_;
  std::vector<bool> obstacle_cell_;         // region label 0
  int mean_channel_ = 0, std_channel_ = 1;  // std_channel_ -1: a mean-only model
  std::vector<std::string> warnings_;
};

}  // namespace plumekit::surrogate
