#include "methods/kernel_dmv.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <tuple>
#include <utility>

#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "methods/option_tables.hpp"

namespace plumekit::methods {

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

// The cells [first, last] of an axis of n cells of size d that [a, b] m covers; first > last when
// none. Worked out in doubles: a far sample's cell index would not fit an int.
std::pair<int, int> cell_span(double a, double b, double d, int n) {
  const double first = std::floor(a / d), last = std::floor(b / d);
  if (!(last >= 0.0) || !(first <= n - 1.0)) return {1, 0};
  return {static_cast<int>(std::max(first, 0.0)), static_cast<int>(std::min(last, n - 1.0))};
}

// The cells a kernel's cutoff box covers.
struct Box {
  int i0 = 1, i1 = 0, j0 = 1, j1 = 0;
};

Box box_of(const GridShape& g, const Sample& s, const Kernel& k) {
  Box b;
  std::tie(b.i0, b.i1) = cell_span(s.position.x - k.reach, s.position.x + k.reach, g.dx(), g.nx);
  std::tie(b.j0, b.j1) = cell_span(s.position.y - k.reach, s.position.y + k.reach, g.dy(), g.ny);
  return b;
}

// Calls f(cell index, weight) for every cell of rows [row0, row1] within the kernel's box.
template <class F>
void for_each_weight(const GridShape& g, const Sample& s, const Kernel& k, const Box& b, int row0,
                     int row1, F&& f) {
  for (int j = std::max(b.j0, row0); j <= std::min(b.j1, row1); ++j)
    for (int i = b.i0; i <= b.i1; ++i) {
      const Vec2 d = g.centre(i, j) - s.position;
      const double m2 = k.ixx * d.x * d.x + 2.0 * k.ixy * d.x * d.y + k.iyy * d.y * d.y;
      // Never below 0 (a rounding of a long thin kernel could), so a weight never tops the peak.
      f(g.index(i, j), k.norm * std::exp(-0.5 * std::max(m2, 0.0)));
    }
}

// The fraction of kernel_dmv's work done, reported from one thread at a time.
class Progress {
 public:
  Progress(const GdmWork& work, std::size_t total) : work_(work), total_(total) {}
  void step() {
    if (!work_.progress) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    work_.progress(static_cast<double>(++done_) / static_cast<double>(total_));
  }

