#pragma once
// What `plumekit predict` reports: the model, the map and the source, the plume's peak and the
// timings, as the JSON summary and one human line. Assembled here so that apps/ only prints.
#include <string>

#include "core/report.hpp"
#include "surrogate/plume_network.hpp"

namespace plumekit::surrogate {

struct PredictRun {
  std::string model, map, out;  // as the user named them
  Vec2 source;                  // arena coordinates
  MapFrame frame;               // the map's: the report's positions are in it
  double predict_s = 0.0;       // the network's forward pass
  double seconds = 0.0;         // the whole command
};

// The unit of the model's "mean" output (model file `outputs[].unit`), "" when none is named.
std::string mean_unit(const Network& network);

Report prediction_report(const PredictRun& run, const PlumePrediction& p, const Network& network);

}  // namespace plumekit::surrogate
