// APF adaptive sampling (seed 000 ch. 8): the field against eqs. 8.1-8.4, the greedy suggestions
// with their repulsion (8.6-8.7), the locality constraints A and B (8.8, §8.2.1), the options, the
// stop rules, and a closed loop on an analytic plume.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "map/map.hpp"
#include "methods/apf_planner.hpp"
#include "methods/gdm_estimates.hpp"
#include "run/gdm_score.hpp"

namespace plumekit::methods {
namespace {

// Hand-made maps over a 10 x 4 m arena at 0.1 m: no confidence, no variance, and a mean bump of
// height 1 and width 0.5 m centred on the cell (50, 20).
methods::GdmMaps bump_maps() {
  const GridShape g = GridShape::with_cell(10.0, 4.0, 0.1);
  methods::GdmMaps m;
  m.mean = m.variance = m.confidence = m.weight = Grid<double>(g, 0.0);
  const Vec2 c = g.centre(50, 20);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double d = norm(g.centre(i, j) - c);
      m.mean(i, j) = std::exp(-d * d / (2.0 * 0.25));
    }
  return m;
}

methods::ApfOptions mean_only(double beta_m, double beta_c) {
  methods::ApfOptions o;
  o.beta_m = beta_m;
  o.beta_v = 0.0;
  o.beta_c = beta_c;
  o.min_step = 0.0;
  return o;
}

TEST(ApfField, FollowsTheClosedForm) {
  const Map arena = default_arena(10.0, 4.0);
  const std::vector<Sample> s{
      {{2.05, 2.05}, 0.0, {}}, {{2.35, 2.05}, 800.0, {}}, {{7.05, 1.05}, 50.0, {}}};
  methods::ApfOptions o;
  const methods::GdmMaps m = methods::kernel_dmv(arena, s, o.gdm);
  const Grid<double> apf = methods::apf_field(m, o);
  double rmax = 0.0, vmax = 0.0;
  for (std::size_t c = 0; c < m.mean.values.size(); ++c)
    rmax = std::max(rmax, m.mean.values[c]), vmax = std::max(vmax, m.variance.values[c]);
  for (const auto& [i, j] : std::vector<std::pair<int, int>>{{21, 20}, {70, 10}, {95, 35}}) {
    const double want =
        0.1 * m.mean(i, j) / rmax + 0.1 * m.variance(i, j) / vmax - 0.8 * m.confidence(i, j);
    EXPECT_NEAR(apf(i, j), want, 1e-12) << i << "," << j;
  }
  // Unnormalised: the raw maps weighted (eq. 8.4 as printed).
  o.normalise = false;
  const Grid<double> raw = methods::apf_field(m, o);
  EXPECT_NEAR(raw(21, 20),
              0.1 * m.mean(21, 20) + 0.1 * m.variance(21, 20) - 0.8 * m.confidence(21, 20), 1e-9);
  // Obstacle cells have no potential.
  Map walled = arena;
  walled.obstacles.push_back({{4.0, 0.0}, {5.0, 0.0}, {5.0, 1.0}, {4.0, 1.0}});
  const Grid<double> blocked = methods::apf_field(methods::kernel_dmv(walled, s, o.gdm), o);
  EXPECT_TRUE(std::isnan(blocked(45, 5)));
  EXPECT_TRUE(std::isfinite(blocked(45, 15)));
}

TEST(ApfSuggestions, RepulsionPushesTheNextPickAway) {
  const Map arena = default_arena(10.0, 4.0);
  const methods::GdmMaps m = bump_maps();
  const methods::ApfOptions o = mean_only(0.2, 0.8);
  const auto s = methods::apf_suggestions(m, arena, o, {1.0, 1.0});
  ASSERT_EQ(s.size(), 10u);
  // The first pick is the bump's peak: 0.2 * 1 - 0.8 * 0.
  EXPECT_EQ(s[0].i, 50);
  EXPECT_EQ(s[0].j, 20);
  EXPECT_NEAR(s[0].value, 0.2, 1e-12);
  // Then every cell has 0.2 bump - 0.8 exp(-d): negative everywhere and rising with d, so the
  // second pick is the cell farthest from the first, the corner (0.05, 0.05).
  EXPECT_EQ(s[1].i, 0);
  EXPECT_EQ(s[1].j, 0);
  const double d = norm(s[1].position - s[0].position);
  EXPECT_NEAR(s[1].value, 0.2 * std::exp(-d * d / 0.5) - 0.8 * std::exp(-d), 1e-12);
  // Later picks spread out: none within 1 m of an earlier one, values never rise.
  for (std::size_t a = 1; a < s.size(); ++a) {
    EXPECT_LE(s[a].value, s[a - 1].value);
    for (std::size_t b = 0; b < a; ++b)
      EXPECT_GT(norm(s[a].position - s[b].position), 1.0) << a << " " << b;
  }
}

TEST(ApfSuggestions, WithoutTheConfidenceTermThereIsNoRepulsion) {
  // Eq. 8.6 scales the repulsion by beta_C: with beta_C = 0 every pick is the same peak cell.
  const auto s = methods::apf_suggestions(bump_maps(), default_arena(10.0, 4.0),
                                          mean_only(1.0, 0.0), {1.0, 1.0});
  ASSERT_EQ(s.size(), 10u);
  for (const methods::ApfSuggestion& x : s) {
    EXPECT_EQ(x.i, 50);
    EXPECT_EQ(x.j, 20);
    EXPECT_DOUBLE_EQ(x.value, 1.0);
  }
}

TEST(ApfSuggestions, SkipCellsWithinTheMinimumStep) {
  methods::ApfOptions o = mean_only(1.0, 0.0);
  o.min_step = 1.0;
  const Vec2 robot{5.05, 2.05};  // on the peak
  const auto s = methods::apf_suggestions(bump_maps(), default_arena(10.0, 4.0), o, robot);
  for (const methods::ApfSuggestion& x : s)
    EXPECT_GE(norm(x.position - robot), 1.0 - 1e-9);
  // The best cell a step away: about exp(-1 / 0.5), the bump on the ring (less, as the cells on
  // the ring itself may fall a hair inside it).
  EXPECT_NEAR(s[0].value, std::exp(-2.0), 0.01);
  EXPECT_LE(s[0].value, std::exp(-2.0) + 1e-9);
  // Maps of another arena are refused.
  EXPECT_THROW(methods::apf_suggestions(bump_maps(), default_arena(12.0, 8.0), o, robot),
               InputError);
}

TEST(ApfLocality, ClosestPicksTheNearestSuggestion) {
  const std::vector<methods::ApfSuggestion> s{
      {{8.0, 2.0}, 0, 0, 0.5}, {{3.0, 2.0}, 0, 0, 0.4}, {{2.0, 3.0}, 0, 0, 0.3}};
  EXPECT_EQ(methods::choose_closest(s, {2.0, 2.0}), 1u);  // 1 m to both: the earlier pick wins
  EXPECT_EQ(methods::choose_closest(s, {2.0, 3.5}), 2u);
  EXPECT_EQ(methods::choose_closest(s, {9.0, 2.0}), 0u);
}

TEST(ApfLocality, CounterCountsTheCellAndItsNeighboursAndResetsOnVisit) {
  const GridShape g = GridShape::with_cell(10.0, 4.0, 0.1);
  methods::SuggestionCounter s(g, 0.5);
  const Vec2 p = g.centre(50, 20);
  s.suggest(p);
  s.suggest(p);
  EXPECT_EQ(s.count(p), 2);
  EXPECT_EQ(s.counts()(55, 20), 2);  // 0.5 m away: a neighbour
  EXPECT_EQ(s.counts()(56, 20), 0);  // 0.6 m
  EXPECT_EQ(s.counts()(54, 23), 2);  // 0.5 m on the diagonal 3-4-5
  EXPECT_EQ(s.counts()(54, 24), 0);  // 0.566 m
  int cells = 0;
  for (int c : s.counts().values)
    cells += c > 0;
  EXPECT_EQ(cells, 81);  // lattice points with a^2 + b^2 <= 25
  s.suggest(g.centre(60, 20));
  EXPECT_EQ(s.counts()(55, 20), 3);  // in both discs
  // Visiting resets the cells within the radius of where the robot stood.
  s.visit(p);
  EXPECT_EQ(s.count(p), 0);
  EXPECT_EQ(s.counts()(55, 20), 0);
  EXPECT_EQ(s.counts()(56, 20), 1);  // 0.6 m from the visit, suggested once from (60, 20)
  EXPECT_EQ(s.count(g.centre(60, 20)), 1);
}

TEST(ApfLocality, MostSuggestedMaximisesCountOverDistance) {
  const GridShape g = GridShape::with_cell(10.0, 4.0, 0.1);
  methods::SuggestionCounter s(g, 0.0);
  const Vec2 robot = g.centre(10, 20), far = g.centre(50, 20), near = g.centre(20, 20);
  for (int k = 0; k < 5; ++k)
    s.suggest(far);  // 4 m, S = 5: 1.25
  s.suggest(near);   // 1 m, S = 1: 1
  const std::vector<methods::ApfSuggestion> list{{near, 20, 20, 0.9}, {far, 50, 20, 0.8}};
  EXPECT_EQ(methods::choose_most_suggested(list, s, robot), 1u);
  s.suggest(near);  // S = 2 at 1 m: 2 > 1.25
  EXPECT_EQ(methods::choose_most_suggested(list, s, robot), 0u);
  // Equal ratios: the earlier (higher-APF) pick.
  for (int k = 0; k < 3; ++k)
    s.suggest(far);  // 8 / 4 = 2
  EXPECT_EQ(methods::choose_most_suggested(list, s, robot), 0u);
}

TEST(ApfOptions, ValidationNamesTheField) {
  const auto field_of = [](const methods::ApfOptions& o) -> std::string {
    try {
      o.validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  methods::ApfOptions o;
  EXPECT_EQ(field_of(o), "");
  EXPECT_NEAR(o.beta_m + o.beta_v + o.beta_c, 1.0, 1e-12);
  o.beta_c = 0.7;  // sums to 0.9
  EXPECT_EQ(field_of(o), "apf.beta_c");
  o = methods::ApfOptions{};
  o.beta_m = -0.1;
  EXPECT_EQ(field_of(o), "apf.beta_m");
  o = methods::ApfOptions{};
  o.suggestions = 0;
  EXPECT_EQ(field_of(o), "apf.suggestions");
  o = methods::ApfOptions{};
  o.charge = 1.0;
  EXPECT_EQ(field_of(o), "apf.charge");
  o = methods::ApfOptions{};
  o.sigma_d = 0.0;
  EXPECT_EQ(field_of(o), "apf.sigma_d");
  o = methods::ApfOptions{};
  o.confidence_stop = 1.0;
  EXPECT_EQ(field_of(o), "apf.confidence_stop");
  o = methods::ApfOptions{};
  o.estimator = "peak";
  EXPECT_EQ(field_of(o), "apf.estimator");
  o = methods::ApfOptions{};
  o.gdm.cell = 0.0;
  EXPECT_EQ(field_of(o), "gdm.cell");
  EXPECT_EQ(methods::parse_locality("b"), Locality::MostSuggested);
  EXPECT_EQ(methods::parse_locality("closest"), Locality::Closest);
  try {
    methods::parse_locality("c");
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "apf.locality");
  }
  const Map arena = default_arena();
  o = methods::ApfOptions{};
  o.beta_v = 0.5;
  EXPECT_THROW(methods::ApfMapping(methods::SearchArea{&arena}, o), OptionError);
}

methods::Observation at(Vec2 p, double gas) {
  methods::Observation o;
  o.position = p;
  o.gas = gas;
  o.wind = {1.0, 0.0};
  return o;
}

TEST(ApfMapping, StopsWhenConfidentEverywhereOrOutOfSteps) {
  const Map arena = default_arena(2.0, 2.0);
  methods::ApfOptions o;
  o.confidence_stop = 0.5;
  methods::ApfMapping m(methods::SearchArea{&arena}, o);
  EXPECT_EQ(m.name(), "apf");
  EXPECT_FALSE(m.estimate());
  EXPECT_EQ(m.stopped_by(), "");
  // A 0.5 m lattice: each corner cell reaches alpha > 0.5 only once the lattice is complete.
  int n = 0;
  for (double y : {0.25, 0.75, 1.25, 1.75})
    for (double x : {0.25, 0.75, 1.25, 1.75}) {
      EXPECT_EQ(m.stopped_by(), "") << n;
      m.observe(at({x, y}, 10.0));
      ++n;
    }
  EXPECT_EQ(m.stopped_by(), "confident");
  double lowest = 1.0;
  for (double a : m.maps().confidence.values)
    lowest = std::min(lowest, a);
  EXPECT_GT(lowest, 0.5);
  // 0 disables that stop; max_steps still ends the run.
  o.confidence_stop = 0.0;
  o.max_steps = 3;
  methods::ApfMapping quick(methods::SearchArea{&arena}, o);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(quick.stopped_by(), "");
    quick.observe(at({1.0, 1.0}, 0.0));
  }
  EXPECT_EQ(quick.stopped_by(), "max_samples");
  EXPECT_THROW(quick.observe(at({std::nan(""), 1.0}, 0.0)), InputError);
}

TEST(ApfMapping, GoesToTheSuggestionItsLocalityPicks) {
  const Map arena = default_arena(10.0, 4.0);
  for (Locality l : {Locality::None, Locality::Closest, Locality::MostSuggested}) {
    methods::ApfOptions o;
    o.locality = l;
    auto m = methods::make_apf_mapping(methods::SearchArea{&arena}, o);
    auto* apf = dynamic_cast<methods::ApfMapping*>(m.get());
    ASSERT_NE(apf, nullptr);
    const Vec2 robot{2.0, 2.0};
    m->observe(at(robot, 100.0));
    const methods::Move move = m->next(robot);
    ASSERT_EQ(apf->suggestions().size(), 10u);
    const auto& s = apf->suggestions();
    EXPECT_EQ(move.goal, s[apf->chosen()].position);
    EXPECT_GE(norm(move.goal - robot), o.min_step - 1e-9);
    const std::size_t want = l == Locality::None ? 0u
                             : l == Locality::Closest
                                 ? methods::choose_closest(s, robot)
                                 : methods::choose_most_suggested(s, apf->counter(), robot);
    EXPECT_EQ(apf->chosen(), want) << to_string(l);
    ASSERT_TRUE(m->estimate());
  }
}

// The steady 2-D advection-diffusion plume of a point source at (2, 4) in a 1 m/s wind along +x
// (diffusivity 0.05 m^2/s, 1000 units/s): c = Q / (2 pi D) exp(u dx / 2D) K0(u r / 2D).
double analytic_plume(Vec2 p) {
  const double q = 1000.0, d = 0.05, u = 1.0;
  const Vec2 s{2.0, 4.0};
  const double r = std::max(norm(p - s), 0.1);
  return q / (2.0 * kPi * d) * std::exp(u * (p.x - s.x) / (2.0 * d)) *
         std::cyl_bessel_k(0.0, u * r / (2.0 * d));
}

struct LoopResult {
  std::vector<double> kl;  // of the mean map against the analytic plume, after each stop
  double distance = 0.0;   // m flown between stops
  Vec2 peak_mean;          // seed 000 §8.5.2.1's estimate A
};

// Drives ApfMapping for `stops` stops in an open 12 x 8 m arena (the seed's section of the
// tunnel), the robot jumping to each goal and reading the analytic plume there.
LoopResult closed_loop(Vec2 start, Locality locality, int stops) {
  const Map arena = default_arena(12.0, 8.0);
  methods::ApfOptions o;  // (0.1, 0.1, 0.8), n_sp 10, DM+V/W
  o.locality = locality;
  methods::ApfMapping m(methods::SearchArea{&arena}, o);
  LoopResult r;
  Grid<double> truth;
  Vec2 robot = start;
  for (int stop = 0; stop < stops && !m.stopped(); ++stop) {
    m.observe(at(robot, analytic_plume(robot)));
    if (truth.values.empty()) {
      truth = m.maps().mean;
      for (int j = 0; j < truth.shape.ny; ++j)
        for (int i = 0; i < truth.shape.nx; ++i)
          truth(i, j) = analytic_plume(truth.shape.centre(i, j));
    }
    r.kl.push_back(run::score_mean(m.maps().mean, truth).kl_distance);
    const Vec2 goal = m.next(robot).goal;
    EXPECT_GE(norm(goal - robot), o.min_step - 1e-9);
    r.distance += norm(goal - robot);
    robot = goal;
  }
  r.peak_mean = methods::source_estimates(m.maps())[0].position;
  return r;
}

TEST(ApfMapping, ClosedLoopMapsTheAnalyticPlume) {
  // What SPPAM A does in 60 stops from the centres of the arena's quarters: it finds the plume
  // and the KL distance of its mean map to the truth falls from stop 10 on (to 2-53 % of it);
  // the peak of the mean lands on the best reading taken, on the plume's axis, 0.9-2.5 m from the
  // source here (within 1.5 m from only about 40 % of 25 starts tried: 60 stops, most of them
  // spent exploring with beta_C = 0.8, do not reach the source's cell). The paths hinge on
  // round-off (ties in the greedy picks), so the bounds leave room.
  const Vec2 source{2.0, 4.0};
  double ratio = 0.0, error = 0.0;
  for (Vec2 start : {Vec2{3.0, 2.0}, Vec2{3.0, 6.0}, Vec2{9.0, 2.0}, Vec2{9.0, 6.0}}) {
    const LoopResult r = closed_loop(start, Locality::Closest, 60);
    ASSERT_EQ(r.kl.size(), 60u);
    const double miss = norm(r.peak_mean - source);
    std::printf("APF from (%g, %g): KL %.2f at stop 10, %.2f at 60; peak mean %.2f m off\n",
                start.x, start.y, r.kl[9], r.kl.back(), miss);
    EXPECT_LT(r.kl.back(), 0.75 * r.kl[9]) << to_string(start);
    EXPECT_LT(miss, 3.5) << to_string(start);
    ratio += r.kl.back() / r.kl[9] / 4.0;
    error += miss / 4.0;
  }
  EXPECT_LT(ratio, 0.4);
  EXPECT_LT(error, 2.5);
}

TEST(ApfMapping, LocalityConstraintsShortenTheFlight) {
  // Seed 000 Tables 8.1-8.2's order: SPPAM A flies least, then B, then adaptive SP.
  const Vec2 start{9.0, 2.0};
  const double none = closed_loop(start, Locality::None, 60).distance;
  const double a = closed_loop(start, Locality::Closest, 60).distance;
  const double b = closed_loop(start, Locality::MostSuggested, 60).distance;
  std::printf("APF flight over 60 stops: none %.0f m, A %.0f m, B %.0f m\n", none, a, b);
  EXPECT_LT(a, b);
  EXPECT_LT(b, none);
}

}  // namespace
}  // namespace plumekit::methods
