// Fuzzes the reader of a localize run.json as `plumekit gdm --run` reads it (run/gdm_samples:
// parse_run_json, find_run_map, run_samples) with arbitrary text. Bad input must end in
// InputError. A found map is a regular file; accepted samples are at least one, each within
// sample_fault's rules, and their maps (kernel_dmv) are finite in every cell.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string_view>

#include "core/error.hpp"
#include "map/map.hpp"
#include "methods/kernel_dmv.hpp"
#include "run/gdm_samples.hpp"

namespace {

void check_maps(const plumekit::Map& map, const std::vector<plumekit::methods::Sample>& samples) {
  plumekit::methods::GdmOptions o;
  o.cell = 0.5;  // 20 x 8 cells: quick
  o.wind_stretch = 0.6;
  const plumekit::methods::GdmMaps m = plumekit::methods::kernel_dmv(map, samples, o);
  for (const auto* g : {&m.mean, &m.variance, &m.confidence, &m.weight})
    for (double v : g->values)
      if (!std::isfinite(v)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace run = plumekit::run;
  namespace methods = plumekit::methods;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  plumekit::Map map = plumekit::default_arena(10.0, 4.0);
  map.frame.origin = {-1.0, 2.0};
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
  check_maps(map, samples);
  return 0;
}
