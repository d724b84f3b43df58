// The flow policy (cfd::solve_wind): central convection, upwind when Newton
// stalls on it (unless FlowOptions::upwind_fallback is off), and the result
// says which scheme was used.
#include <gtest/gtest.h>

#include <filesystem>

#include "cfd/flow_policy.hpp"
#include "map/map_json.hpp"

namespace plumekit::cfd {
namespace {

namespace fs = std::filesystem;
const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

// At nu = 0.001 on 20 cm cells of cluttered-1 (Re 4000, cell Peclet number
// 200) Newton finds no steady central flow; first-order upwind converges.
FlowOptions stalling_central() {
  FlowOptions o;
  o.cell = 0.2;
  o.nu = 0.001;
  return o;
}

TEST(FlowPolicy, DefaultSchemeConvergesWithoutFallingBack) {
  FlowOptions o;
  o.cell = 0.2;
  const WindResult w = solve_wind(read_map(kMaps / "cluttered-1.json"), o);
  EXPECT_TRUE(w.flow.summary.converged);
  EXPECT_EQ(w.requested, Convection::Central);
  EXPECT_EQ(w.scheme(), Convection::Central);
  EXPECT_FALSE(w.fell_back());
}

TEST(FlowPolicy, CentralStallsAndUpwindIsUsed) {
  const Map map = read_map(kMaps / "cluttered-1.json");
  const FlowOptions o = stalling_central();
  EXPECT_THROW(solve(map, o), ConvergenceError);  // the case does stall
  const WindResult w = solve_wind(map, o);
  EXPECT_TRUE(w.flow.summary.converged);
  EXPECT_EQ(w.requested, Convection::Central);
  EXPECT_EQ(w.scheme(), Convection::Upwind);
  EXPECT_TRUE(w.fell_back());
  // The wind is the upwind solve's, byte for byte.
  FlowOptions upwind = o;
  upwind.convection = Convection::Upwind;
  const FlowResult direct = solve(map, upwind);
  EXPECT_EQ(w.flow.wind.u(), direct.wind.u());
  EXPECT_EQ(w.flow.wind.v(), direct.wind.v());
}

TEST(FlowPolicy, NoFallbackWhenItIsSwitchedOff) {
  FlowOptions o = stalling_central();
  o.upwind_fallback = false;
  try {
    solve_wind(read_map(kMaps / "cluttered-1.json"), o);
    FAIL() << "central stalls and must not fall back";
  } catch (const ConvergenceError& e) {
    EXPECT_EQ(e.summary().convection, Convection::Central);
  }
}

TEST(FlowPolicy, AStalledUpwindSolveIsNotRetried) {
  FlowOptions o = stalling_central();
  o.convection = Convection::Upwind;
  o.max_iterations = 2;  // too few for any scheme
  int starts = 0;
  o.on_iteration = [&](int it, double, double) { starts += it == 0; };
  EXPECT_THROW(solve_wind(read_map(kMaps / "cluttered-1.json"), o), ConvergenceError);
  EXPECT_EQ(starts, 1);  // one attempt on the fine grid (coarse grids report no iterations)
}

}  // namespace
}  // namespace plumekit::cfd
