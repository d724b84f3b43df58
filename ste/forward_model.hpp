#pragma once
// The forward model: one interface for every plume model STE can estimate with,
// the predicted mean concentration at a set of points for one parameter vector. The first
// two parameters are always the source's x and y (metres).
//
// Models whose only free quantity besides the source position is the release
// rate (surrogate, physics) also answer the dual question cheaply: what a
// sensor at one point reads for every candidate source cell at once. That is
// a SourceTableModel; the exact grid estimator uses it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::ste {

struct Parameter {
  std::string name;
  double lo = 0.0, hi = 0.0;  // the uniform prior's bounds
};

class ForwardModel {
 public:
  virtual ~ForwardModel() = default;
  virtual std::string name() const = 0;
  // Layout and prior bounds of the parameter vector; [0], [1] are x, y.
  virtual const std::vector<Parameter>& parameters() const = 0;
  // Mean concentration (dataset units) at each point for `params`.
  virtual std::vector<double> predict(const std::vector<double>& params,
                                      const std::vector<Vec2>& points) const = 0;
  // One point; models override it when they can avoid predict()'s vectors.
  virtual double predict_at(const double* params, Vec2 p) const;
  // The model as a table of candidate sources (the surrogate's and physics' grid estimators
  // read it), or null for a model of free parameters (the Gaussian plume's MH).
  virtual const class SourceTableModel* as_source_table() const { return nullptr; }
};

// Parameters {x, y, release_scale}: the concentration is release_scale times
// the unit-release prediction of a source at (x, y), which is tabulated on a
// grid of source cells.
class SourceTableModel : public ForwardModel {
 public:
  const SourceTableModel* as_source_table() const override { return this; }
  // The candidate source cells; a source is only possible at allowed cells
  // (free cell centres): the prior is zero inside obstacles.
  virtual const GridShape& candidates() const = 0;
  virtual const std::vector<std::uint8_t>& allowed() const = 0;
  // What a sensor at `p` reads, at release scale 1, for a source at each cell
  // of candidates() (0 at cells that are not allowed). Thread-safe.
  virtual std::vector<double> readings_at(Vec2 p) const = 0;
  // Whether the model also predicts how much the readings scatter (their std), and that std at
  // `p`, at release scale 1, per cell like readings_at (empty when the model has none).
  virtual bool has_spreads() const { return false; }
  virtual std::vector<double> spreads_at(Vec2) const { return {}; }

  // Generic form: the nearest allowed cell's reading times the scale (slow:
  // one readings_at per point; the estimators use readings_at directly).
  std::vector<double> predict(const std::vector<double>& params,
                              const std::vector<Vec2>& points) const override;
  // The allowed cell nearest to (x, y) (by centre), or -1 if none.
  int nearest_allowed(Vec2 p) const;
};

// Marks the cells of `shape` whose centre is free in `map` and at least
// `clearance` metres from every obstacle and arena wall.
std::vector<std::uint8_t> free_cells(const Map& map, const GridShape& shape, double clearance);

}  // namespace plumekit::ste
