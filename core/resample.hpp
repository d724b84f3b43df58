#pragma once
// Resampling a field between two grids over one arena, around obstacles: a field on a fine grid
// with solid cells (a flow grid) read at the cell centres of another grid (the 64 x 64 sensor
// grid of the dataset, the source cells of ste's physics model).
#include <cstdint>
#include <utility>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"

namespace plumekit {

// Bilinear weights of the point `p` over the free cell centres of `grid` (`solid` holds one
// flag per cell), renormalised when some of the four neighbours are solid; the nearest free
// centre within 3 cells when all four are. Pairs (cell index, weight); empty when no free cell
// is near.
std::vector<std::pair<int, double>> free_bilinear_weights(const GridShape& grid,
                                                          const std::vector<std::uint8_t>& solid,
                                                          Vec2 p);

// Reads fields on `source` (with its solid cells) at the cell centres of `target`: bilinear among
// free cells, 0 at points inside solid cells. The weights depend only on the grids and the solid
// cells, so they are computed once, for many fields.
class GridResampler {
 public:
  GridResampler(const GridShape& source, const std::vector<std::uint8_t>& solid,
                const GridShape& target);
  // std::logic_error when `field` is not on the source grid.
  Grid<double> apply(const Grid<double>& field) const;

 private:
  GridShape source_, target_;
  std::vector<int> begin_;  // target cell c's weights: [begin_[c], begin_[c + 1])
  std::vector<std::pair<int, double>> weights_;
};

}  // namespace plumekit
