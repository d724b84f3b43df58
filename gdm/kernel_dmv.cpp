#include "gdm/kernel_dmv.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/option_check.hpp"

namespace plumekit::gdm {

namespace {

constexpr double kPi = 3.14159265358979323846;

// One reading's kernel: the inverse covariance of its Gaussian, the reach of its cutoff box, and
// its normalisation 1 / (2 pi a b) = 1 / (2 pi sigma^2) (the areas are equal).
struct Kernel {
  double ixx = 0, ixy = 0, iyy = 0;  // Sigma^-1
  double reach = 0;                  // m, half the side of the box it is summed over
  double norm = 0;
};

Kernel kernel_of(const Sample& s, const GdmOptions& o) {
  const double sigma = o.kernel_width;
  double a = sigma, b = sigma, cs = 1.0, sn = 0.0;
  if (o.wind_stretch > 0.0 && s.wind) {
    const double speed = norm(*s.wind);
    if (speed > 0.0) {
      a = sigma + o.wind_stretch * speed;
      b = sigma / (1.0 + o.wind_stretch * speed / sigma);
      cs = s.wind->x / speed;
      sn = s.wind->y / speed;
    }
  }
  // Sigma = R diag(a^2, b^2) R^T; a and b are standard deviations along and across the wind.
  const double ia = 1.0 / (a * a), ib = 1.0 / (b * b);
  Kernel k;
  k.ixx = cs * cs * ia + sn * sn * ib;
  k.iyy = sn * sn * ia + cs * cs * ib;
  k.ixy = cs * sn * (ia - ib);
  k.reach = o.cutoff * std::max(a, b);
  k.norm = 1.0 / (2.0 * kPi * a * b);
  return k;
}

// Calls f(cell index, weight) for every cell within the kernel's box around s.
template <class F>
void for_each_weight(const GridShape& g, const Sample& s, const Kernel& k, F&& f) {
  const int i0 = std::max(0, static_cast<int>(std::floor((s.position.x - k.reach) / g.dx())));
  const int i1 =
      std::min(g.nx - 1, static_cast<int>(std::floor((s.position.x + k.reach) / g.dx())));
  const int j0 = std::max(0, static_cast<int>(std::floor((s.position.y - k.reach) / g.dy())));
  const int j1 =
      std::min(g.ny - 1, static_cast<int>(std::floor((s.position.y + k.reach) / g.dy())));
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Vec2 d = g.centre(i, j) - s.position;
      const double m2 = k.ixx * d.x * d.x + 2.0 * k.ixy * d.x * d.y + k.iyy * d.y * d.y;
      f(g.index(i, j), k.norm * std::exp(-0.5 * m2));
    }
}

void check_samples(const std::vector<Sample>& samples) {
  if (samples.empty()) throw InputError("gdm: no samples to map");
  for (std::size_t n = 0; n < samples.size(); ++n) {
    const Sample& s = samples[n];
    const bool wind_ok = !s.wind || (std::isfinite(s.wind->x) && std::isfinite(s.wind->y));
    if (!std::isfinite(s.position.x) || !std::isfinite(s.position.y) || !std::isfinite(s.reading) ||
        !wind_ok)
      throw InputError("gdm: sample " + std::to_string(n + 1) + " is not finite");
  }
}

}  // namespace

const char* to_string(Background b) {
  return b == Background::Mean ? "mean" : "min";
}

Background parse_background(const std::string& name) {
  if (name == "mean") return Background::Mean;
  if (name == "min") return Background::Min;
  throw OptionError("gdm.background", "unknown background '" + name + "'; use mean or min");
}

void GdmOptions::validate() const {
  check_positive("gdm.cell", cell, 10.0, "m", "the default is 0.1 m");
  check_positive("gdm.kernel_width", kernel_width, 100.0, "m", "the default is 0.4 m");
  check_positive("gdm.sigma_omega", sigma_omega, 1e6, "", "the default is 1");
  check_non_negative("gdm.wind_stretch", wind_stretch, 100.0, "s",
                     "0 (the default) gives Kernel DM+V; the seed used 0.2-0.6 s");
  check_range("gdm.cutoff", cutoff, 1.0, 10.0, "kernel widths", "the default is 4");
}

GdmMaps kernel_dmv(const Map& map, const std::vector<Sample>& samples, const GdmOptions& o) {
  o.validate();
  check_samples(samples);
  const GridShape g = GridShape::with_cell(map.width, map.height, o.cell);
  std::vector<Kernel> kernels;
  double sum = 0.0, lowest = samples[0].reading;
  for (const Sample& s : samples) {
    kernels.push_back(kernel_of(s, o));
    sum += s.reading;
    lowest = std::min(lowest, s.reading);
  }
  GdmMaps m;
  m.samples = static_cast<int>(samples.size());
  m.background_mean = o.background == Background::Mean ? sum / samples.size() : lowest;
  // Omega and R (eqs. 7.9, 7.10), then the confidence and the mean (7.12, 7.13).
  Grid<double> weighted(g, 0.0);
  m.weight = Grid<double>(g, 0.0);
  for (std::size_t n = 0; n < samples.size(); ++n)
    for_each_weight(g, samples[n], kernels[n], [&](std::size_t c, double w) {
      m.weight.values[c] += w;
      weighted.values[c] += w * samples[n].reading;
    });
  m.confidence = m.mean = m.variance = Grid<double>(g, 0.0);
  for (std::size_t c = 0; c < g.size(); ++c) {
    const double omega = m.weight.values[c];
    const double alpha = 1.0 - std::exp(-omega / (o.sigma_omega * o.sigma_omega));
    m.confidence.values[c] = alpha;
    m.mean.values[c] = (omega > 0.0 ? alpha * weighted.values[c] / omega : 0.0) +
                       (1.0 - alpha) * m.background_mean;
  }
  // V (7.11): each reading's squared departure from the mean map at its nearest cell, spread by
  // the same kernels; v̄ is the mean of those departures.
  Grid<double> spread(g, 0.0);
  std::vector<double> departure(samples.size());
  double departures = 0.0;
  for (std::size_t n = 0; n < samples.size(); ++n) {
    const Vec2 p = samples[n].position;
    const int i = std::clamp(static_cast<int>(std::floor(p.x / g.dx())), 0, g.nx - 1);
    const int j = std::clamp(static_cast<int>(std::floor(p.y / g.dy())), 0, g.ny - 1);
    const double d = samples[n].reading - m.mean(i, j);
    departure[n] = d * d;
    departures += d * d;
  }
  m.background_variance = departures / samples.size();
  for (std::size_t n = 0; n < samples.size(); ++n)
    for_each_weight(g, samples[n], kernels[n],
                    [&](std::size_t c, double w) { spread.values[c] += w * departure[n]; });
  for (std::size_t c = 0; c < g.size(); ++c) {
    const double omega = m.weight.values[c], alpha = m.confidence.values[c];
    m.variance.values[c] = (omega > 0.0 ? alpha * spread.values[c] / omega : 0.0) +
                           (1.0 - alpha) * m.background_variance;
  }
  // Cells inside obstacles hold no gas: NaN, so that pictures and scores leave them out.
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (map.obstacle_at(g.centre(i, j)) >= 0)
        m.mean(i, j) = m.variance(i, j) = m.confidence(i, j) = std::nan("");
  return m;
}

}  // namespace plumekit::gdm
