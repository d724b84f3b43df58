#pragma once
// A plume model whose readings at a fixed set of points are tabulated once per
// map, and whose readings at any other point are remembered for a while.
// Navigation over a whole floor scores the same goals at every decision, and
// for the physics model each reading costs an adjoint solve: a table turns
// hundreds of solves per decision into lookups. The lattice's moves lie on a
// fixed grid in the floor mode (ste/navigation.hpp), so a robot that moves
// half a metre finds most of its next moves already solved: the most recently
// used rows are kept up to a byte budget. Readings are kept as float32
// (memory: points x source cells x 4 bytes), and a row is rounded to float32
// whether it was remembered or not, so a run does not depend on what other
// runs on the same map asked before it.
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "ste/forward_model.hpp"

namespace plumekit::ste {

class CachedReadings final : public SourceTableModel {
 public:
  // Tabulates readings_at (and spreads_at, when the model has them) at every point, on
  // `threads` threads (0: one per core). Rows at other points are remembered up to
  // `recent_bytes` (0: none).
  CachedReadings(std::unique_ptr<SourceTableModel> model, const std::vector<Vec2>& points,
                 int threads, double recent_bytes = kRecentBytes);
  ~CachedReadings() override;

  std::string name() const override { return model_->name(); }
  const std::vector<Parameter>& parameters() const override { return model_->parameters(); }
  const GridShape& candidates() const override { return model_->candidates(); }
  const std::vector<std::uint8_t>& allowed() const override { return model_->allowed(); }
  std::vector<double> readings_at(Vec2 p) const override;
  bool has_spreads() const override { return model_->has_spreads(); }
  std::vector<double> spreads_at(Vec2 p) const override;
  const SourceTableModel& wrapped() const { return *model_; }

  // What one point's rows take for `model`: its readings (and spreads) at every source cell,
  // float32. The table and the remembered rows are both sized by it.
  static double bytes_per_point(const SourceTableModel& model) {
    return 4.0 * static_cast<double>(model.candidates().size()) * (model.has_spreads() ? 2.0 : 1.0);
  }
  // The default budget of remembered rows: 256 MiB.
  static constexpr double kRecentBytes = 256.0 * 1024 * 1024;

 private:
  class Recent;  // the remembered rows of one kind, least recently used first out
  std::vector<double> row(const std::vector<float>& table, std::size_t k) const;

  std::unique_ptr<SourceTableModel> model_;
  std::unordered_map<Vec2, std::size_t, Vec2Hash> index_;
  std::size_t cells_ = 0;
  std::vector<float> readings_, spreads_;  // [point][cell]
  std::unique_ptr<Recent> recent_readings_, recent_spreads_;
};

}  // namespace plumekit::ste
