// Fuzzes the dataset's validating reader (dataset/dataset_reader) with arbitrary text: each input
// goes to parse_manifest (manifest.json and its parts), parse_parameters (parameters.json) and
// parse_checksums (a shard's checksums.json), the three byte-level entry points. Bad input must
// end in InputError; anything else escaping is a bug, and libFuzzer reports it as a crash. An
// accepted manifest must be consistent: shards in its part, no map twice, samples summed.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <string_view>

#include "core/error.hpp"
#include "dataset/dataset_reader.hpp"

namespace ds = plumekit::dataset;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const ds::Manifest m = ds::parse_manifest(bytes, "fuzz/manifest.json");
    if (m.part_n < 1 || m.part_k < 0 || m.part_k >= m.part_n) std::abort();
    long long samples = 0;
    std::set<int> maps;
    for (const ds::ManifestShard& s : m.shards) {
      if (s.map_index < 0 || s.map_index >= m.maps || s.map_index % m.part_n != m.part_k ||
          !maps.insert(s.map_index).second || s.samples < 0)
        std::abort();
      samples += s.samples;
    }
    if (samples != m.samples) std::abort();
  } catch (const plumekit::InputError&) {
  }
  try {
    ds::parse_parameters(bytes, "fuzz/parameters.json");
  } catch (const plumekit::InputError&) {
  }
  try {
    ds::parse_checksums(bytes, "fuzz/shards/shard-00000/checksums.json");
  } catch (const plumekit::InputError&) {
  }
  return 0;
}
