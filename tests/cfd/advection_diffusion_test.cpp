// The steady advection-diffusion plume against the analytic point-source
// solution, its conservation, and the adjoint identity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../cfd/reference_csv.hpp"
#include "cfd/advection_diffusion.hpp"
#include "cfd/flow_solver.hpp"
#include "map/map_json.hpp"
#include "support/uniform_wind.hpp"

namespace plumekit::dataset {
namespace {

// Value of a flow-grid field at a point, as sensors read it.
double at(const cfd::AdvectionDiffusion& ad, const Grid<double>& c, Vec2 p) {
  double v = 0.0;
  for (const auto& [k, w] : ad.point_weights(p))
    v += w * c.values[k];
  return v;
}

// The tabulated benchmark: u = 1, D = 0.1, Q = 1, source (2, 5), zero-flux
// walls at y = 0 and 10 (column C_wall_images), domain [0, 50] x [0, 10].
class PointSource : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    wind_ = new cfd::WindField(test::uniform_wind(50.0, 10.0, 0.1, 1.0));
    ad_ = new cfd::AdvectionDiffusion(*wind_, {0.1, 1.0});
    c_ = new Grid<double>(ad_->solve({2.0, 5.0}));
  }
  static void TearDownTestSuite() {
    delete c_;
    delete ad_;
    delete wind_;
  }
  static cfd::WindField* wind_;
  static cfd::AdvectionDiffusion* ad_;
  static Grid<double>* c_;
};
cfd::WindField* PointSource::wind_ = nullptr;
cfd::AdvectionDiffusion* PointSource::ad_ = nullptr;
Grid<double>* PointSource::c_ = nullptr;

TEST_F(PointSource, MatchesAnalyticSolutionInTheFarField) {
  const test::Table t = test::read_reference("plume2d_point_source_analytic.csv");
  ASSERT_FALSE(t.at("x").empty());
  int checked = 0;
  double worst = 0.0;
  for (std::size_t k = 0; k < t.at("x").size(); ++k) {
    const double x = t.at("x")[k], y = t.at("y")[k], r = t.at("r")[k];
    const double exact = t.at("C_wall_images")[k];
    // Far field: several diffusion lengths from the source (u r / 2D >= 20),
    // downstream, and clear of the open outlet's boundary layer.
    if (r < 4.0 || x < 2.0 || x > 45.0 || exact < 1e-3) continue;
    const double c = at(*ad_, *c_, {x, y});
    EXPECT_NEAR(c, exact, 0.05 * exact) << "at (" << x << ", " << y << ")";
    worst = std::max(worst, std::abs(c - exact) / exact);
    ++checked;
  }
  EXPECT_GE(checked, 10);
  std::printf("far field: %d points, worst relative error %.4f\n", checked, worst);
}

TEST_F(PointSource, FluxThroughEveryDownstreamSectionIsTheReleaseRate) {
  const GridShape& g = ad_->shape();
  for (int i = 1; i <= g.nx; ++i) {
    const double x = i * g.dx();
    const double flux = ad_->flux_through_column(*c_, i);
    // The release is shared by the cells either side of x = 2: skip that face.
    if (x > 2.0 + 1e-9) {
      EXPECT_NEAR(flux, 1.0, 1e-6) << "section x = " << x;
    } else if (x < 2.0 - 1e-9) {
      EXPECT_NEAR(flux, 0.0, 1e-6) << "upstream section x = " << x;
    }
  }
}

TEST_F(PointSource, IsNonNegative) {
  for (double v : c_->values)
    EXPECT_GE(v, 0.0);
}

// The adjoint reading of a sensor for a source equals the forward solution
// of that source read at the sensor, in a solved cluttered flow.
TEST(AdvectionDiffusion, AdjointEqualsForwardInClutteredFlow) {
  const Map map = read_map(std::string(PLUMEKIT_DATA_DIR) + "/maps/cluttered-1.json");
  cfd::FlowOptions fo;
  fo.cell = 0.1;
  const cfd::FlowResult flow = cfd::solve(map, fo);
  const cfd::AdvectionDiffusion ad(flow.wind);
  const GridShape& g = ad.shape();
  for (const Vec2 sensor : {Vec2{5.3, 1.0}, Vec2{8.0, 3.1}, Vec2{4.0, 3.5}}) {
    const Grid<double> adj = ad.adjoint(sensor);
    int compared = 0;
    for (const auto& [i, j] : {std::pair{5, 10}, std::pair{12, 30}, std::pair{20, 5},
                               std::pair{45, 20}, std::pair{60, 35}}) {
      if (ad.solid(i, j)) continue;
      const Grid<double> fwd = ad.solve(g.centre(i, j));
      const double expected = at(ad, fwd, sensor);
      EXPECT_NEAR(adj(i, j), expected, 1e-9 * std::max(1.0, std::abs(expected)));
      ++compared;
    }
    EXPECT_GE(compared, 4);
  }
  // The plume reaches round the L: a source upstream of it is read behind it.
  const Grid<double> c = ad.solve({1.5, 1.0});
  EXPECT_GT(at(ad, c, {5.0, 1.0}), 1.0);
  EXPECT_EQ(c(static_cast<int>(3.2 / g.dx()), static_cast<int>(1.0 / g.dy())), 0.0);
}

