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

Vec2 WindField::at(Vec2 point) const {
  const int nx = shape_.nx, ny = shape_.ny;
  if (!(point.x >= 0.0 && point.x <= shape_.width && point.y >= 0.0 && point.y <= shape_.height))
    return {0.0, 0.0};
  const int ci = std::min(nx - 1, static_cast<int>(point.x / shape_.dx()));
  const int cj = std::min(ny - 1, static_cast<int>(point.y / shape_.dy()));
  if (solid(ci, cj)) return {0.0, 0.0};
  // Bilinear between the four surrounding cell centres; solid cells
  // contribute zero velocity.
  const GridShape::Bilinear b = shape_.bilinear(point);
  const double w00 = (1 - b.tx) * (1 - b.ty), w10 = b.tx * (1 - b.ty), w01 = (1 - b.tx) * b.ty,
               w11 = b.tx * b.ty;
  const std::size_t k00 = shape_.index(b.i0, b.j0), k10 = shape_.index(b.i1, b.j0);
  const std::size_t k01 = shape_.index(b.i0, b.j1), k11 = shape_.index(b.i1, b.j1);
  return {w00 * u_[k00] + w10 * u_[k10] + w01 * u_[k01] + w11 * u_[k11],
          w00 * v_[k00] + w10 * v_[k10] + w01 * v_[k01] + w11 * v_[k11]};
}

double WindField::max_speed() const {
  double m = 0.0;
  for (std::size_t k = 0; k < u_.size(); ++k)
    m = std::max(m, std::hypot(u_[k], v_[k]));
  return m;
}

}  // namespace plumekit::cfd
