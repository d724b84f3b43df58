// The flow solver on the shipped cluttered maps, its outputs, and bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>
#include <vector>

#include "cfd/flow_output.hpp"
#include "cfd/flow_solver.hpp"
#include "core/atomic_file.hpp"
#include "core/npy.hpp"
#include "map/map_json.hpp"

namespace plumekit::cfd {
namespace {

namespace fs = std::filesystem;
const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

void expect_sound_flow(const Map& map, const FlowResult& r) {
  const FlowSummary& s = r.summary;
  EXPECT_TRUE(s.converged);
  EXPECT_LT(s.momentum_residual, s.tolerance);
  EXPECT_LT(s.continuity_residual, s.tolerance);
  EXPECT_NEAR(s.inflow, map.first_inlet().speed * map.height, 1e-9);
  EXPECT_LT(s.mass_imbalance, 1e-12);
  const WindField& w = r.wind;
  const GridShape& g = w.shape();
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      if (!w.solid(i, j)) continue;
      // No flow inside obstacles, nor through the faces of solid cells.
      EXPECT_EQ(w.cell_velocity(i, j).x, 0.0);
      EXPECT_EQ(w.cell_velocity(i, j).y, 0.0);
      EXPECT_EQ(w.face_u()[j * (g.nx + 1) + i], 0.0);
      EXPECT_EQ(w.face_v()[j * g.nx + i], 0.0);
    }
  for (const Polygon& poly : map.obstacles) {
    Vec2 c{0, 0};
    for (Vec2 v : poly)
      c = c + (1.0 / poly.size()) * v;
    if (map.obstacle_at(c) >= 0) {
      EXPECT_EQ(norm(w.at(c)), 0.0);
    }
  }
}

TEST(FlowMaps, ShippedMapsConvergeBalanceMassAndStayOutOfObstacles) {
  for (const char* name :
       {"empty.json", "cluttered-1.json", "cluttered-2.json", "cluttered-3.json"}) {
    SCOPED_TRACE(name);
    const Map map = read_map(kMaps / name);
    const FlowResult r = solve(map, FlowOptions{});
    expect_sound_flow(map, r);
    // The flow goes round obstacles: somewhere it runs backwards (recirculation).
    if (!map.obstacles.empty()) {
      double most_negative = 0.0;
      for (double u : r.wind.u())
        most_negative = std::min(most_negative, u);
      EXPECT_LT(most_negative, -0.05);
    }
  }
}

// The mixing-length closure at nu = 0.001 on a shipped map, checked for soundness.
FlowResult mixing_length_flow(const char* name) {
  const Map map = read_map(kMaps / name);
  FlowOptions o;
  o.turbulence = Turbulence::MixingLength;
  o.nu = 1e-3;
  FlowResult r = solve(map, o);
  expect_sound_flow(map, r);
  return r;
}

TEST(FlowMaps, MixingLengthAddsEddyViscosityAndConverges) {
  EXPECT_GT(mixing_length_flow("cluttered-2.json").summary.max_eddy_viscosity, 1e-3);
}

TEST(FlowMaps, MixingLengthSettlesWithinTheLaminarIterationBudget) {
  // cluttered-1: the plainly relaxed eddy viscosity took 120 iterations to
  // settle; Anderson-mixed updates take 71 (docs/design/flow-solver.md).
  EXPECT_LT(mixing_length_flow("cluttered-1.json").summary.iterations, 100);
}

TEST(FlowMaps, EverySchemeConvergesOnAClutteredMap) {
  const Map map = read_map(kMaps / "cluttered-3.json");
  for (Convection c : {Convection::Upwind, Convection::Central, Convection::VanLeer}) {
    FlowOptions o;
    o.convection = c;
    o.cell = 0.1;
    expect_sound_flow(map, solve(map, o));
  }
}

TEST(FlowMaps, SameInputGivesTheSameBytes) {
  const Map map = read_map(kMaps / "cluttered-1.json");
  FlowOptions o;
  o.cell = 0.1;
  const FlowResult a = solve(map, o), b = solve(map, o);
  EXPECT_EQ(npy_float32(a.wind.u(), {1, a.wind.u().size()}),
            npy_float32(b.wind.u(), {1, b.wind.u().size()}));
}

// Dataset workers solve flows side by side. The BLAS under UMFPACK must then
// neither race (Debian's serial OpenBLAS does) nor split its work by thread
// count: concurrent solves give the bytes of a solve alone.
TEST(FlowMaps, ConcurrentSolvesGiveTheBytesOfASolveAlone) {
  const Map map = read_map(kMaps / "cluttered-1.json");
  const FlowOptions o;  // the default 5 cm grid: large fronts, long BLAS calls
  const std::vector<double> alone = solve(map, o).wind.face_u();
  for (int round = 0; round < 3; ++round) {
    std::vector<double> got[2];
    std::thread other([&] { got[1] = solve(map, o).wind.face_u(); });
    got[0] = solve(map, o).wind.face_u();
    other.join();
    EXPECT_TRUE(got[0] == alone) << "round " << round;
    EXPECT_TRUE(got[1] == alone) << "round " << round;
  }
}

TEST(FlowMaps, WindSamplingIsBilinearBetweenCellCentres) {
  const Map map = read_map(kMaps / "empty.json");
  FlowOptions o;
  o.cell = 0.1;
  const FlowResult r = solve(map, o);
  const WindField& w = r.wind;
  // At a cell centre the sample is the cell value; halfway between two it is their mean.
  EXPECT_NEAR(w.at({5.05, 2.05}).x, w.cell_velocity(50, 20).x, 1e-12);
  EXPECT_NEAR(w.at({5.1, 2.05}).x, 0.5 * (w.cell_velocity(50, 20).x + w.cell_velocity(51, 20).x),
              1e-12);
  EXPECT_EQ(norm(w.at({-1.0, 2.0})), 0.0);  // outside the arena
}

TEST(FlowMaps, OutputsHaveTheDocumentedShapesAndContent) {
  const Map map = read_map(kMaps / "cluttered-2.json");
  FlowOptions o;
  o.cell = 0.1;
  const FlowResult r = solve(map, o);
  const fs::path dir = fs::temp_directory_path() / "plumekit_flow_output_test";
  fs::remove_all(dir);
  write_flow(dir, map, r, o);
  for (const char* f : {"u.npy", "v.npy", "p.npy", "wind.vti", "wind.png", "wind.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const NpyArray u = read_npy(dir / "u.npy");
  ASSERT_EQ(u.shape, (std::vector<std::size_t>{40, 100}));  // (ny, nx)
  // Row 0 is y = 0: compare a cell near the bottom-left.
  EXPECT_NEAR(u.values[3 * 100 + 7], r.wind.cell_velocity(7, 3).x, 1e-6);
  const auto summary = nlohmann::json::parse(read_file(dir / "wind.json"));
  EXPECT_EQ(summary["grid"]["nx"], 100);
  EXPECT_EQ(summary["grid"]["ny"], 40);
  EXPECT_LT(summary["mass_imbalance"].get<double>(), 1e-12);
  const std::string vti = read_file(dir / "wind.vti");
  EXPECT_NE(vti.find("WholeExtent=\"0 100 0 40 0 0\""), std::string::npos);
  EXPECT_NE(vti.find("Name=\"velocity\" NumberOfComponents=\"3\" format=\"binary\""),
            std::string::npos);
  fs::remove_all(dir);
}

std::string error_of(const Map& map, const FlowOptions& o) {
  try {
    solve(map, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FlowMaps, RefusesBadInput) {
  const Map map = read_map(kMaps / "cluttered-1.json");
  FlowOptions o;
  o.nu = -0.01;
  EXPECT_NE(error_of(map, o).find("flow.nu: must be a finite number more than 0"),
            std::string::npos);
  o = FlowOptions{};
  o.cell = 2.0;  // 5 x 2 cells
  EXPECT_NE(error_of(map, o).find("at least 3 cells"), std::string::npos);

  // Two obstacles 4 cm apart: open in the map, closed by 5 cm cells.
  Map gap = default_arena(4.0, 2.0);
  gap.obstacles = {{{1.5, 0.4}, {2.5, 0.4}, {2.5, 1.0}, {1.5, 1.0}},
                   {{1.5, 1.04}, {2.5, 1.04}, {2.5, 1.6}, {1.5, 1.6}}};
  o = FlowOptions{};
  o.strict_gaps = true;  // by default the grid closes the gap, with a warning
  EXPECT_NE(error_of(gap, o).find("0.04 m apart"), std::string::npos);
  o = FlowOptions{};
  o.cell = 0.02;
  o.nu = 0.05;                      // (a steady flow at this size)
  EXPECT_EQ(error_of(gap, o), "");  // fine enough to keep the gap open

  Map blocked = default_arena();
  blocked.obstacles = {{{3, 0}, {4, 0}, {4, 4}, {3, 4}}};
  EXPECT_NE(error_of(blocked, FlowOptions{}).find("no free path"), std::string::npos);
}

TEST(FlowMaps, NonConvergenceReportsTheHistoryAndWritesNothing) {
  const Map map = read_map(kMaps / "cluttered-1.json");
  FlowOptions o;
  o.max_iterations = 2;
  try {
    solve(map, o);
    FAIL() << "converged in 2 iterations";
  } catch (const ConvergenceError& e) {
    EXPECT_FALSE(e.summary().converged);
    EXPECT_EQ(e.summary().history.size(), 3u);
    EXPECT_NE(std::string(e.what()).find("Residual history"), std::string::npos);
  }
}

}  // namespace
}  // namespace plumekit::cfd
