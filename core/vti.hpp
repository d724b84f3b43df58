#pragma once
// VTK XML ImageData (.vti) files with cell data, for ParaView. Arrays are
// float32, stored inline as base64 "binary" (a UInt32 byte count, then the
// little-endian values), which every VTK reader accepts.
#include <string>
#include <vector>

#include "core/grid.hpp"

namespace plumekit {

struct VtiArray {
  std::string name;
  int components = 1;
  std::vector<float> values;  // cell-major (row 0 at y = 0), components interleaved
};

// The file text for a 2-D grid (one cell thick in z); `vectors` and `scalars`
// name the default arrays ParaView shows.
// `origin`: where the grid's lower-left corner lies (the map frame's position
// of the arena), so that ParaView shows the user's coordinates.
std::string vti_cell_data(const GridShape& shape, const std::vector<VtiArray>& arrays,
                          const std::string& vectors, const std::string& scalars, Vec2 origin = {});

}  // namespace plumekit
