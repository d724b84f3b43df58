#pragma once
// Kernel DM+V and Kernel DM+V/W (seed 000 §7.1, after Lilienthal et al. and Reggente and
// Lilienthal): maps of the mean, the variance and the confidence of gas readings taken at points,
// each reading spread over the cells around it by a Gaussian kernel. DM+V/W stretches a reading's
// kernel along the wind measured with it (a, b below) and keeps its area.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "core/thread_pool.hpp"
#include "map/map.hpp"

namespace plumekit::methods {

struct Sample {
  Vec2 position;             // arena frame
  double reading = 0.0;      // concentration units
  std::optional<Vec2> wind;  // m/s, the wind measured with it (DM+V/W)
};

// r̄ and v̄, what a cell far from every reading shows: the readings' mean (ch. 7) or their
// minimum (ch. 8's simulations, where most readings are 0).
enum class Background { Mean, Min };
const char* to_string(Background b);
// "mean", "min"; OptionError on gdm.background otherwise.
Background parse_background(const std::string& name);

struct GdmOptions {
  double cell = 0.1;          // m (seed: 0.10 in simulation, 0.15 on real data)
  double kernel_width = 0.4;  // sigma, m (seed: 0.4 for 1 m sample spacing, up to 1.2)
  double sigma_omega = 1.0;   // confidence alpha = 1 - exp(-Omega / sigma_omega^2)
  // gamma, s: 0 gives Kernel DM+V (round kernels); > 0 gives DM+V/W: along the wind
  // a = sigma + gamma |u|, across it b = sigma / (1 + gamma |u| / sigma), a b = sigma^2. The seed
  // used 0.6 s in its 0.5 m/s tunnel and 0.2 s outdoors.
  double wind_stretch = 0.0;
  Background background = Background::Mean;
  // Kernels are summed out to this many of their longer axis (exp(-8) = 3e-4 of the peak at 4).
  double cutoff = 4.0;
  // OptionError naming the field ("gdm.cell", ...) and its range.
  void validate() const;
};

struct GdmMaps {
  // Cell-centred over the arena, row 0 at y = 0. Cells whose centre lies in an obstacle are NaN.
  Grid<double> mean, variance, confidence;
  Grid<double> weight;  // Omega, the kernel weight each cell received
  double background_mean = 0.0, background_variance = 0.0;  // r̄, v̄
  int samples = 0;
  int outside_arena = 0;  // of `samples`, those outside the arena (counted: their kernels reach in)
};

// What a sample may hold. Readings within +-kMaxReading, so that the variance map (their squares)
// stays finite; winds within kMaxWind m/s per component; positions at most the arena's larger side
// outside the arena (farther is a wrong map or frame; nearer ones count, their kernels reach in).
inline constexpr double kMaxReading = 1e150;
inline constexpr double kMaxWind = 1000.0;

// The first unusable field of a sample: its column ("x", "y", "reading", "u", "v") and why, values
// in the map's frame; an empty column when the sample is usable. Readers name the file and line.
struct SampleFault {
  std::string column, reason;
};
SampleFault sample_fault(const Map& map, const Sample& sample);

// Bytes per cell of the maps: kernel_dmv's six grids of doubles and the gdm command's copies as
// it writes them (measured 34-44 B per cell of peak RSS; docs/methods.md).
inline constexpr double kGdmBytesPerCell = 64.0;

// MemoryLimitError naming gdm.cell and a cell that fits, unless `bytes_per_cell` on the maps' grid
// of `cell` fits the memory limit (core/memory_limit.hpp). kernel_dmv checks kGdmBytesPerCell;
// callers that score the maps too check the sum with kScoreBytesPerCell (map_score.hpp) first.
void check_grid_memory(const Map& map, double cell, double bytes_per_cell);

// How kernel_dmv runs: on `pool` (serial without one; the maps are the same bytes for any thread
// count), calling `progress` (from one thread at a time) with the fraction done.
struct GdmWork {
  ThreadPool* pool = nullptr;
  std::function<void(double fraction)> progress;
};

// The maps of `samples` over `map`'s arena. InputError when there is no sample or a sample breaks
// sample_fault's rules; MemoryLimitError (naming gdm.cell and a cell that fits) when the grid would
// not fit in the memory limit. Samples outside the arena count like any other.
GdmMaps kernel_dmv(const Map& map, const std::vector<Sample>& samples, const GdmOptions& options,
                   const GdmWork& work = {});

}  // namespace plumekit::methods
