#include "ste/cached_readings.hpp"

#include "core/thread_pool.hpp"

namespace plumekit::ste {

CachedReadings::CachedReadings(std::unique_ptr<SourceTableModel> model,
                               const std::vector<Vec2>& points, int threads)
    : model_(std::move(model)), cells_(model_->candidates().size()) {
  std::vector<Vec2> unique;
  for (const Vec2& p : points)
    if (index_.emplace(p, unique.size()).second) unique.push_back(p);
  readings_.resize(unique.size() * cells_);
  if (model_->has_spreads()) spreads_.resize(unique.size() * cells_);
  ThreadPool pool(threads);
  pool.parallel_for(unique.size(), [&](std::size_t k) {
    const std::vector<double> r = model_->readings_at(unique[k]);
    std::copy(r.begin(), r.end(), readings_.begin() + k * cells_);
    if (spreads_.empty()) return;
    const std::vector<double> s = model_->spreads_at(unique[k]);
    std::copy(s.begin(), s.end(), spreads_.begin() + k * cells_);
  });
}

std::vector<double> CachedReadings::row(const std::vector<float>& table, std::size_t k) const {
  return std::vector<double>(table.begin() + k * cells_, table.begin() + (k + 1) * cells_);
}

std::vector<double> CachedReadings::readings_at(Vec2 p) const {
  const auto it = index_.find(p);
  return it == index_.end() ? model_->readings_at(p) : row(readings_, it->second);
}

std::vector<double> CachedReadings::spreads_at(Vec2 p) const {
  const auto it = index_.find(p);
  if (it == index_.end() || spreads_.empty()) return model_->spreads_at(p);
  return row(spreads_, it->second);
}

}  // namespace plumekit::ste
