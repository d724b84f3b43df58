// Fuzzes the readings reader (gdm/samples: parse_samples_csv) with arbitrary text. Bad input must
// end in InputError; an accepted CSV gives at least one sample, every one within sample_fault's
// rules, with a wind for all or for none, and finite maps (kernel_dmv) in every cell.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "fuzz/gdm_maps.hpp"
#include "run/gdm_samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const plumekit::Map map = plumekit::fuzz::gdm_arena();
  std::vector<plumekit::methods::Sample> samples;
  try {
    samples = plumekit::run::parse_samples_csv(text, "fuzz.csv", map);
  } catch (const plumekit::InputError&) {
    return 0;
  }
  if (samples.empty()) std::abort();
  for (const auto& s : samples) {
    if (!std::isfinite(s.position.x) || !std::isfinite(s.position.y) || !std::isfinite(s.reading))
      std::abort();
    if (s.wind.has_value() != samples[0].wind.has_value()) std::abort();
    if (s.wind && (!std::isfinite(s.wind->x) || !std::isfinite(s.wind->y))) std::abort();
    if (!plumekit::methods::sample_fault(map, s).column.empty()) std::abort();
  }
  plumekit::fuzz::check_finite_gdm_maps(map, samples);
  return 0;
}
