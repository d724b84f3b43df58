// The narrow-gap search (cfd/gap_closing.hpp) on real maps: the bucketed
// search and the closing pass against the pairwise brute force that
// check_grid used before, and against rasterizing the map on the same grid.
//
//   gap_search_bench [--cell 0.05] [--no-brute-force] MAP.json...
//
// Prints, per map: obstacles, vertices, grid, gaps found, the narrowest, and
// median seconds (of 5) of each step.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cfd/gap_closing.hpp"
#include "map/map_json.hpp"
#include "map/rasterize.hpp"

namespace {

template <class F>
double median_seconds(int repeats, F f) {
  std::vector<double> t;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace plumekit;
  double cell = 0.05;
  bool brute = true;
  std::vector<std::string> files;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--cell") && k + 1 < argc)
      cell = std::stod(argv[++k]);
    else if (!std::strcmp(argv[k], "--no-brute-force"))
      brute = false;
    else
      files.push_back(argv[k]);
  }
  std::printf("%-28s %9s %9s %11s %6s %10s %9s %9s %9s %9s\n", "map", "obstacles", "vertices",
              "grid", "gaps", "narrowest", "raster_s", "search_s", "close_s", "brute_s");
  for (const std::string& file : files) {
    const Map map = read_map(file);
    std::size_t vertices = 0;
    for (const Polygon& p : map.obstacles)
      vertices += p.size();
    const GridShape shape = GridShape::with_cell(map.width, map.height, cell);
    std::vector<cfd::GapReport> gaps;
    const double raster = median_seconds(5, [&] { rasterize_occupancy(map, shape); });
    const double search = median_seconds(5, [&] { gaps = cfd::find_narrow_gaps(map, shape); });
    const Grid<std::uint8_t> solid0 = rasterize_occupancy(map, shape);
    const double close = median_seconds(5, [&] {
      std::vector<std::uint8_t> solid = solid0.values;
      cfd::close_narrow_gaps(map, shape, solid);
    });
    double brute_s = -1.0;
    if (brute) {
      std::vector<cfd::GapReport> slow;
      brute_s = median_seconds(1, [&] { slow = cfd::find_narrow_gaps_brute_force(map, shape); });
      if (slow.size() != gaps.size() || (!gaps.empty() && slow[0].width != gaps[0].width))
        std::printf("MISMATCH: brute force found %zu gaps\n", slow.size());
    }
    char grid[32];
    std::snprintf(grid, sizeof grid, "%dx%d", shape.nx, shape.ny);
    std::printf("%-28s %9zu %9zu %11s %6zu %10.4g %9.4f %9.4f %9.4f %9.4f\n",
                map.name.substr(0, 28).c_str(), map.obstacles.size(), vertices, grid, gaps.size(),
                gaps.empty() ? 0.0 : gaps[0].width, raster, search, close, brute_s);
  }
  return 0;
}
