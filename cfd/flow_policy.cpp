#include "cfd/flow_policy.hpp"

#include <malloc.h>

namespace plumekit::cfd {

void tune_malloc_for_flow() {
  // Each LU factorization frees and allocates tens of MB. Above glibc's mmap
  // threshold every allocation is fresh pages from the kernel, zeroed and
  // faulted in one by one (a tenth of a 5 cm solve's time); keep freed memory
  // in the heap for the next factorization instead. Set once per process.
  static const bool tuned = [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    return true;
  }();
  (void)tuned;
}

WindResult solve_wind(const Map& map, const FlowOptions& options) {
  tune_malloc_for_flow();
  try {
    return {solve(map, options), options.convection};
  } catch (const ConvergenceError&) {
    if (!options.upwind_fallback || options.convection == Convection::Upwind) throw;
  }
  FlowOptions upwind = options;
  upwind.convection = Convection::Upwind;
  return {solve(map, upwind), options.convection};
}

}  // namespace plumekit::cfd
