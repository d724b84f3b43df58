// The OpenFOAM flow engine (cfd/openfoam_engine.hpp) against plane Poiseuille
// flow, the built-in solver, itself over 2 MPI ranks, and bad input. Needs
// Debian's openfoam and openmpi-bin (scripts/install-deps.sh installs them).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cfd/flow_solver.hpp"
#include "cfd/openfoam_engine.hpp"
#include "cfd/openfoam_run.hpp"
#include "map/map_json.hpp"
#include "support/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using namespace plumekit;
using namespace plumekit::cfd;

// A 2 x 1 m channel with a fully developed (parabolic) inflow, peak 1 m/s.
const std::string kChannel = R"({
  "format": "plumekit-map/1", "name": "channel", "size": [2.0, 1.0],
  "inlet": {"side": "left", "from": 0.0, "to": 1.0, "speed": 1.0, "profile": "parabolic"},
  "outlet": {"side": "right", "from": 0.0, "to": 1.0},
  "obstacles": [], "sources": [[0.5, 0.5]]
})";
// Partial inlet and outlet spans and a block in the way.
const std::string kObstacle = R"({
  "format": "plumekit-map/1", "name": "obstacle", "size": [2.0, 1.0],
  "inlet": {"side": "left", "from": 0.2, "to": 1.0, "speed": 1.0, "profile": "uniform"},
  "outlet": {"side": "right", "from": 0.0, "to": 0.6},
  "obstacles": [[[0.6, 0.3], [0.9, 0.3], [0.9, 0.7], [0.6, 0.7]]],
  "sources": [[0.3, 0.5]]
})";

FlowOptions flow_options(double nu) {
  FlowOptions o;
  o.cell = 0.05;
  o.nu = nu;
  return o;
}

OpenFoamOptions foam_options(int ranks) {
  OpenFoamOptions f;
  f.engine = Engine::OpenFoam;
  f.ranks = ranks;
  f.tolerance = 1e-8;
  return f;
}

// ||a - b|| / ||b|| over the cell-centred velocities (zero in solid cells).
double relative_l2(const WindField& a, const WindField& b) {
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < a.u().size(); ++k) {
    num += std::pow(a.u()[k] - b.u()[k], 2) + std::pow(a.v()[k] - b.v()[k], 2);
    den += std::pow(b.u()[k], 2) + std::pow(b.v()[k], 2);
  }
  return std::sqrt(num / den);
}

// The largest |net outflow| of a fluid cell, from its face velocities, per
// unit inflow speed: the discrete divergence the later stages see.
double max_cell_divergence(const WindField& w) {
  const GridShape& s = w.shape();
  double worst = 0.0;
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      if (w.solid(i, j)) continue;
      const double div =
          (w.face_u()[j * (s.nx + 1) + i + 1] - w.face_u()[j * (s.nx + 1) + i]) * s.dy() +
          (w.face_v()[(j + 1) * s.nx + i] - w.face_v()[j * s.nx + i]) * s.dx();
      worst = std::max(worst, std::abs(div) / s.dx());
    }
  return worst;
}

class OpenFoamEngine : public test::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    ASSERT_FALSE(find_program("simpleFoam").empty())
        << "OpenFOAM is not installed: scripts/install-deps.sh installs openfoam and openmpi-bin";
  }
  OpenFoamResult solve(const std::string& map_text, const FlowOptions& flow,
                       const OpenFoamOptions& foam) {
    return solve_openfoam(parse_map(map_text, "test"), flow, foam, dir);
  }
  bool work_dir_empty() const { return fs::is_empty(dir); }
};

TEST_F(OpenFoamEngine, MatchesPlanePoiseuilleFlow) {
  const OpenFoamResult r = solve(kChannel, flow_options(0.1), foam_options(1));
  const WindField& w = r.flow.wind;
  const GridShape& s = w.shape();
  ASSERT_EQ(s.nx, 40);
  ASSERT_EQ(s.ny, 20);
  double err_u = 0.0, err_v = 0.0;
  for (int j = 0; j < s.ny; ++j) {
    const double eta = (j + 0.5) / s.ny;
    for (int i = 0; i < s.nx; ++i) {
      err_u = std::max(err_u, std::abs(w.cell_velocity(i, j).x - 4.0 * eta * (1.0 - eta)));
      err_v = std::max(err_v, std::abs(w.cell_velocity(i, j).y));
    }
  }
  EXPECT_LT(err_u, 5e-3);  // of the 1 m/s peak; measured 2.1e-3
  EXPECT_LT(err_v, 2e-3);
  // dp/dx = -12 nu mean / H^2 = -8 nu peak / H^2 = -0.8, from the mean pressure of two columns.
  double drop = 0.0;
  for (int j = 0; j < s.ny; ++j)
    drop += w.cell_pressure(30, j) - w.cell_pressure(10, j);
  EXPECT_NEAR(drop / s.ny / (20 * s.dx()), -0.8, 0.008);
  EXPECT_TRUE(work_dir_empty()) << "the temporary case was not removed";
}

