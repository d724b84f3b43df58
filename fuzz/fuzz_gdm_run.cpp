// Fuzzes the reader of a localize run.json as `plumekit gdm --run` reads it (run/gdm_samples:
// parse_run_json, find_run_map, run_samples) with arbitrary text. Bad input must end in
// InputError. A found map is a regular file; accepted samples are at least one, each within
// sample_fault's rules, and their maps (kernel_dmv) are finite in every cell.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string_view>

#include "core/error.hpp"
#include "fuzz/gdm_maps.hpp"
#include "run/gdm_samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace run = plumekit::run;
  namespace methods = plumekit::methods;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const plumekit::Map map = plumekit::fuzz::gdm_arena();
  nlohmann::json record;
  try {
    record = run::parse_run_json(text, "run.json");
  } catch (const plumekit::InputError&) {
    return 0;
  }
  try {
    // A folder that does not exist: only a recorded absolute path can be found.
    const std::filesystem::path found =
        run::find_run_map(record, "/nonexistent-plumekit-fuzz/run/run.json", {});
    if (!std::filesystem::is_regular_file(found)) std::abort();
  } catch (const plumekit::InputError&) {
  }
  std::vector<methods::Sample> samples;
  try {
    samples = run::run_samples(record, "run.json", map);
  } catch (const plumekit::InputError&) {
    return 0;
  }
  if (samples.empty()) std::abort();
  for (const auto& s : samples)
    if (!methods::sample_fault(map, s).column.empty() || !s.wind) std::abort();
  plumekit::fuzz::check_finite_gdm_maps(map, samples);
  return 0;
}
