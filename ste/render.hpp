#pragma once
// Pictures of STE runs, drawn with core's MapCanvas: a run's trajectory over
// the true mean plume with each sample coloured by its value, the final
// posterior, and the evaluation's box plots (thesis Figs. 14.8 and 14.9).
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "core/grid.hpp"
#include "core/map.hpp"
#include "ste/localizer.hpp"

namespace plumekit::ste {

// The trajectory (paths and samples) over `mean_plume`; the true source red,
// the start green, the estimate a magenta cross.
cv::Mat draw_trajectory(const Map& map, const Grid<double>& mean_plume,
                        const LocalizationResult& run, Vec2 source, const std::string& title);

// The posterior's (x, y) marginal, with the true source and the estimate.
cv::Mat draw_posterior(const Map& map, const Posterior& posterior, Vec2 source, Vec2 estimate,
                       const std::string& title);

// Box plots (median, quartiles, whiskers at 1.5 IQR, outliers as dots), one per group.
cv::Mat draw_box_plot(const std::vector<std::vector<double>>& groups,
                      const std::vector<std::string>& labels, const std::string& y_label,
                      const std::string& title, double reference_line = -1.0);

}  // namespace plumekit::ste