// A vent on an obstacle's edge lets gas out as an outlet on the arena's edge
// does. (It used to count as obstacle surface, the only way out was diffusion
// back through the inlet, and the room filled up upstream of the source.)
TEST(AdvectionDiffusion, GasLeavesThroughAVentOnAnObstacleEdge) {
  Map map = read_map(std::string(PLUMEKIT_TEST_DATA) + "/maps-v2/building.json");
  // Only the left inlet and the vent in the outer wall's inner edge.
  map.openings = {map.openings[0], map.openings[2]};
  cfd::FlowOptions flow;
  flow.cell = 0.1;
  flow.nu = 0.05;
  const cfd::WindField wind = cfd::solve(map, flow).wind;
  const cfd::AdvectionDiffusion ad(wind, {0.05, 1000.0});
  const Vec2 source{4.5, 3.0};  // just below the vent (x 4..5 m at y = 3.6 m)
  const Grid<double> c = ad.solve(source);
  // The gas in the room is at most the release rate times the time air takes
  // to cross it (free area over throughput, 1 m^2/s): it leaves as fast as
  // it is released. Without the vent it piled up to ~1e13.
  double mass = 0.0, area = 0.0;
  for (std::size_t k = 0; k < c.values.size(); ++k) {
    EXPECT_TRUE(std::isfinite(c.values[k]) && c.values[k] >= 0.0);
    mass += c.values[k] * 0.01;
    area += wind.solid_cells()[k] ? 0.0 : 0.01;
  }
  EXPECT_GT(mass, 0.0);
  EXPECT_LT(mass, 1000.0 * area / 1.0);
}

// With a first-order decay lambda, the gas that crosses a section downstream
// of the source falls as exp(k x), k = (u - sqrt(u^2 + 4 D lambda)) / (2 D),
// the decaying root of u m' = D m'' - lambda m for the section's total m; and
// the cells' balance holds exactly: what crosses x is the release less what
// left through the inlet and what decayed upstream of x.
TEST(AdvectionDiffusion, DecayTakesGasAtItsRateAndThinsThePlumeDownstream) {
  const cfd::WindField wind = test::uniform_wind(50.0, 10.0, 0.1, 1.0);
  const double u = 1.0, D = 0.1, lambda = 0.1;
  cfd::AdvectionDiffusionOptions o;
  o.diffusivity = D;
  o.release_rate = 1.0;
  o.decay_rate = lambda;
  const cfd::AdvectionDiffusion ad(wind, o);
  const Grid<double> c = ad.solve({2.0, 5.0});
  const GridShape& g = ad.shape();
  const double k = (u - std::sqrt(u * u + 4.0 * D * lambda)) / (2.0 * D);
  const int i10 = static_cast<int>(std::lround(10.0 / g.dx()));
  const int i30 = static_cast<int>(std::lround(30.0 / g.dx()));
  const double ratio = ad.flux_through_column(c, i30) / ad.flux_through_column(c, i10);
  EXPECT_NEAR(ratio, std::exp(k * 20.0), 0.02 * std::exp(k * 20.0));
  double decayed = 0.0;  // lambda times the mass in the columns left of i30
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < i30; ++i)
      decayed += lambda * c(i, j) * g.dx() * g.dy();
  EXPECT_NEAR(ad.flux_through_column(c, i30) - ad.flux_through_column(c, 0), 1.0 - decayed, 1e-6);
  EXPECT_LT(ad.flux_through_column(c, i30), 0.2);
  // Without decay the same section carries the whole release.
  o.decay_rate = 0.0;
  const cfd::AdvectionDiffusion steady(wind, o);
  EXPECT_NEAR(steady.flux_through_column(steady.solve({2.0, 5.0}), i30), 1.0, 1e-6);
}

TEST(AdvectionDiffusion, RejectsNonPositiveDiffusivity) {
  const cfd::WindField w = test::uniform_wind(2.0, 1.0, 0.1, 1.0);
  EXPECT_THROW(cfd::AdvectionDiffusion(w, {0.0, 1.0}), InputError);
  cfd::AdvectionDiffusionOptions o;
  o.decay_rate = -0.1;
  EXPECT_THROW(cfd::AdvectionDiffusion(w, o), OptionError);
}

}  // namespace
}  // namespace plumekit::dataset
