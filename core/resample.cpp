#include "core/resample.hpp"

#include <algorithm>
#include <stdexcept>

namespace plumekit {

namespace {

// The nearest free cell centre within 3 cells of `p`, or -1.
int nearest_free_cell(const GridShape& g, const std::vector<std::uint8_t>& solid, Vec2 p) {
  double best = 1e300;
  int bk = -1;
  const int ci = std::clamp(static_cast<int>(p.x / g.dx()), 0, g.nx - 1);
  const int cj = std::clamp(static_cast<int>(p.y / g.dy()), 0, g.ny - 1);
  for (int j = std::max(0, cj - 3); j <= std::min(g.ny - 1, cj + 3); ++j)
    for (int i = std::max(0, ci - 3); i <= std::min(g.nx - 1, ci + 3); ++i) {
      if (solid[g.index(i, j)]) continue;
      const double d = norm(g.centre(i, j) - p);
      if (d < best) best = d, bk = static_cast<int>(g.index(i, j));
    }
  return bk;
}

}  // namespace

std::vector<std::pair<int, double>> free_bilinear_weights(const GridShape& g,
                                                          const std::vector<std::uint8_t>& solid,
                                                          Vec2 p) {
  const GridShape::Bilinear b = g.bilinear(p);
  const double tx = b.tx, ty = b.ty;
  std::vector<std::pair<int, double>> w;
  double total = 0.0;
  auto add = [&](int i, int j, double weight) {
    const int k = static_cast<int>(g.index(i, j));
    if (solid[k] || weight <= 0.0) return;
    for (auto& e : w)
      if (e.first == k) {
        e.second += weight;
        total += weight;
        return;
      }
    w.emplace_back(k, weight);
    total += weight;
  };
  add(b.i0, b.j0, (1 - tx) * (1 - ty));
  add(b.i1, b.j0, tx * (1 - ty));
  add(b.i0, b.j1, (1 - tx) * ty);
  add(b.i1, b.j1, tx * ty);
  if (total <= 0.0) {
    // Every neighbouring centre is solid (a point hard against an obstacle).
    if (const int k = nearest_free_cell(g, solid, p); k >= 0) w.emplace_back(k, 1.0);
    return w;
  }
  for (auto& e : w)
    e.second /= total;
  return w;
}

GridResampler::GridResampler(const GridShape& s, const std::vector<std::uint8_t>& solid,
                             const GridShape& target)
    : source_(s), target_(target), begin_(target.size() + 1, 0) {
  // At most four weights per cell: reserved once, so that a fine target grid (ste's physics
  // model, millions of cells) never holds the old and the doubled array at once.
  weights_.reserve(4 * target.size());
  for (int j = 0; j < target.ny; ++j)
    for (int i = 0; i < target.nx; ++i) {
      const std::size_t c = target.index(i, j);
      const Vec2 p = target.centre(i, j);
      const int ci = std::min(s.nx - 1, static_cast<int>(p.x / s.dx()));
      const int cj = std::min(s.ny - 1, static_cast<int>(p.y / s.dy()));
      if (!solid[s.index(ci, cj)])  // inside an obstacle: no weights, 0
        for (const auto& w : free_bilinear_weights(s, solid, p))
          weights_.push_back(w);
      begin_[c + 1] = static_cast<int>(weights_.size());
    }
}

Grid<double> GridResampler::apply(const Grid<double>& field) const {
  if (field.shape.nx != source_.nx || field.shape.ny != source_.ny)
    throw std::logic_error("GridResampler: the field is not on the source grid");
  Grid<double> out(target_, 0.0);
  for (std::size_t c = 0; c < target_.size(); ++c) {
    if (begin_[c] == begin_[c + 1]) continue;
    double v = 0.0;
    for (int e = begin_[c]; e < begin_[c + 1]; ++e)
      v += weights_[e].second * field.values[weights_[e].first];
    out.values[c] = v;
  }
  return out;
}

}  // namespace plumekit
