#pragma once
// The flow policy: how every plumekit command that needs a wind gets one.
//
//   cfd::WindResult w = cfd::solve_wind(map, options);
//   w.flow.wind ...; w.scheme(); w.fell_back()
//
// cfd::solve with the options' convection; when Newton does not converge
// with central or van Leer convection and options.upwind_fallback is set (the
// default), solve again with first-order upwind, which converges where the
// others find no steady flow (at high cell Peclet numbers). The result says
// which scheme was used. Also tunes malloc for the LU factorizations, once per
// process (flow_policy.cpp says why).
#include "cfd/flow_solver.hpp"

namespace plumekit::cfd {

struct WindResult {
  FlowResult flow;       // flow.summary.convection: the scheme that was used
  Convection requested;  // options.convection
  Convection scheme() const { return flow.summary.convection; }
  bool fell_back() const { return scheme() != requested; }
};

// Throws what cfd::solve throws; a ConvergenceError is the last attempt's.
WindResult solve_wind(const Map& map, const FlowOptions& options);

// Keeps freed memory in the heap for the next factorization (mallopt). Called
// by solve_wind; idempotent.
void tune_malloc_for_flow();

}  // namespace plumekit::cfd
