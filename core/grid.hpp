#pragma once
// A uniform cell-centred grid over the arena [0, width] x [0, height].
// Storage is row-major with row 0 at y = 0: value(i, j) is column i (x), row j (y).
#include <cassert>
#include <cstddef>
#include <vector>

#include "core/geometry.hpp"

namespace plumekit {

struct GridShape {
  int nx = 0;
  int ny = 0;
  double width = 0.0;
  double height = 0.0;

  double dx() const { return width / nx; }
  double dy() const { return height / ny; }
  std::size_t size() const { return static_cast<std::size_t>(nx) * ny; }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * nx + i; }
  Vec2 centre(int i, int j) const { return {(i + 0.5) * dx(), (j + 0.5) * dy()}; }
  bool contains(int i, int j) const { return i >= 0 && i < nx && j >= 0 && j < ny; }

  // Bilinear interpolation between cell centres: value(p) = sum of w_ab f(i_a, j_b),
  // with weights (1-tx)(1-ty), tx(1-ty), (1-tx)ty, tx ty; constant beyond the
  // outermost centres.
  struct Bilinear {
    int i0, i1, j0, j1;
    double tx, ty;
  };
  Bilinear bilinear(Vec2 p) const;

  // The grid whose cells are as close to `cell` metres as an integer count
  // allows: n = max(1, round(extent / cell)); the cell is then extent / n.
  static GridShape with_cell(double width, double height, double cell);
};

template <class T>
struct Grid {
  GridShape shape;
  std::vector<T> values;

  Grid() = default;
  Grid(GridShape s, T fill) : shape(s), values(s.size(), fill) {}

  T& operator()(int i, int j) {
    assert(shape.contains(i, j));
    return values[shape.index(i, j)];
  }
  const T& operator()(int i, int j) const {
    assert(shape.contains(i, j));
    return values[shape.index(i, j)];
  }
};

}  // namespace plumekit