 private:
  const GdmWork& work_;
  std::size_t total_, done_ = 0;
  std::mutex mutex_;
};

// Bands of rows: a few per thread, for balance, but no more (each band visits every sample whose
// box reaches it, so thin bands repeat that work), and at least 8, for the progress bar.
int band_count(const GridShape& g, const GdmWork& work) {
  return std::min(g.ny, std::max(8, 4 * (work.pool ? work.pool->size() : 1)));
}

// Runs pass(first row, last row) over bands of rows, on the pool when there is one. Each cell's
// sums run over the samples in their order whatever the banding, so the maps are the same bytes
// for any thread count.
void over_bands(const GridShape& g, const GdmWork& work, Progress& progress,
                const std::function<void(int, int)>& pass) {
  const int bands = band_count(g, work);
  const auto band = [&](std::size_t b) {
    pass(static_cast<int>(b * g.ny / bands), static_cast<int>((b + 1) * g.ny / bands) - 1);
    progress.step();
  };
  if (work.pool)
    work.pool->parallel_for(static_cast<std::size_t>(bands), band);
  else
    for (int b = 0; b < bands; ++b)
      band(static_cast<std::size_t>(b));
}

void check_samples(const Map& map, const std::vector<Sample>& samples) {
  if (samples.empty()) throw InputError("gdm: no samples to map");
  for (std::size_t n = 0; n < samples.size(); ++n)
    if (const SampleFault f = sample_fault(map, samples[n]); !f.column.empty())
      throw InputError("gdm: sample " + std::to_string(n + 1) + ", " + f.column + ": " + f.reason);
}

// A power of two at or above every |reading| (1 when all are 0). The sums run on the readings
// divided by it, so they stay finite for any accepted reading, and the maps scale back exactly
// (a power of two changes no rounding): the same bytes as unscaled sums wherever those are finite.
double reading_scale(const std::vector<Sample>& samples) {
  double top = 0.0;
  for (const Sample& s : samples)
    top = std::max(top, std::abs(s.reading));
  if (top == 0.0) return 1.0;
  int exponent = 0;
  std::frexp(top, &exponent);
  return std::ldexp(1.0, exponent);
}

// Bounded inputs keep every sum finite; should a cell still come out otherwise, the maps are
// refused rather than written.
void check_finite(const Map& map, const GdmMaps& m) {
  const std::pair<const char*, const Grid<double>*> maps[] = {
      {"mean", &m.mean}, {"variance", &m.variance}, {"confidence", &m.confidence}};
  for (const auto& [name, grid] : maps)
    for (int j = 0; j < grid->shape.ny; ++j)
      for (int i = 0; i < grid->shape.nx; ++i)
        if (!std::isfinite((*grid)(i, j))) {
          const Vec2 at = map.to_frame(grid->shape.centre(i, j));
          throw InputError("gdm: the " + std::string(name) + " map is not finite at (" +
                           compact(at.x) + ", " + compact(at.y) + ") m; the readings (" +
                           compact(m.background_mean) + " on average) are out of range");
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

const OptionTable<GdmOptions>& gdm_option_table() {
  using O = GdmOptions;
  // Lower bounds keep a kernel's peak 1 / (2 pi sigma^2) and Omega / sigma_omega^2 finite.
  static const OptionTable<O> table{
      "Gas distribution mapping (methods::GdmOptions)",
      {{"gdm.cell", "--map-cell", &O::cell, positive(10.0, "m"), "The gas map's cell, m"},
       {"gdm.kernel_width", "--kernel-width", &O::kernel_width, real_range(1e-3, 100.0, "m"),
        "The kernel's sigma, m (seed 000: 0.4 for samples 1 m apart)"},
       {"gdm.sigma_omega", "--sigma-omega", &O::sigma_omega, real_range(1e-6, 1e6, ""),
        "Confidence scale: alpha = 1 - exp(-Omega / sigma_omega^2)"},
       {"gdm.wind_stretch", "--wind-stretch", &O::wind_stretch, non_negative(100.0, "s"),
        "gamma, s: 0 gives Kernel DM+V; more stretches each kernel along its sample's wind "
        "(Kernel DM+V/W; seed 000: 0.2-0.6)",
        "0 (the default) gives Kernel DM+V; the seed used 0.2-0.6 s"},
       {"gdm.background",
        "--background",
        enum_field(&O::background, &to_string, &parse_background, "mean, min"),
        {},
        "What a cell far from every sample shows: the readings' mean or min"},
       {"gdm.cutoff", "", &O::cutoff, real_range(1.0, 10.0, "kernel widths"),
        "Kernels are summed out to this many of their longer axis"}}};
  return table;
}

void GdmOptions::validate() const {
  plumekit::validate(gdm_option_table(), *this);
}

void check_grid_memory(const Map& map, double cell, double bytes_per_cell) {
  // The count in doubles: a tiny cell's would not fit an int.
  const auto cells_of = [&](double c) {
    return std::max(1.0, std::round(map.width / c)) * std::max(1.0, std::round(map.height / c));
  };
  const double cells = cells_of(cell);
  if (fits_in_memory(cells * bytes_per_cell)) return;
  // Rounded up to two digits, then grown until the rounded cell counts fit too.
  double fit = std::sqrt(map.width * map.height * bytes_per_cell / memory_limit());
  const double unit = std::pow(10.0, std::floor(std::log10(fit)) - 1.0);
  fit = std::ceil(fit / unit) * unit;
  while (!fits_in_memory(cells_of(fit) * bytes_per_cell))
    fit += unit;
  check_memory(cells * bytes_per_cell,
               "the gas maps' grid of " + compact(cells) + " cells of " + compact(cell) +
                   " m on the " + compact(map.width) + " x " + compact(map.height) + " m arena",
               "use a larger gdm.cell (" + compact(fit) + " m fits)");
}

SampleFault sample_fault(const Map& map, const Sample& s) {
  const double margin = std::max(map.width, map.height);
  // Along one axis: the arena position `at` of `extent`, whose map frame starts at `origin`.
  const auto position = [&](const char* column, double at, double extent,
                            double origin) -> SampleFault {
    if (!std::isfinite(at)) return {column, "not finite"};
    if (at >= -margin && at <= extent + margin) return {};
    return {column, compact(at + origin) + " m lies more than the arena's larger side (" +
                        compact(margin) + " m) outside the map's arena (" + compact(origin) +
                        " to " + compact(origin + extent) +
                        " m): is it the map and the frame (metres) the samples were taken in?"};
  };
  if (SampleFault f = position("x", s.position.x, map.width, map.frame.origin.x); !f.column.empty())
    return f;
  if (SampleFault f = position("y", s.position.y, map.height, map.frame.origin.y);
      !f.column.empty())
    return f;
  if (!std::isfinite(s.reading)) return {"reading", "not finite"};
  if (std::abs(s.reading) > kMaxReading)
    return {"reading", compact(s.reading) + " is beyond +-" + compact(kMaxReading) +
                           ", the largest accepted (the variance map holds its square)"};
  if (!s.wind) return {};
  for (const auto& [column, u] : {std::pair{"u", s.wind->x}, std::pair{"v", s.wind->y}}) {
    if (!std::isfinite(u)) return {column, "not finite"};
    if (std::abs(u) > kMaxWind)
      return {column, compact(u) + " m/s is beyond +-" + compact(kMaxWind) +
                          " m/s, the fastest wind accepted"};
  }
  return {};
}

namespace {

// Omega and R (eqs. 7.9, 7.10), then the confidence and the mean (7.12, 7.13), on readings
// divided by `scale`.
void mean_maps(const GridShape& g, const std::vector<Sample>& samples,
               const std::vector<Kernel>& kernels, const std::vector<Box>& boxes, double scale,
               const GdmOptions& o, const GdmWork& work, Progress& progress, GdmMaps& m) {
  Grid<double> weighted(g, 0.0);
  m.weight = Grid<double>(g, 0.0);
  over_bands(g, work, progress, [&](int row0, int row1) {
    for (std::size_t n = 0; n < samples.size(); ++n) {
      if (boxes[n].j1 < row0 || boxes[n].j0 > row1) continue;
      const double r = samples[n].reading / scale;
      for_each_weight(g, samples[n], kernels[n], boxes[n], row0, row1,
                      [&](std::size_t c, double w) {
                        m.weight.values[c] += w;
                        weighted.values[c] += w * r;
                      });
    }
  });
  const double background = m.background_mean / scale;
  m.confidence = m.mean = m.variance = Grid<double>(g, 0.0);
  for (std::size_t c = 0; c < g.size(); ++c) {
    const double omega = m.weight.values[c];
    const double alpha = 1.0 - std::exp(-omega / (o.sigma_omega * o.sigma_omega));
    m.confidence.values[c] = alpha;
    m.mean.values[c] =
        (omega > 0.0 ? alpha * weighted.values[c] / omega : 0.0) + (1.0 - alpha) * background;
  }
}

// V (7.11): each reading's squared departure from the mean map at its nearest cell, spread by the
// same kernels; v̄ is the mean of those departures. Readings and the mean map are divided by
// `scale`, the variances by its square.
void variance_map(const GridShape& g, const std::vector<Sample>& samples,
                  const std::vector<Kernel>& kernels, const std::vector<Box>& boxes, double scale,
                  const GdmWork& work, Progress& progress, GdmMaps& m) {
  std::vector<double> departure(samples.size());
  double departures = 0.0;
  for (std::size_t n = 0; n < samples.size(); ++n) {
    const Vec2 p = samples[n].position;
    const int i = static_cast<int>(std::clamp(std::floor(p.x / g.dx()), 0.0, g.nx - 1.0));
    const int j = static_cast<int>(std::clamp(std::floor(p.y / g.dy()), 0.0, g.ny - 1.0));
    const double d = samples[n].reading / scale - m.mean(i, j);
    departure[n] = d * d;
    departures += d * d;
  }
  const double background = departures / samples.size();
  Grid<double> spread(g, 0.0);
  over_bands(g, work, progress, [&](int row0, int row1) {
    for (std::size_t n = 0; n < samples.size(); ++n)
      if (boxes[n].j1 >= row0 && boxes[n].j0 <= row1)
        for_each_weight(g, samples[n], kernels[n], boxes[n], row0, row1,
                        [&](std::size_t c, double w) { spread.values[c] += w * departure[n]; });
  });
  for (std::size_t c = 0; c < g.size(); ++c) {
    const double omega = m.weight.values[c], alpha = m.confidence.values[c];
    m.variance.values[c] =
        ((omega > 0.0 ? alpha * spread.values[c] / omega : 0.0) + (1.0 - alpha) * background) *
        scale * scale;
    m.mean.values[c] *= scale;
  }
  m.background_variance = background * scale * scale;
}

// Cells inside obstacles hold no gas: NaN, so that pictures and scores leave them out.
void blank_obstacles(const Map& map, const GdmWork& work, GdmMaps& m) {
  const GridShape& g = m.mean.shape;
  const auto row = [&](std::size_t r) {
    const int j = static_cast<int>(r);
    for (int i = 0; i < g.nx; ++i)
      if (map.obstacle_at(g.centre(i, j)) >= 0)
        m.mean(i, j) = m.variance(i, j) = m.confidence(i, j) = std::nan("");
  };
  if (work.pool)
    work.pool->parallel_for(static_cast<std::size_t>(g.ny), row);
  else
    for (int j = 0; j < g.ny; ++j)
      row(static_cast<std::size_t>(j));
}

}  // namespace

GdmMaps kernel_dmv(const Map& map, const std::vector<Sample>& samples, const GdmOptions& o,
                   const GdmWork& work) {
  o.validate();
  check_samples(map, samples);
  check_grid_memory(map, o.cell, kGdmBytesPerCell);
  const GridShape g = GridShape::with_cell(map.width, map.height, o.cell);
  GdmMaps m;
  m.samples = static_cast<int>(samples.size());
  std::vector<Kernel> kernels;
  std::vector<Box> boxes;
  kernels.reserve(samples.size());
  boxes.reserve(samples.size());
  double sum = 0.0, lowest = samples[0].reading;
  const double scale = reading_scale(samples);
  for (const Sample& s : samples) {
    kernels.push_back(kernel_of(s, o));
    boxes.push_back(box_of(g, s, kernels.back()));
    sum += s.reading / scale;
    lowest = std::min(lowest, s.reading);
    m.outside_arena += map.in_arena(s.position) ? 0 : 1;
  }
  m.background_mean = o.background == Background::Mean ? sum / samples.size() * scale : lowest;
  Progress progress(work, 2 * static_cast<std::size_t>(band_count(g, work)));
  mean_maps(g, samples, kernels, boxes, scale, o, work, progress, m);
  variance_map(g, samples, kernels, boxes, scale, work, progress, m);
  check_finite(map, m);
  blank_obstacles(map, work, m);
  return m;
}

}  // namespace plumekit::methods
