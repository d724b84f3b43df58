#pragma once
// Steady advection-diffusion of a point release in a solved wind field:
//
//   div(u C) - div(D grad C) + lambda C = Q delta(x - s)
//
// (lambda, the first-order decay rate, is 0 unless set: gas that is lost
// at a rate, such as the filament world's filaments that end when too wide).
//
// finite volumes on the flow's own MAC grid, with the face velocities as the
// fluxes (so the discrete operator conserves mass exactly as the flow does).
// The operator depends only on the wind, so it is assembled and LU-factored
// (UMFPACK) once per map; each source is then one forward solve, and the
// adjoint (one transposed solve per sensor) gives that sensor's reading for
// every possible source at once.
#include <memory>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/grid.hpp"
#include "core/option_table.hpp"

namespace plumekit::cfd {

struct AdvectionDiffusionOptions {
  // Constant eddy diffusivity, m^2/s. 0.05 gives a plume sigma of about 0.7 m
  // 5 m downstream of the source at 1 m/s (sigma^2 = 2 D x / u), a plausible
  // width for a plume in a 4 m wide room; it equals the filament model's
  // default equivalent diffusivity (filament_model.hpp).
  double diffusivity = 0.05;
  // Release rate per metre of depth, concentration units * m^2/s. With the
  // defaults, concentrations 1 m downstream of a source in a 1 m/s wind are
  // about Q / sqrt(4 pi D x / u) ~ 1300 and fall to ~400 at 10 m: the 0..3000
  // range of the thesis's (unnormalised) dataset.
  double release_rate = 1000.0;
  // First-order decay rate lambda, 1/s: a sink lambda C everywhere. 0 (the
  // default): gas leaves only through outlets. The filament world drops a
  // filament once it is max_radius wide, (R^2 - R0^2) / growth = 28 s after
  // its release, so its gas has a finite life that the physics model of
  // ste/ can mirror (docs/validation.md, "Floors").
  double decay_rate = 0.0;

  // Throws OptionError naming "plume.diffusivity", "plume.release_rate" or
  // "plume.decay_rate" and the allowed range. AdvectionDiffusion's constructor calls it.
  void validate() const;
};

// Its options table (core/option_table.hpp): validate(), the dataset commands' --diffusivity,
// the Python properties and docs/options.md.
const OptionTable<AdvectionDiffusionOptions>& advection_diffusion_option_table();

// What the factorization did.
struct AdvectionDiffusionSummary {
  int nx = 0, ny = 0;
  int unknowns = 0;        // free cells
  long long nonzeros = 0;  // of the operator
  double factor_s = 0.0;
  double max_cell_peclet = 0.0;  // |u| h / D over faces; the scheme blends to upwind above 2
};

class AdvectionDiffusion {
 public:
  // Assembles and factors the operator. Throws InputError for a non-positive
  // diffusivity or a wind field with no free cells.
  AdvectionDiffusion(const cfd::WindField& wind, const AdvectionDiffusionOptions& options = {});
  ~AdvectionDiffusion();
  AdvectionDiffusion(const AdvectionDiffusion&) = delete;
  AdvectionDiffusion& operator=(const AdvectionDiffusion&) = delete;

  const AdvectionDiffusionSummary& summary() const { return summary_; }
  const GridShape& shape() const { return shape_; }
  bool solid(int i, int j) const { return solid_[shape_.index(i, j)] != 0; }
  // One flag per flow cell: what core/resample.hpp reads fields around.
  const std::vector<std::uint8_t>& solid_mask() const { return solid_; }
  const AdvectionDiffusionOptions& options() const { return options_; }

  // Concentration on the flow grid (zero in solid cells) of a release of
  // options.release_rate at `source`, spread bilinearly over the four nearest
  // free cell centres so the field moves smoothly with the source.
  Grid<double> solve(Vec2 source) const;

  // The adjoint: a field on the flow grid whose value at cell c is what a
  // sensor at `sensor` (bilinear among free cell centres) reads for a release
  // of options.release_rate at the centre of c. One transposed solve.
  Grid<double> adjoint(Vec2 sensor) const;

  // Total advective + diffusive flux (per metre of depth) through the vertical
  // line x = i * dx, from the face values of a solved field: the release rate
  // downstream of the source, 0 upstream of it.
  double flux_through_column(const Grid<double>& c, int i) const;

  // Bilinear weights of a point over free cell centres (renormalised when
  // some of the four neighbours are solid): pairs (cell index, weight);
  // core/resample.hpp's free_bilinear_weights on the flow grid.
  std::vector<std::pair<int, double>> point_weights(Vec2 p) const;

 private:
  struct Lu;
  GridShape shape_;
  AdvectionDiffusionOptions options_;
  std::vector<double> face_u_, face_v_;
  std::vector<std::uint8_t> solid_;
  std::vector<int> unknown_;  // cell -> unknown index, -1 if solid
  std::vector<int> cell_of_;  // unknown -> cell
  std::unique_ptr<Lu> lu_;
  AdvectionDiffusionSummary summary_;
  // +x flux (advective + diffusive) through the face left of cell (i, j).
  double face_flux(const Grid<double>& c, int i, int j) const;
};

}  // namespace plumekit::cfd
