#pragma once
// A steady 2-D wind field: MAC face velocities as solved, plus cell-centred
// velocity and pressure. Grid convention: cell-centred, row-major, row 0 at
// y = 0, origin at the arena's lower-left corner; zero inside obstacles.
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/grid.hpp"

namespace plumekit::cfd {

// Velocity at a point from cell-centred components u, v (row-major, ny x nx):
// bilinear between cell centres, solid cells counting as zero; zero inside a
// solid cell and outside the arena. WindField::at and FluctuatingWind::at.
Vec2 sample_cell_velocity(const GridShape& shape, const std::vector<std::uint8_t>& solid,
                          const std::vector<double>& u, const std::vector<double>& v, Vec2 point);

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
