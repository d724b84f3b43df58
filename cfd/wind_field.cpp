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

bool WindField::corners(Vec2 point, CellCorners& out) const {
  const int nx = shape_.nx, ny = shape_.ny;
  if (!(point.x >= 0.0 && point.x <= shape_.width && point.y >= 0.0 && point.y <= shape_.height))
    return false;
  const int ci = std::min(nx - 1, static_cast<int>(point.x / shape_.dx()));
  const int cj = std::min(ny - 1, static_cast<int>(point.y / shape_.dy()));
  if (solid(ci, cj)) return false;
  // Bilinear between the four surrounding cell centres; solid cells
  // contribute zero velocity.
  const GridShape::Bilinear b = shape_.bilinear(point);
  out = {{shape_.index(b.i0, b.j0), shape_.index(b.i1, b.j0), shape_.index(b.i0, b.j1),
          shape_.index(b.i1, b.j1)},
         {(1 - b.tx) * (1 - b.ty), b.tx * (1 - b.ty), (1 - b.tx) * b.ty, b.tx * b.ty}};
  return true;
}

Vec2 WindField::at(Vec2 point) const {
  CellCorners c;
  if (!corners(point, c)) return {0.0, 0.0};
  const double* w = c.weight;
  const std::size_t* k = c.cell;
  return {w[0] * u_[k[0]] + w[1] * u_[k[1]] + w[2] * u_[k[2]] + w[3] * u_[k[3]],
          w[0] * v_[k[0]] + w[1] * v_[k[1]] + w[2] * v_[k[2]] + w[3] * v_[k[3]]};
}

double WindField::max_speed() const {
  double m = 0.0;
  for (std::size_t k = 0; k < u_.size(); ++k)
    m = std::max(m, std::hypot(u_[k], v_[k]));
  return m;
}

}  // namespace plumekit::cfd
