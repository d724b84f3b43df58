// Fuzzes the ROS map_server importer (core/ros_import: import_ros_map), YAML and image together.
// An input is the YAML text, a NUL byte, then the image bytes (PGM or PNG); without a NUL it is
// all YAML. The importer takes a path, so both parts go to files in a private temporary folder,
// the image as image.pgm, the name the seed YAMLs give. Bad input must end in InputError;
// anything else escaping is a bug, and libFuzzer reports it as a crash. An accepted import must
// be a valid map of the image's size.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "fuzz/scratch_folder.hpp"
#include "map/map_json.hpp"
#include "map/ros_import.hpp"

namespace fs = std::filesystem;
using plumekit::fuzz::scratch_folder;
using plumekit::fuzz::write_file;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view yaml = input.substr(0, nul);
  const std::string_view image = nul == std::string_view::npos ? "" : input.substr(nul + 1);
  const fs::path& dir = scratch_folder("ros");
  write_file(dir / "map.yaml", yaml);
  write_file(dir / "image.pgm", image);
  try {
    const plumekit::RosImport result = plumekit::import_ros_map(dir / "map.yaml", {});
    plumekit::validate_map(result.map, "fuzz import");
    if (result.occupied.rows != result.rows || result.occupied.cols != result.cols) std::abort();
  } catch (const plumekit::InputError&) {
  }
  return 0;
}