TEST_F(OpenFoamEngine, TwoMpiRanksGiveTheSerialFieldAndBalanceMass) {
  const OpenFoamResult serial = solve(kObstacle, flow_options(0.02), foam_options(1));
  const OpenFoamResult parallel = solve(kObstacle, flow_options(0.02), foam_options(2));
  EXPECT_EQ(parallel.run.ranks, 2);
  EXPECT_TRUE(parallel.run.converged);
  EXPECT_LT(relative_l2(parallel.flow.wind, serial.flow.wind), 1e-5);
  for (const OpenFoamResult* r : {&serial, &parallel}) {
    const FlowSummary& s = r->flow.summary;
    EXPECT_NEAR(s.inflow, 0.8, 1e-9);  // 1 m/s over the inlet's 0.8 m
    EXPECT_LT(s.mass_imbalance, 1e-6);
    EXPECT_LT(max_cell_divergence(r->flow.wind), 1e-5);
  }
  EXPECT_TRUE(work_dir_empty());
}

TEST_F(OpenFoamEngine, AgreesWithTheBuiltInSolver) {
  FlowOptions flow = flow_options(0.05);
  flow.convection = Convection::Central;
  const OpenFoamResult foam = solve(kObstacle, flow, foam_options(1));
  const FlowResult builtin = cfd::solve(parse_map(kObstacle, "test"), flow);
  // Measured 1.8 %: collocated linearUpwind vs the staggered central scheme,
  // largest at the outlet's end (docs/design/flow-solver.md, "OpenFOAM engine").
  EXPECT_LT(relative_l2(foam.flow.wind, builtin.wind), 0.03);
  const FlowResult channel_builtin = cfd::solve(parse_map(kChannel, "test"), flow_options(0.1));
  const OpenFoamResult channel = solve(kChannel, flow_options(0.1), foam_options(1));
  EXPECT_LT(relative_l2(channel.flow.wind, channel_builtin.wind), 5e-3);
  for (std::size_t k = 0; k < builtin.wind.solid_cells().size(); ++k)
    ASSERT_EQ(foam.flow.wind.solid_cells()[k], builtin.wind.solid_cells()[k]) << k;
}

// A plumekit-map/2 building: two inlets, an outlet on the arena wall and a
// vent on the outer wall's inner edge (an obstacle's edge, y = 3.6 m, x 4..5 m).
TEST_F(OpenFoamEngine, TakesEveryOpeningFromTheGridOnAMapV2Building) {
  const Map map = read_map(fs::path(PLUMEKIT_TEST_DATA) / "maps-v2" / "building.json");
  FlowOptions flow = flow_options(0.05);
  flow.cell = 0.1;
  const OpenFoamResult foam = solve_openfoam(map, flow, foam_options(1), dir);
  const FlowResult builtin = cfd::solve(map, flow);
  EXPECT_NEAR(foam.flow.summary.inflow, builtin.summary.inflow, 1e-9);
  EXPECT_LT(foam.flow.summary.mass_imbalance, 1e-6);
  EXPECT_LT(relative_l2(foam.flow.wind, builtin.wind), 0.04);  // measured 2.4 %
  const WindField& w = foam.flow.wind;
  double vent = 0.0;
  for (int i = 40; i < 50; ++i)
    vent += w.face_v()[36 * w.shape().nx + i] * w.shape().dx();
  EXPECT_GT(vent, 0.1);  // out through the vent
}

TEST_F(OpenFoamEngine, RunsTheKOmegaSstModel) {
  OpenFoamOptions foam = foam_options(1);
  foam.turbulence = FoamTurbulence::KOmegaSST;
  foam.tolerance = 1e-6;
  const OpenFoamResult r = solve(kObstacle, flow_options(1.5e-5), foam);
  EXPECT_TRUE(r.run.converged);
  EXPECT_EQ(r.run.residuals.count("k"), 1u);
  EXPECT_EQ(r.run.residuals.count("omega"), 1u);
  EXPECT_LT(r.flow.summary.mass_imbalance, 1e-5);
  EXPECT_GT(r.flow.summary.max_speed, 1.0);
}

