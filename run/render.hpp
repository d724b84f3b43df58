#pragma once
// Pictures of STE runs, drawn with core's MapCanvas: a run's trajectory over
// the true mean plume with each sample coloured by its value, the final
// posterior, and the evaluation's box plots (thesis Figs. 14.8 and 14.9).
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "core/grid.hpp"
#include "map/map.hpp"
#include "map/map_render.hpp"
#include "run/evaluation.hpp"
#include "run/run_record.hpp"

namespace plumekit::run {

// The run a picture shows. Its title is built from these fields only, so a
// title cannot describe another run than the one drawn.
struct RunToDraw {
  const LocalizationResult* result = nullptr;
  Vec2 source;            // the true source
  int source_index = -1;  // its index among the map's sources; -1: not one of them
  int run = -1;           // the run's number for its source; -1: a single run
  std::string model;      // plume model, e.g. "surrogate"
  // Why this run was picked, e.g. "median error of 30 runs"; empty for none.
  std::string chosen_as;
};
// An evaluation run (all fields from the record).
RunToDraw run_to_draw(const RunRecord& record, const std::string& model,
                      const std::string& chosen_as = "");
// A single run (localize, demo); the source index is looked up among the map's sources.
RunToDraw run_to_draw(const Map& map, const LocalizationResult& result, Vec2 source,
                      const std::string& model);

// "<map>: <model>, source S1 run 2: error 0.42 m, 18 samples, 23.1 m travelled,
// stopped by entropy (<chosen_as>)": every number from `run`.
std::string trajectory_title(const Map& map, const RunToDraw& run);

// The trajectory (paths and samples) over `mean_plume`: the true source, the
// start, the estimate, each sample coloured on the plume's colour scale.
Picture draw_trajectory(const Map& map, const Grid<double>& mean_plume, const RunToDraw& run,
                        const RenderOptions& options = {});

// The run's final posterior (x, y) marginal, with the true source and the estimate.
Picture draw_posterior(const Map& map, const RunToDraw& run, const RenderOptions& options = {});

// Box plots (median, quartiles, whiskers at 1.5 IQR, outliers as dots), one
// per group, each named and with its number of values.
struct BoxPlot {
  std::vector<std::vector<double>> groups;
  std::vector<std::string> names;  // one per group
  std::string title, y_label, x_label = "test map";
  double reference = -1.0;  // a horizontal line where > 0, e.g. the success radius
  std::string reference_label;
};
Picture draw_box_plot(const BoxPlot& plot);

// Shorthand for the evaluation's plots: `names` label the groups.
Picture draw_box_plot(const std::vector<std::vector<double>>& groups,
                      const std::vector<std::string>& names, const std::string& y_label,
                      const std::string& title, double reference_line = -1.0);

}  // namespace plumekit::run
