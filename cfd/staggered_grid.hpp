#pragma once
// The marker-and-cell (MAC) grid: pressure at cell centres, u on the faces
// normal to x, v on the faces normal to y. It classifies every face (a fixed
// value, a free unknown, or an outflow unknown), numbers the unknowns, and
// resolves what a momentum equation sees at a neighbour: an unknown, a fixed
// value, or a ghost that mirrors the face itself to impose a wall condition.
//
// Faces are addressed per component c (0 = u, 1 = v) in (along, across)
// coordinates: `along` indexes faces in the component's own direction
// (0..n_along), `across` indexes the cells beside it. For u, (along, across)
// = (i, j); for v, (along, across) = (j, i). One code path serves both.
#include <array>
#include <cstdint>
#include <vector>

#include "cfd/options.hpp"
#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

// A value seen by an equation: scale * x[col] + offset (col < 0: a constant).
struct Ref {
  int col = -1;
  double scale = 0.0;
  double offset = 0.0;
  int local = -1;  // slot in the row's list of distinct unknowns
};

enum FaceKind : std::uint8_t { kFixed, kFree, kOutflow };

// What lies at position s along a wall (closed: every wall is a wall).
enum class WallType { Wall, Inlet, Outlet };
WallType wall_type(const Map& map, Side side, double s, bool closed);

class StaggeredGrid {
 public:
  StaggeredGrid(const Map& map, const GridShape& shape, const FlowOptions& options);

  const GridShape& shape() const { return shape_; }
  int nx() const { return shape_.nx; }
  int ny() const { return shape_.ny; }
  int n_along(int c) const { return c == 0 ? nx() : ny(); }
  int n_across(int c) const { return c == 0 ? ny() : nx(); }
  double h_along(int c) const { return c == 0 ? shape_.dx() : shape_.dy(); }
  double h_across(int c) const { return c == 0 ? shape_.dy() : shape_.dx(); }

  // Storage index of face (along a, across b) of component c.
  std::size_t face(int c, int a, int b) const {
    return c == 0 ? static_cast<std::size_t>(b) * (nx() + 1) + a
                  : static_cast<std::size_t>(a) * nx() + b;
  }
  std::size_t face_count(int c) const { return c == 0 ? (nx() + 1) * ny() : nx() * (ny() + 1); }
  // Linear cell index of the cell at (along a, across b) of component c.
  std::size_t cell(int c, int a, int b) const {
    return c == 0 ? shape_.index(a, b) : shape_.index(b, a);
  }
  bool solid(std::size_t cell) const { return solid_[cell] != 0; }
  bool solid(int c, int a, int b) const { return solid_[cell(c, a, b)] != 0; }
  const std::vector<std::uint8_t>& solid_cells() const { return solid_; }

  FaceKind kind(int c, std::size_t f) const { return static_cast<FaceKind>(kind_[c][f]); }
  double fixed_value(int c, std::size_t f) const { return fixed_[c][f]; }
  int column(int c, std::size_t f) const { return col_[c][f]; }
  int pressure_column(std::size_t cell) const { return p_col_[cell]; }
  int unknowns() const { return unknowns_; }
  int velocity_unknowns() const { return velocity_unknowns_; }
  bool has_outflow() const { return has_outflow_; }

  // What the momentum equation of face (a, b) sees:
  Ref along(int c, int a, int b, int k) const;       // the face k steps along (k = +-1, +-2)
  Ref across(int c, int a, int b, int k) const;      // the face k cells across
  Ref other(int c, int a_other, int b_other) const;  // a face of the other component
  // p in the cell on the low (a-1) or high (a) side of face (a, b); beyond an
  // outflow face, the ghost that makes p = 0 on the face.
  Ref pressure(int c, int a, int b, bool high) const;
  Ref real_face(int c, std::size_t f) const;  // fixed value or unknown, no ghost
  // The boundary condition at position s along a wall.
  WallType wall_at(Side side, double s) const { return wall_type(*map_, side, s, closed_); }
  // Which cells beside face (a, b) are fluid: 2 both, 1 only the high one (a),
  // -1 only the low one (a-1), 0 neither. +-1 marks a boundary face.
  int fluid_side(int c, int a, int b) const;
  // The map's opening that face (a, b) lies on (Map::opening_on_line), or -1;
  // always -1 in a closed box.
  int opening_at(int c, int a, int b) const;

 private:
  void seal_pockets();
  void classify_boundary_face(int c, int a, int b, bool fluid_high);
  // Whether the obstacle wall across from the faces of component c, on grid
  // line b_line of the across direction at along position a, is an outlet.
  bool outlet_across(int c, int a, int b_line) const;
  // The ghost a face sees across a domain wall (side beyond across index b).
  Ref wall_ghost(int c, int a, int b, bool beyond_high) const;

  GridShape shape_;
  std::vector<std::uint8_t> solid_;
  std::array<std::vector<std::uint8_t>, 2> kind_;
  std::array<std::vector<double>, 2> fixed_;
  std::array<std::vector<int>, 2> col_;
  std::vector<int> p_col_;
  const Map* map_;
  std::array<double, 4> wall_speed_;
  bool closed_;
  int unknowns_ = 0;
  int velocity_unknowns_ = 0;
  bool has_outflow_ = false;
};

}  // namespace plumekit::cfd
