// The sensor grid's concentration (world/grid_concentration.cpp, a dataset's frames) against a
// brute-force sum: every sensor adds, for every filament within the kernel's cutoff that no
// obstacle edge hides, mass / (pi R^2) exp(-d^2 / R^2). Tiles of 8 x 8 sensors, grids that are
// not multiples of 8, and bands of rows on several threads must all give that sum.
#include <gtest/gtest.h>

#include <cmath>

#include "map/map_json.hpp"
#include "support/uniform_wind.hpp"
#include "world/filament_model.hpp"

namespace plumekit {
namespace {

bool cut_by_an_edge(const Map& map, Vec2 a, Vec2 b) {
  for (const Polygon& poly : map.obstacles)
    for (std::size_t k = 0; k < poly.size(); ++k)
      if (segments_intersect(a, b, poly[k], poly[(k + 1) % poly.size()])) return true;
  return false;
}

struct Reference {
  std::vector<double> values;
  long hidden_pairs = 0;  // filament-sensor pairs within reach that an edge cuts
};

Reference brute_force(const Map& map, const std::vector<world::Filament>& filaments,
                      const GridShape& shape, const world::FilamentOptions& o) {
  Reference ref;
  ref.values.assign(shape.size(), 0.0);
  const double mass = o.release_rate / o.release_per_second;
  for (int j = 0; j < shape.ny; ++j)
    for (int i = 0; i < shape.nx; ++i) {
      const Vec2 c = shape.centre(i, j);
      double sum = 0.0;
      for (const world::Filament& f : filaments) {
        const double r = o.cutoff * std::sqrt(f.radius2);
        if (std::abs(c.x - f.position.x) > r || std::abs(c.y - f.position.y) > r) continue;
        if (cut_by_an_edge(map, f.position, c)) {
          ++ref.hidden_pairs;
          continue;
        }
        const double d2 = (c.x - f.position.x) * (c.x - f.position.x) +
                          (c.y - f.position.y) * (c.y - f.position.y);
        sum += mass / (M_PI * f.radius2) * std::exp(-d2 / f.radius2);
      }
      ref.values[shape.index(i, j)] = sum;
    }
  return ref;
}

TEST(GridConcentration, EverySensorSumsTheFilamentsItSeesWhateverTheTilesAndThreads) {
  const Map map = read_map(std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json");
  const cfd::WindField wind = test::uniform_wind(map.width, map.height, 0.05, 0.6);
  world::FilamentOptions o;
  o.unsteady_wind = false;  // the grid reads filaments; how they moved does not matter here
  o.max_spinup = 10.0;
  for (const GridShape shape : {GridShape{37, 29, map.width, map.height},  // tiles cut at edges
                                GridShape{64, 64, map.width, map.height}}) {
    SCOPED_TRACE(std::to_string(shape.nx) + " x " + std::to_string(shape.ny));
    std::vector<double> grid[2];
    std::vector<world::Filament> filaments;
    for (const int threads : {1, 3}) {
      o.threads = threads;
      world::FilamentSimulation sim(map, wind, {1.0, 0.5 * map.height}, o, 23);
      world::spin_up(sim, o);
      filaments = sim.filaments();
      grid[threads == 1 ? 0 : 1].assign(shape.size(), 0.0);
      sim.concentration(shape, grid[threads == 1 ? 0 : 1]);
    }
    ASSERT_GT(filaments.size(), 500u);  // past where the bands go to threads (256)
    EXPECT_EQ(grid[0], grid[1]);        // bands of rows on 3 threads: the same sums, bit for bit
    const Reference ref = brute_force(map, filaments, shape, o);
    EXPECT_GT(ref.hidden_pairs, 10000);  // the map's blocks do cut many pairs
    double peak = 0.0;
    for (const double v : ref.values)
      peak = std::max(peak, v);
    ASSERT_GT(peak, 0.0);
    int zero = 0;
    for (std::size_t k = 0; k < ref.values.size(); ++k) {
      ASSERT_NEAR(grid[0][k], ref.values[k], 1e-9 * peak) << "sensor " << k;
      if (ref.values[k] == 0.0) {
        EXPECT_EQ(grid[0][k], 0.0) << "sensor " << k;  // nothing seen: exactly nothing
        ++zero;
      }
    }
    EXPECT_GT(zero, 0);
  }
}

}  // namespace
}  // namespace plumekit
