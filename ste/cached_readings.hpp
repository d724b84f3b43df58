#pragma once
// A plume model whose readings at a fixed set of points are tabulated once per
// map. Navigation over a whole floor scores the same goals at every decision,
// and for the physics model each reading costs an adjoint solve: a table turns
// hundreds of solves per decision into lookups. Readings are kept as float32
// (memory: goals x source cells x 4 bytes); any other point is asked of the
// wrapped model.
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "ste/forward_model.hpp"

namespace plumekit::ste {

class CachedReadings final : public SourceTableModel {
 public:
  // Tabulates readings_at (and spreads_at, when the model has them) at every point, on
  // `threads` threads (0: one per core).
  CachedReadings(std::unique_ptr<SourceTableModel> model, const std::vector<Vec2>& points,
                 int threads);

  std::string name() const override { return model_->name(); }
  const std::vector<Parameter>& parameters() const override { return model_->parameters(); }
  const GridShape& candidates() const override { return model_->candidates(); }
  const std::vector<std::uint8_t>& allowed() const override { return model_->allowed(); }
  std::vector<double> readings_at(Vec2 p) const override;
  bool has_spreads() const override { return model_->has_spreads(); }
  std::vector<double> spreads_at(Vec2 p) const override;
  const SourceTableModel& wrapped() const { return *model_; }

 private:
  std::vector<double> row(const std::vector<float>& table, std::size_t k) const;

  std::unique_ptr<SourceTableModel> model_;
  std::unordered_map<Vec2, std::size_t, Vec2Hash> index_;
  std::size_t cells_ = 0;
  std::vector<float> readings_, spreads_;  // [point][cell]
};

}  // namespace plumekit::ste
