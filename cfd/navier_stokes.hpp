#pragma once
// The discrete steady incompressible Navier-Stokes equations on the MAC grid:
// one momentum equation per velocity unknown, one continuity equation per
// fluid cell. Residual and exact Jacobian come from the same templated code
// (double for the residual, Dual for the Jacobian), so they always agree.
//
// Momentum, per unit volume, for the face of component w between cells
// a-1 and a (along) in cell row b (across):
//   (F_e w_e - F_w w_w)/h_a + (G_n w_n - G_s w_s)/h_b
//   - [nu_e (w_{a+1} - w_a) - nu_w (w_a - w_{a-1})]/h_a^2
//   - [nu_n (w_{b+1} - w_b) - nu_s (w_b - w_{b-1})]/h_b^2
//   + (p_a - p_{a-1})/h_a = 0
// with mass fluxes F (own component averaged to cell centres) and G (the other
// component averaged to cell corners), and face values w_e, w_n... from the
// convection scheme. Continuity: (u_e - u_w)/dx + (v_n - v_s)/dy = 0.
#include <Eigen/SparseCore>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "cfd/staggered_grid.hpp"

namespace plumekit::cfd {

class NavierStokes {
 public:
  NavierStokes(const StaggeredGrid& grid, Convection convection);

  int size() const { return grid_.unknowns(); }
  int momentum_rows() const { return grid_.velocity_unknowns(); }
  // Effective viscosity per cell (molecular + eddy); solid cells are ignored.
  void set_viscosity(const std::vector<double>& nu_cell);

  void residual(const double* x, double* r) const;
  // Values of the Jacobian at x, in the fixed pattern of jacobian().
  void update_jacobian(const double* x);
  Eigen::SparseMatrix<double>& jacobian() { return jacobian_; }
  // Adds s to the Jacobian's diagonal in the momentum rows (pseudo-time term).
  void add_to_momentum_diagonal(double s);
  // The continuity rows' (constant) coefficients: D, (unknowns - momentum
  // rows) x momentum rows, D u + c being the continuity residual.
  Eigen::SparseMatrix<double> continuity_matrix() const;

 private:
  // A grid Ref as a row stores it: the unknown, its slot in the row, and the
  // index of its (scale, offset) pair in coefs_. The pairs are few (+-1, 0
  // and the fixed faces' values), and two doubles in every entry were 60 %
  // of the equations' memory (250 MB on tb3_world's 5 cm grid).
  struct Term {
    int col;
    std::uint32_t coef : 24;
    std::uint32_t local : 8;
  };
  struct Coef {
    double scale, offset;
  };
  struct MomentumRow {
    int row;
    Term w[5];   // own component along: a-2, a-1, a, a+1, a+2
    Term wb[4];  // own component across: b-2, b-1, b+1, b+2
    Term o[4];   // other component: north pair, south pair
    Term p[2];   // pressure in cells a-1 and a
    int cell_w, cell_e, corner_s, corner_n;
    double inv_ha, inv_hb;
  };
  struct ContinuityRow {
    int row;
    Term f[4];  // u east, u west, v north, v south
    double inv_dx, inv_dy;
    bool pinned;  // closed box: p = 0 here instead of (redundant) continuity
  };

  // The constructor's steps: one face's momentum row, the cells' continuity
  // rows, and the Jacobian's fixed pattern with each row's slots in it.
  MomentumRow momentum_row(int c, int a, int b);
  Term term(const Ref& r);  // interns r's (scale, offset)
  void add_continuity_rows();
  void build_pattern();

  template <class T>
  T load(const Term& t, const double* x) const;
  template <class T>
  T momentum(const MomentumRow& row, const double* x) const;
  template <class T>
  T continuity(const ContinuityRow& row, const double* x) const;
  template <class T>
  T face_value(const T& flux, const T& far_up_m, const T& up_m, const T& up_p,
               const T& far_up_p) const;

  const StaggeredGrid& grid_;
  Convection convection_;
  std::vector<MomentumRow> momentum_;
  std::vector<ContinuityRow> continuity_;
  std::vector<Coef> coefs_;
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::uint32_t> coef_index_;  // by bit pattern
  std::vector<double> nu_cell_, nu_corner_;
  // Row r's Jacobian values: jacobian_'s values[slot_value_[slot_begin_[r] + local]].
  std::vector<int> slot_begin_, slot_value_;
  Eigen::SparseMatrix<double> jacobian_;
};

}  // namespace plumekit::cfd
