// Fuzzes the readings reader (gdm/samples: parse_samples_csv) with arbitrary text. Bad input must
// end in InputError; an accepted CSV gives at least one sample, every one within sample_fault's
// rules, with a wind for all or for none, and finite maps (kernel_dmv) in every cell.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "map/map.hpp"
#include "methods/kernel_dmv.hpp"
#include "run/gdm_samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  plumekit::Map map = plumekit::default_arena(10.0, 4.0);
  map.frame.origin = {-1.0, 2.0};
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
  plumekit::methods::GdmOptions o;
  o.cell = 0.5;  // 20 x 8 cells: quick
  o.wind_stretch = 0.6;
  const plumekit::methods::GdmMaps m = plumekit::methods::kernel_dmv(map, samples, o);
  for (const auto* g : {&m.mean, &m.variance, &m.confidence, &m.weight})
    for (double v : g->values)
      if (!std::isfinite(v)) std::abort();
  return 0;
}
