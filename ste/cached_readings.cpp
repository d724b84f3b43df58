#include "ste/cached_readings.hpp"

#include <algorithm>
#include <iterator>

#include "core/thread_pool.hpp"

namespace plumekit::ste {

namespace {

std::vector<float> to_float(const std::vector<double>& v) {
  return std::vector<float>(v.begin(), v.end());
}

std::vector<double> to_double(const std::vector<float>& v) {
  return std::vector<double>(v.begin(), v.end());
}

}  // namespace

// Rows keyed by their exact point, at most `capacity` of them; the least recently used goes
// first. Thread-safe: runs on one map share it. A row is computed outside the lock, so two runs
// may compute the same one at once; both get the same values.
class CachedReadings::Recent {
 public:
  explicit Recent(std::size_t capacity) : capacity_(capacity) {}

  template <class Compute>
  std::vector<double> get(Vec2 p, Compute compute) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto it = rows_.find(p);
      if (it != rows_.end()) {
        order_.splice(order_.end(), order_, it->second.position);
        return to_double(it->second.values);
      }
    }
    std::vector<float> values = to_float(compute(p));
    std::vector<double> result = to_double(values);
    if (capacity_ == 0) return result;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (rows_.count(p) != 0) return result;
    if (rows_.size() == capacity_) {
      rows_.erase(order_.front());
      order_.pop_front();
    }
    order_.push_back(p);
    rows_.emplace(p, Row{std::prev(order_.end()), std::move(values)});
    return result;
  }

 private:
  struct Row {
    std::list<Vec2>::iterator position;  // in order_
    std::vector<float> values;
  };
  std::size_t capacity_;
  std::mutex mutex_;
  std::list<Vec2> order_;  // least recently used first
  std::unordered_map<Vec2, Row, Vec2Hash> rows_;
};

CachedReadings::CachedReadings(std::unique_ptr<SourceTableModel> model,
                               const std::vector<Vec2>& points, int threads, double recent_bytes)
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
  const double row_bytes = std::max(4.0, bytes_per_point(*model_));  // no division by 0 cells
  const auto capacity = static_cast<std::size_t>(std::max(0.0, recent_bytes) / row_bytes);
  recent_readings_ = std::make_unique<Recent>(capacity);
  recent_spreads_ = std::make_unique<Recent>(model_->has_spreads() ? capacity : 0);
}

CachedReadings::~CachedReadings() = default;

std::vector<double> CachedReadings::row(const std::vector<float>& table, std::size_t k) const {
  return std::vector<double>(table.begin() + k * cells_, table.begin() + (k + 1) * cells_);
}

std::vector<double> CachedReadings::readings_at(Vec2 p) const {
  const auto it = index_.find(p);
  if (it != index_.end()) return row(readings_, it->second);
  return recent_readings_->get(p, [&](Vec2 q) { return model_->readings_at(q); });
}

std::vector<double> CachedReadings::spreads_at(Vec2 p) const {
  if (spreads_.empty()) return model_->spreads_at(p);
  const auto it = index_.find(p);
  if (it != index_.end()) return row(spreads_, it->second);
  return recent_spreads_->get(p, [&](Vec2 q) { return model_->spreads_at(q); });
}

}  // namespace plumekit::ste
