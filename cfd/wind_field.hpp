#pragma once
// A steady 2-D wind field: MAC face velocities as solved, plus cell-centred
// velocity and pressure. Grid convention: cell-centred, row-major, row 0 at
// y = 0, origin at the arena's lower-left corner; zero inside obstacles.
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"

namespace plumekit::cfd {

// The four cell centres around a point, (i0, j0), (i1, j0), (i0, j1), (i1, j1)
// as row-major indices, and their bilinear weights.
struct CellCorners {
  std::size_t cell[4];
  double weight[4];
};

class WindField {
 public:
  WindField() = default;
  // face_u: (nx+1) x ny, index j*(nx+1)+i; face_v: nx x (ny+1), index j*nx+i.
  WindField(GridShape shape, std::vector<double> face_u, std::vector<double> face_v,
            std::vector<double> pressure, std::vector<std::uint8_t> solid);

  const GridShape& shape() const { return shape_; }
  // Velocity at any point: bilinear between cell centres; zero inside
  // obstacle cells and outside the arena.
  Vec2 at(Vec2 point) const;
  // The cell centres and weights at(point) interpolates between; false where
  // the wind is zero (outside the arena, inside an obstacle cell).
  bool corners(Vec2 point, CellCorners& out) const;
  Vec2 cell_velocity(int i, int j) const {
    return {u_[shape_.index(i, j)], v_[shape_.index(i, j)]};
  }
  double cell_pressure(int i, int j) const { return p_[shape_.index(i, j)]; }
  bool solid(int i, int j) const { return solid_[shape_.index(i, j)] != 0; }

  const std::vector<double>& u() const { return u_; }  // cell-centred, ny x nx
  const std::vector<double>& v() const { return v_; }
  const std::vector<double>& p() const { return p_; }
  const std::vector<double>& face_u() const { return face_u_; }
  const std::vector<double>& face_v() const { return face_v_; }
  const std::vector<std::uint8_t>& solid_cells() const { return solid_; }
  double max_speed() const;

 private:
  GridShape shape_;
  std::vector<double> face_u_, face_v_;
  std::vector<double> u_, v_, p_;
  std::vector<std::uint8_t> solid_;
};

}  // namespace plumekit::cfd
