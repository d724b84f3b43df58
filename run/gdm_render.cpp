#include "run/gdm_render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/option_check.hpp"

namespace plumekit::run {

namespace {

struct Panel {
  const Grid<double>* field;
  std::string title, label;
  double lo, hi;
  bool peak;  // mark the peak (a source estimate; not for the confidence)
};

// The largest finite value's cell centre and value.
std::pair<Vec2, double> peak_of(const Grid<double>& f) {
  double top = -std::numeric_limits<double>::infinity();
  Vec2 at;
  for (int j = 0; j < f.shape.ny; ++j)
    for (int i = 0; i < f.shape.nx; ++i)
      if (std::isfinite(f(i, j)) && f(i, j) > top) top = f(i, j), at = f.shape.centre(i, j);
  return {at, top};
}

Picture draw_panel(const Map& map, const Panel& p, const std::vector<methods::Sample>& samples,
                   const std::optional<Vec2>& source, const RenderOptions& options) {
  Map shown = map;
  shown.sources.clear();  // the true source, when known, is drawn below
  ColourBar bar{p.lo, p.hi, p.label};
  bar.uniform = !(p.hi > p.lo);
  Frame frame{p.title, bar, {}, true};
  frame.legend.push_back({LegendEntry::Symbol::Dot, colours::kPath, "sample"});
  if (p.peak) frame.legend.push_back({LegendEntry::Symbol::Cross, colours::kEstimate, "peak"});
  if (source) frame.legend.push_back({LegendEntry::Symbol::Dot, colours::kSource, "true source"});
  MapCanvas canvas(shown, options, frame);
  canvas.draw_free_space();
  canvas.draw_field(*p.field, p.lo, bar.uniform ? p.lo + 1.0 : p.hi);
  canvas.draw_obstacles();
  canvas.draw_walls_and_openings();
  for (const methods::Sample& s : samples)
    if (map.in_arena(s.position)) canvas.draw_marker(s.position, colours::kPath, 2);
  if (source) canvas.draw_marker(*source, colours::kSource, 5);
  if (p.peak) canvas.draw_cross(peak_of(*p.field).first, colours::kEstimate);
  return canvas.finish();
}

}  // namespace

Picture draw_gdm(const Map& map, const methods::GdmMaps& maps,
                 const std::vector<methods::Sample>& samples, const std::optional<Vec2>& source,
                 const std::string& method, const std::string& unit, const RenderOptions& options) {
  const std::string u = unit.empty() ? "concentration units" : unit;
  const std::string head = (map.name.empty() ? "map" : map.name) + ": " + method + ", " +
                           std::to_string(maps.samples) + " samples";
  const double mean_peak = peak_of(maps.mean).second, var_peak = peak_of(maps.variance).second;
  const std::vector<Panel> panels{
      {&maps.mean, head + ": mean, peak " + compact(mean_peak), "mean [" + u + "]",
       std::min(0.0, maps.background_mean), mean_peak, true},
      {&maps.variance, head + ": variance, peak " + compact(var_peak), "variance [(" + u + ")^2]",
       0.0, var_peak, true},
      {&maps.confidence, head + ": confidence", "confidence", 0.0, 1.0, false}};
  std::vector<Picture> pictures;
  for (const Panel& p : panels)
    pictures.push_back(draw_panel(map, p, samples, source, options));
  return stack_pictures(pictures);
}

}  // namespace plumekit::run