TEST_F(OpenFoamEngine, RefusesBadInputAndLeavesNothing) {
  const Map map = parse_map(kObstacle, "test");
  OpenFoamOptions foam = foam_options(0);
  try {
    solve_openfoam(map, flow_options(0.05), foam, dir);
    FAIL() << "ranks 0 accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "flow.ranks");
  }
  OpenFoamOptions builtin;  // the built-in engine with an OpenFOAM-only option
  builtin.ranks = 2;
  try {
    builtin.validate();
    FAIL() << "flow.ranks accepted with the built-in engine";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "flow.ranks");
  }
  FlowOptions mixing = flow_options(0.05);
  mixing.turbulence = Turbulence::MixingLength;
  try {
    solve_openfoam(map, mixing, foam_options(1), dir);
    FAIL() << "mixing length accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "flow.turbulence");
  }
  foam = foam_options(1);
  foam.max_iterations = 5;
  EXPECT_THROW(solve_openfoam(map, flow_options(0.05), foam, dir), ConvergenceError);
  EXPECT_TRUE(work_dir_empty());
}

// Stand-ins for OpenFOAM's programs, first on PATH: each prints `says` and exits `code`.
void fake_program(const fs::path& dir, const std::string& name, const std::string& says, int code) {
  fs::create_directories(dir);
  std::ofstream(dir / name) << "#!/bin/sh\necho '" << says << "'\nexit " << code << "\n";
  fs::permissions(dir / name, fs::perms::owner_all);
}

TEST_F(OpenFoamEngine, ReportsAFailingRankWithItsLog) {
  const fs::path bin = dir / "fake-bin";
  const fs::path work = dir / "work";
  fs::create_directories(work);
  fake_program(bin, "simpleFoam", "unused", 0);
  fake_program(bin, "decomposePar", "decomposed", 0);
  fake_program(bin, "reconstructPar", "unused", 0);
  fake_program(bin, "mpirun", "mpirun noticed that process rank 1 exited on signal 9", 137);
  const std::string path = std::getenv("PATH");
  setenv("PATH", bin.c_str(), 1);
  try {
    solve_openfoam(parse_map(kObstacle, "test"), flow_options(0.05), foam_options(2), work);
    ADD_FAILURE() << "a failing rank was not reported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("`mpirun -np 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("exit 137"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("process rank 1 exited"), std::string::npos) << e.what();
  }
  setenv("PATH", path.c_str(), 1);
  EXPECT_TRUE(fs::is_empty(work));
}

TEST_F(OpenFoamEngine, CommandWritesTheWindOrExitsTwoWithNoOutput) {
  const fs::path map = dir / "obstacle.json";
  std::ofstream(map) << kObstacle;
  const std::string args = "flow " + map.string() + " --cell 0.05 --engine openfoam --json --out ";
  auto r = run(args + (dir / "wind").string() + " --ranks 2");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["engine"], "openfoam");
  EXPECT_EQ(j["openfoam"]["ranks"], 2);
  EXPECT_EQ(j["turbulence"], "laminar");
  EXPECT_GT(j["openfoam"]["iterations"].get<int>(), 10);
  for (const char* f : {"u.npy", "v.npy", "p.npy", "wind.json", "wind.vti", "wind.png"})
    EXPECT_TRUE(fs::exists(dir / "wind" / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "wind" / "openfoam-case"));
  // Later stages read OpenFOAM's wind back (cfd/wind_file.hpp).
  const fs::path plume = dir / "plume";
  r = run("plume " + map.string() + " --source 0.5,0.5 --wind " + (dir / "wind").string() +
          " --out " + plume.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(plume / "mean.npy"));
  fs::remove_all(plume);

  r = run(args + (dir / "bad").string() + " --ranks 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--ranks"), std::string::npos) << r.err;
  r = run(args + (dir / "bad").string() + " --foam-max-iter 5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("did not converge"), std::string::npos) << r.err;
  const std::string path = std::getenv("PATH");
  setenv("PATH", (dir / "no-openfoam-here").c_str(), 1);
  r = run(args + (dir / "bad").string());
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("openfoam"), std::string::npos) << r.err;
  // Nothing but the map and the good output: no partial output, no temporaries.
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir))
    left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"obstacle.json", "wind"}));
}

}  // namespace
