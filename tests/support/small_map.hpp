#pragma once
// A small map with one block and two sources, for the command-line tests of
// the commands that localize (quick to solve, room for a start and a source).
#include <filesystem>
#include <fstream>
#include <string>

namespace plumekit::test {

inline const std::string kSmallMap = R"({
  "format": "plumekit-map/1", "name": "small", "size": [6.0, 3.0],
  "inlet": {"side": "left", "speed": 1.0}, "outlet": {"side": "right"},
  "obstacles": [[[2.5, 1.0], [3.0, 1.0], [3.0, 2.0], [2.5, 2.0]]],
  "sources": [[4.5, 0.5], [1.5, 0.7]]
})";

// Writes kSmallMap to DIR/maps/small.json (a folder `evaluate` can take) and returns its path.
inline std::string write_small_map(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir / "maps");
  const auto path = dir / "maps" / "small.json";
  std::ofstream(path) << kSmallMap;
  return path.string();
}

}  // namespace plumekit::test
