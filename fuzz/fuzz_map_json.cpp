// Fuzzes the map reader (core/map_json: parse_map) with arbitrary text. Bad input must end in
// InputError; anything else escaping is a bug, and libFuzzer reports it as a crash. A map that is
// accepted must survive a write and a re-read unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "map/map_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  plumekit::Map map;
  try {
    map = plumekit::parse_map(text, "fuzz.json");
  } catch (const plumekit::InputError&) {
    return 0;
  }
  const std::string written = plumekit::map_to_json(map).dump(2);
  const plumekit::Map reread = plumekit::parse_map(written, "fuzz-rewritten.json");
  if (plumekit::map_to_json(reread).dump(2) != written) std::abort();
  return 0;
}
