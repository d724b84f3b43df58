// FlowOptions::validate, the grid size and memory checks before a solve, and
// the advice of the messages (field names, never flags; the right direction).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "cfd/flow_solver.hpp"
#include "cfd/grid_check.hpp"
#include "core/memory_limit.hpp"

namespace plumekit::cfd {
namespace {

class MemoryLimitScope {
 public:
  explicit MemoryLimitScope(double bytes) { set_memory_limit(bytes); }
  ~MemoryLimitScope() { set_memory_limit(default_memory_limit()); }
};

template <class E, class F>
E error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e;
  }
  ADD_FAILURE() << "no exception of the expected type";
  throw std::logic_error("unreachable");
}

void expect_has(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

TEST(FlowOptions, EveryFieldIsRangeChecked) {
  struct Case {
    const char* field;
    void (*set)(FlowOptions&);
    const char* range;
  } cases[] = {
      {"flow.cell", [](FlowOptions& o) { o.cell = -0.05; }, "more than 0 and at most 10 m"},
      {"flow.cell", [](FlowOptions& o) { o.cell = 11.0; }, "0 (the default) is 0.05 m"},
      {"flow.cell", [](FlowOptions& o) { o.cell = NAN; }, "got nan"},
      {"flow.nu", [](FlowOptions& o) { o.nu = 1e9; }, "at most 10 m^2/s, got 1e+09"},
      {"flow.nu", [](FlowOptions& o) { o.nu = -1.0; }, "got -1"},
      {"flow.tolerance", [](FlowOptions& o) { o.tolerance = 0.0; }, "from 1e-14 to 0.1"},
      {"flow.max_iterations", [](FlowOptions& o) { o.max_iterations = -1; }, "from 0 to 100000"},
      {"flow.kappa", [](FlowOptions& o) { o.kappa = INFINITY; }, "got inf"},
      {"flow.lm_max", [](FlowOptions& o) { o.lm_max = NAN; }, "got nan"},
      {"flow.wall_speed.top", [](FlowOptions& o) { o.wall_speed[3] = 1e6; }, "to 100 m/s"},
  };
  const Map map = default_arena();
  for (const Case& c : cases) {
    FlowOptions o;
    c.set(o);
    const auto e = error_of<OptionError>([&] { solve(map, o); });
    EXPECT_EQ(e.field(), c.field);
    expect_has(e.message(), c.range);
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(FlowOptions().validate());
}

TEST(FlowOptions, EnumNamesRoundTripAndUnknownNamesNameTheField) {
  for (Turbulence t : {Turbulence::None, Turbulence::MixingLength})
    EXPECT_EQ(parse_turbulence(to_string(t)), t);
  for (Convection c : {Convection::Upwind, Convection::Central, Convection::VanLeer})
    EXPECT_EQ(parse_convection(to_string(c)), c);
  for (LinearSolverKind k : {LinearSolverKind::Nullspace, LinearSolverKind::Coupled})
    EXPECT_EQ(parse_linear_solver(to_string(k)), k);
  EXPECT_EQ(convection_names(), "upwind, central, vanleer");

  auto e = error_of<OptionError>([] { parse_convection("Central"); });
  EXPECT_EQ(e.field(), "flow.convection");
  expect_has(e.message(), "unknown name 'Central'; use one of upwind, central, vanleer");
  e = error_of<OptionError>([] { parse_turbulence("k-epsilon"); });
  EXPECT_EQ(e.field(), "flow.turbulence");
  expect_has(e.message(), "none, mixing-length");
  e = error_of<OptionError>([] { parse_linear_solver(""); });
  EXPECT_EQ(e.field(), "flow.linear_solver");
  expect_has(e.message(), "nullspace, coupled");
}

TEST(FlowGridSize, TooFewOrTooManyCellsNameTheCellThatFits) {
  FlowOptions o;
  o.cell = 2.0;
  auto e = error_of<OptionError>([&] { solve(default_arena(), o); });
  EXPECT_EQ(e.field(), "flow.cell");
  expect_has(e.message(), "use a cell of at most 1.333 m");
  o.cell = 0.001;  // 10000 x 4000 cells
  e = error_of<OptionError>([&] { solve(default_arena(), o); });
  expect_has(e.message(), "4e+07 cells");
  expect_has(e.message(), "use a cell of at least 0.0032 m");
}

TEST(FlowGridSize, HundredMetreArenaAtFiveCentimetresIsRefusedQuickly) {
  const MemoryLimitScope scope(parse_memory_size("8G"));
  const Map map = default_arena(100.0, 100.0);
  const auto t0 = std::chrono::steady_clock::now();
  FlowOptions five_cm;
  five_cm.cell = 0.05;  // the default would be 0.15 m on this arena
  const auto e = error_of<MemoryLimitError>([&] { solve(map, five_cm); });
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  const std::string m = e.what();
  expect_has(m, "the flow solve on 2000 x 2000 cells of 0.05 m needs about");
  expect_has(m, "limit of 8.0 GiB");
  expect_has(m, "use a larger flow.cell (");
  // The advised cell does fit.
  const std::size_t at = m.find("flow.cell (") + 11;
  FlowOptions fits;
  fits.cell = std::stod(m.substr(at));
  EXPECT_GT(fits.cell, 0.05);
  EXPECT_LT(fits.cell, 0.2);
  EXPECT_NO_THROW(check_grid_size(map, fits));
}

TEST(FlowGridSize, EstimateCoversTheMeasuredPeaks) {
  // Measured peak RSS (KiB) of `plumekit flow` (docs/design/flow-solver.md, "Memory estimate"): the
  // estimate is an upper bound, and not a loose one.
  struct Point {
    double cells, rss;
  } measured[] = {{100 * 40, 41480e3 * 1.024},
                  {200 * 80, 90220e3 * 1.024},
                  {400 * 160, 316912e3 * 1.024},
                  {571 * 229, 675552e3 * 1.024},
                  {800 * 320, 1278436e3 * 1.024},
                  // 10 x 10 and 20 x 20 m squares at 5 cm: more fill per cell.
                  {200 * 200, 294376e3 * 1.024},
                  {400 * 400, 1242464e3 * 1.024}};
  for (const Point& p : measured) {
    EXPECT_GE(flow_memory_estimate(p.cells), p.rss) << p.cells;
    EXPECT_LE(flow_memory_estimate(p.cells), 2.0 * p.rss) << p.cells;
  }
}

TEST(FlowMessages, NarrowGapNamesTheFieldAndAFinerCell) {
  Map map = default_arena();
  map.obstacles.push_back({{3.0, 0.0}, {4.0, 0.0}, {4.0, 1.9}, {3.0, 1.9}});
  map.obstacles.push_back({{3.0, 1.93}, {4.0, 1.93}, {4.0, 4.0}, {3.0, 4.0}});
  FlowOptions strict;
  strict.strict_gaps = true;  // by default the grid closes the gap, with a warning
  const auto e = error_of<OptionError>([&] { solve(map, strict); });
  EXPECT_EQ(e.field(), "flow.cell");
  expect_has(e.message(), "0.03 m apart");
  expect_has(e.message(), "use a cell of 0.029 m or finer");  // 0.03 m: 333 cells of 0.03003 m
  EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
}

TEST(FlowMessages, NonConvergenceAdviceFollowsTheReynoldsNumber) {
  FlowOptions viscous;
  viscous.nu = 10.0;  // Re = 1 m/s * 4 m / 10 = 0.4
  viscous.max_iterations = 1;
  viscous.sequencing = false;
  viscous.cell = 0.2;
  auto e = error_of<ConvergenceError>([&] { solve(default_arena(), viscous); });
  expect_has(e.what(), "Reynolds number 0.4");
  expect_has(e.what(), "try a smaller flow.nu");
  EXPECT_EQ(std::string(e.what()).find("larger flow.nu"), std::string::npos);

  FlowOptions fast = viscous;
  fast.nu = 0.001;
  e = error_of<ConvergenceError>([&] { solve(default_arena(), fast); });
  expect_has(e.what(), "Try a larger flow.nu, a finer flow.cell, or upwind convection");
  EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace plumekit::cfd
