#pragma once
// The surrogate as the rest of plumekit sees it: a network plus one map gives the plume of any
// source in that map's free space. The input features are built by the dataset module's own
// functions (dataset/features.hpp), so the network sees exactly what it was trained on.
#include <memory>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "core/map.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {

// One source's plume on the model's grid (64 x 64 cells over the arena).
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

class PlumeNetwork {
 public:
  // Builds the map-only feature channels once. Checks the model's feature contract against the map
  // and the dataset's features (grid 64 x 64, arena size, channel names, the source channel's
  // form: euclidean or inverse, an output named mean, and optionally std); InputError naming what
  // disagrees.
  PlumeNetwork(std::shared_ptr<const Network> network, const Map& map);

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
  // The network's input for one source, [3][ny][nx] (channels as in dataset/features.hpp; the
  // source channel in the model's form).
  std::vector<float> features(Vec2 source) const;

 private:
  void check_source(Vec2 source) const;

  std::shared_ptr<const Network> network_;
  std::shared_ptr<const Map> map_;
  GridShape grid_;
  std::vector<float> map_features_;         // channels 0 and 1, [2][ny][nx]
  std::vector<bool> obstacle_cell_;         // region label 0
  int mean_channel_ = 0, std_channel_ = 1;  // std_channel_ -1: a mean-only model
  std::vector<std::string> warnings_;
};

}  // namespace plumekit::surrogate
