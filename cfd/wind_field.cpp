#include "cfd/wind_field.hpp"

#include <algorithm>
#include <cmath>

namespace plumekit::cfd {

WindField::WindField(GridShape shape, std::vector<double> face_u, std::vector<double> face_v,
                     std::vector<double> pressure, std::vector<std::uint8_t> solid)
    : shape_(shape),
      face_u_(std::move(face_u)),
      face_v_(std::move(face_v)),
      u_(shape.size(), 0.0),
      v_(shape.size(), 0.0),
      p_(std::move(pressure)),
      solid_(std::move(solid)) {
  const int nx = shape.nx;
  for (int j = 0; j < shape.ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = shape.index(i, j);
      if (solid_[k]) {
        p_[k] = 0.0;
        continue;
      }
      u_[k] = 0.5 * (face_u_[j * (nx + 1) + i] + face_u_[j * (nx + 1) + i + 1]);
      v_[k] = 0.5 * (face_v_[j * nx + i] + face_v_[(j + 1) * nx + i]);
    }
  }
}

Vec2 sample_cell_velocity(const GridShape& shape, const std::vector<std::uint8_t>& solid,
                          const std::vector<double>& u, const std::vector<double>& v, Vec2 point) {
  const int nx = shape.nx, ny = shape.ny;
  if (!(point.x >= 0.0 && point.x <= shape.width && point.y >= 0.0 && point.y <= shape.height))
    return {0.0, 0.0};
  const int ci = std::min(nx - 1, static_cast<int>(point.x / shape.dx()));
  const int cj = std::min(ny - 1, static_cast<int>(point.y / shape.dy()));
  if (solid[shape.index(ci, cj)]) return {0.0, 0.0};
  // Bilinear between the four surrounding cell centres; solid cells
  // contribute zero velocity.
  const GridShape::Bilinear b = shape.bilinear(point);
  const double w00 = (1 - b.tx) * (1 - b.ty), w10 = b.tx * (1 - b.ty), w01 = (1 - b.tx) * b.ty,
               w11 = b.tx * b.ty;
  const std::size_t k00 = shape.index(b.i0, b.j0), k10 = shape.index(b.i1, b.j0);
  const std::size_t k01 = shape.index(b.i0, b.j1), k11 = shape.index(b.i1, b.j1);
  return {w00 * u[k00] + w10 * u[k10] + w01 * u[k01] + w11 * u[k11],
          w00 * v[k00] + w10 * v[k10] + w01 * v[k01] + w11 * v[k11]};
}

Vec2 WindField::at(Vec2 point) const {
  return sample_cell_velocity(shape_, solid_, u_, v_, point);
}

double WindField::max_speed() const {
  double m = 0.0;
  for (std::size_t k = 0; k < u_.size(); ++k)
    m = std::max(m, std::hypot(u_[k], v_[k]));
  return m;
}

}  // namespace plumekit::cfd
