#include "methods/particle_filter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "core/random.hpp"
#include "map/map.hpp"
#include "methods/pf_method.hpp"
#include "methods/wind_statistics.hpp"

namespace plumekit::methods {
namespace {

// The seeds' wind tunnel: an open 32 x 8 m arena, wind along +x (upwind -x).
class ParticleFilterTest : public ::testing::Test {
 protected:
  Map map = default_arena(32.0, 8.0);
  SearchArea area{&map};
  ParticleFilterOptions options;
};

const Vec2 kWind{0.5, 0.0};

Observation stop(Vec2 p, double gas, Vec2 wind = kWind, double s0 = 0.075) {
  Observation o;
  o.position = p;
  o.gas = gas;
  o.wind = wind;
  o.wind_variance = s0;
  return o;
}

// `actual` equals `expected` as a cyclic vertex sequence (same orientation), within `tol`.
void expect_polygon(const Polygon& actual, const Polygon& expected, double tol = 1e-9) {
  ASSERT_EQ(actual.size(), expected.size());
  std::size_t start = 0;
  for (std::size_t i = 1; i < actual.size(); ++i) {
    if (norm(actual[i] - expected[0]) < norm(actual[start] - expected[0])) start = i;
  }
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const Vec2 a = actual[(start + i) % actual.size()];
    EXPECT_NEAR(a.x, expected[i].x, tol) << "vertex " << i << ": " << to_string(a);
    EXPECT_NEAR(a.y, expected[i].y, tol) << "vertex " << i << ": " << to_string(a);
  }
}

TEST(AdaptiveThreshold, FollowsTheEmaAndTheDetectionLimit) {
  AdaptiveThreshold t(50.0, 0.5);
  EXPECT_FALSE(t.update(200.0));  // z_0 = 0, c̄_0 = c_0
  EXPECT_DOUBLE_EQ(t.average(), 200.0);
  EXPECT_FALSE(t.update(100.0));  // 100 <= 200; c̄ = 150
  EXPECT_DOUBLE_EQ(t.average(), 150.0);
  EXPECT_TRUE(t.update(160.0));  // c̄ = 155
  EXPECT_DOUBLE_EQ(t.average(), 155.0);
  EXPECT_FALSE(t.update(49.0));  // below th_c: 0; c̄ = 77.5
  EXPECT_DOUBLE_EQ(t.average(), 77.5);
  EXPECT_FALSE(t.update(0.0));  // c̄ = 38.75
  EXPECT_TRUE(t.update(50.0));  // at th_c counts; 50 > 38.75; c̄ = 44.375
  EXPECT_DOUBLE_EQ(t.average(), 44.375);
  EXPECT_EQ(t.readings(), 6);
  AdaptiveThreshold zero(50.0, 0.5);
  EXPECT_FALSE(zero.update(0.0));
  EXPECT_FALSE(zero.update(0.0));  // 0 > 0 is no detection
  EXPECT_TRUE(zero.update(60.0));
}

// Robot (20, 4), wind +x, S0 = 0.25: m0 = (20.5, 4), r1 = (20, 4.5) (right of upwind -x is +y),
// l1 = (20, 3.5); the rays leave at 22.5 deg off -x and meet y = 8 and y = 0 at
// x = 20 - 3.5 / tan(22.5 deg); the corners between them, counter-clockwise, are (0, 8), (0, 0).
TEST_F(ParticleFilterTest, EnvelopeVerticesMatchTheHandComputedOnes) {
  const PatchPathEnvelope e = make_envelope({20.0, 4.0}, kWind, 0.25, 32.0, 8.0, 1.0);
  const double xi = 20.0 - 3.5 / std::tan(radians(22.5));
  expect_polygon(
      e.polygon,
      {{20.5, 4.0}, {20.0, 4.5}, {xi, 8.0}, {0.0, 8.0}, {0.0, 0.0}, {xi, 0.0}, {20.0, 3.5}});
  EXPECT_DOUBLE_EQ(e.opening_deg, 45.0);
  EXPECT_GT(signed_area(e.polygon), 0.0);  // counter-clockwise
  EXPECT_NEAR(e.up.x, -1.0, 1e-15);
  EXPECT_NEAR(e.right_ray.y, std::sin(radians(22.5)), 1e-15);
  EXPECT_NEAR(e.left_ray.y, -std::sin(radians(22.5)), 1e-15);
}

TEST_F(ParticleFilterTest, EnvelopeIsClippedAtTheDownwindWall) {
  // m0 = (32.3, 4) lies outside: the triangle is cut at x = 32; S0 = 0 gives parallel rays and
  // the floored opening.
  const PatchPathEnvelope e = make_envelope({31.8, 4.0}, kWind, 0.0, 32.0, 8.0, 1.0);
  expect_polygon(e.polygon,
                 {{32.0, 4.3}, {31.8, 4.5}, {0.0, 4.5}, {0.0, 3.5}, {31.8, 3.5}, {32.0, 3.7}});
  EXPECT_DOUBLE_EQ(e.opening_deg, 1.0);
}

TEST_F(ParticleFilterTest, EnvelopeOfAnUnsteadyWindIsTheUpwindHalf) {
  // Wind toward -y (upwind +y), S0 = 1: the rays run across the wind along y = 4.
  const PatchPathEnvelope e = make_envelope({10.0, 4.0}, {0.0, -2.0}, 1.0, 32.0, 8.0, 1.0);
  expect_polygon(
      e.polygon,
      {{10.0, 3.5}, {10.5, 4.0}, {32.0, 4.0}, {32.0, 8.0}, {0.0, 8.0}, {0.0, 4.0}, {9.5, 4.0}});
  EXPECT_DOUBLE_EQ(e.opening_deg, 180.0);
  EXPECT_TRUE(e.upwind_of_s({3.0, 3.6}));  // s is y = 3.5
  EXPECT_FALSE(e.upwind_of_s({3.0, 3.4}));
}

TEST_F(ParticleFilterTest, EnvelopeContainsAgreesWithItsPolygon) {
  std::mt19937_64 rng(5);
  int checked = 0, inside = 0;
  for (int k = 0; k < 40; ++k) {
    const Vec2 p{uniform(rng, -1.0, 33.0), uniform(rng, -1.0, 9.0)};
    const Vec2 wind = heading(uniform(rng, -kPi, kPi));
    const PatchPathEnvelope e = make_envelope(p, wind, uniform01(rng), 32.0, 8.0, 1.0);
    for (int i = 0; i < 500; ++i) {
      const Vec2 q{uniform(rng, 0.0, 32.0), uniform(rng, 0.0, 8.0)};
      double edge = 1e300;
      for (std::size_t v = 0; v < e.polygon.size(); ++v)
        edge = std::min(
            edge, distance_to_segment(q, e.polygon[v], e.polygon[(v + 1) % e.polygon.size()]));
      if (edge < 1e-6) continue;
      ++checked;
      inside += e.contains(q);
      EXPECT_EQ(e.contains(q), covers(e.polygon, q)) << to_string(p) << " " << to_string(q);
      if (e.contains(q)) {
        EXPECT_TRUE(e.upwind_of_s(q));  // C_t lies in S_t
      }
    }
  }
  EXPECT_GT(checked, 19000);
  EXPECT_GT(inside, 1000);
}

TEST(WeightFactor, SixCasesOfEquationSix) {
  const double a = 0.4, b = 0.9, r = 36.0 / 180.0;
  EXPECT_DOUBLE_EQ(weight_factor(ParticleClass::Inside, true, a, b, 36.0), 1.0);
  EXPECT_DOUBLE_EQ(weight_factor(ParticleClass::Upwind, true, a, b, 36.0), a * r);
  EXPECT_DOUBLE_EQ(weight_factor(ParticleClass::Downwind, true, a, b, 36.0), a * a * r);
  EXPECT_DOUBLE_EQ(weight_factor(ParticleClass::Inside, false, a, b, 36.0), b * b * r);
  EXPECT_DOUBLE_EQ(weight_factor(ParticleClass::Upwind, false, a, b, 36.0), b);
  EXPECT_DOUBLE_EQ(weight_factor(ParticleClass::Downwind, false, a, b, 36.0), 1.0);
}

// One particle in each class, for z = 1 and z = 0: the normalised closed forms.
TEST_F(ParticleFilterTest, WeightUpdateOfEachClassMatchesItsClosedForm) {
  const PatchPathEnvelope e = make_envelope({20.0, 4.0}, kWind, 0.1, 32.0, 8.0, 1.0);
  const std::vector<Vec2> p{{10.0, 4.0}, {15.0, 7.0}, {25.0, 4.0}};
  EXPECT_EQ(classify(e, p[0]), ParticleClass::Inside);
  EXPECT_EQ(classify(e, p[1]), ParticleClass::Upwind);
  EXPECT_EQ(classify(e, p[2]), ParticleClass::Downwind);
  EXPECT_EQ(classify(e, {20.3, 4.0}), ParticleClass::Inside);    // in the triangle
  EXPECT_EQ(classify(e, {20.3, 4.45}), ParticleClass::Upwind);   // beside it, upwind of s
  EXPECT_EQ(classify(e, {20.6, 4.0}), ParticleClass::Downwind);  // just downwind of m0
  options.resample_fraction = 0.0;  // never resample: the weights are the update's
  const double a = options.alpha, b = options.beta, r = 18.0 / 180.0;
  const std::vector<double> w0{0.2, 0.3, 0.5};
  for (bool z : {true, false}) {
    ParticleFilter pf(area, options, 3);
    pf.set_particles(p, w0);
    const FilterStep& s = pf.update(e, z);
    EXPECT_FALSE(s.resampled);
    std::vector<double> f =
        z ? std::vector<double>{1.0, a * r, a * a * r} : std::vector<double>{b * b * r, b, 1.0};
    const double sum = w0[0] * f[0] + w0[1] * f[1] + w0[2] * f[2];
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(pf.weights()[i], w0[i] * f[i] / sum, 1e-15) << z;
  }
}

TEST(EffectiveSampleSize, IsOneOverTheSumOfSquares) {
  EXPECT_DOUBLE_EQ(effective_sample_size(std::vector<double>(4, 0.25)), 4.0);
  EXPECT_DOUBLE_EQ((effective_sample_size(std::vector<double>{1.0, 0.0, 0.0, 0.0})), 1.0);
  // Not {0.5, 0.5, 0.0, 0.0}: GCC 12.2 with AVX-512 (-march=native here) stores that list as
  // four 0.5s.
  EXPECT_DOUBLE_EQ((effective_sample_size(std::vector<double>{0.5, 0.0, 0.5, 0.0})), 2.0);
}

// k of 10 particles inside the PPE, the rest downwind; a non-detection scales the inside ones by
// beta^2 theta_C / 180: resampling happens exactly when N_eff < gamma N.
TEST_F(ParticleFilterTest, ResamplesExactlyWhenTheEffectiveSizeDropsBelowGammaN) {
  const PatchPathEnvelope e = make_envelope({20.0, 4.0}, kWind, 0.1, 32.0, 8.0, 1.0);
  const double f = options.beta * options.beta * 0.1;
  bool seen[2] = {false, false};
  for (int k = 0; k <= 10; ++k) {
    std::vector<Vec2> p;
    for (int i = 0; i < 10; ++i)
      p.push_back(i < k ? Vec2{10.0, 4.0} : Vec2{25.0, 4.0});
    ParticleFilter pf(area, options, 11);
    pf.set_particles(p, std::vector<double>(10, 0.1));
    const double sum = k * f + (10 - k), sq = k * f * f + (10 - k);
    const double expected = sum * sum / sq;
    const FilterStep& s = pf.update(e, false);
    EXPECT_NEAR(s.effective_size, expected, 1e-9) << k;
    EXPECT_EQ(s.resampled, expected < 0.5 * 10) << k;
    seen[s.resampled] = true;
    if (s.resampled) {
      for (double w : pf.weights())
        EXPECT_DOUBLE_EQ(w, 0.1);
    }
  }
  EXPECT_TRUE(seen[0] && seen[1]);
}

TEST(NormalizeWeights, ResetsAZeroOrNonFiniteSumToUniform) {
  std::vector<double> w{0.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(normalize_weights(w));
  for (double x : w)
    EXPECT_DOUBLE_EQ(x, 0.25);
  w = {1.0, std::numeric_limits<double>::infinity()};
  EXPECT_FALSE(normalize_weights(w));
  EXPECT_DOUBLE_EQ(w[0], 0.5);
  w = {1.0, 3.0};
  EXPECT_TRUE(normalize_weights(w));
  EXPECT_DOUBLE_EQ(w[1], 0.75);
}

TEST_F(ParticleFilterTest, ZeroWeightsAreResetByTheUpdate) {
  ParticleFilter pf(area, options, 2);
  const std::vector<Vec2> p = pf.particles();
  pf.set_particles(p, std::vector<double>(p.size(), 0.0));
  const FilterStep& s = pf.update(stop({20.0, 4.0}, 0.0));
  EXPECT_TRUE(s.weights_reset);
  EXPECT_FALSE(s.resampled);
  for (double w : pf.weights())
    EXPECT_DOUBLE_EQ(w, 1.0 / 1000);
}

// delta = 1 and gamma = 1: every particle is injected, from F ∩ S_t on a detection and from
// F \ C_t otherwise, and covers its whole region.
TEST_F(ParticleFilterTest, InjectionDrawsFromItsRegion) {
  options.injection = 1.0;
  options.resample_fraction = 1.0;
  options.particles = 400;
  const PatchPathEnvelope e = make_envelope({20.0, 4.0}, kWind, 0.2, 32.0, 8.0, 1.0);
  for (bool z : {true, false}) {
    ParticleFilter pf(area, options, 4);
    std::vector<double> w(400);
    for (int i = 0; i < 400; ++i)
      w[i] = i + 1.0;  // not uniform: N_eff < N
    pf.set_particles(pf.particles(), w);
    ASSERT_TRUE(pf.update(e, z).resampled);
    int in = 0, up = 0, down = 0;
    for (Vec2 q : pf.particles()) {
      const ParticleClass c = classify(e, q);
      in += c == ParticleClass::Inside;
      up += c == ParticleClass::Upwind;
      down += c == ParticleClass::Downwind;
      EXPECT_TRUE(area.is_free(q));
    }
    if (z) {
      EXPECT_EQ(down, 0);
      EXPECT_GT(in, 20);
      EXPECT_GT(up, 20);
    } else {
      EXPECT_EQ(in, 0);
      EXPECT_GT(up, 20);
      EXPECT_GT(down, 20);
    }
  }
}

// delta = 0: resampled particles lie near their parents (jitter sd sqrt(0.1) m), in the area,
// and never in an obstacle.
TEST_F(ParticleFilterTest, ResampledParticlesAreJitteredOffObstacles) {
  map.obstacles.push_back({{10.0, 2.0}, {14.0, 2.0}, {14.0, 6.0}, {10.0, 6.0}});
  options.injection = 0.0;
  options.resample_fraction = 1.0;
  ParticleFilter pf(area, options, 6);
  for (Vec2 q : pf.particles())
    EXPECT_TRUE(area.is_free(q));
  // Half the particles hug the obstacle's left side and a corner of the area, half elsewhere.
  std::vector<Vec2> p;
  for (int i = 0; i < 1000; ++i)
    p.push_back(i % 2 ? Vec2{9.9, 4.0} : Vec2{0.0, 0.0});
  std::vector<double> w(1000, 1.0);
  w[0] = 2.0;
  pf.set_particles(p, w);
  ASSERT_TRUE(pf.update(make_envelope({20.0, 4.0}, kWind, 0.2, 32.0, 8.0, 1.0), false).resampled);
  int near_obstacle = 0;
  for (Vec2 q : pf.particles()) {
    EXPECT_TRUE(area.is_free(q)) << to_string(q);
    EXPECT_TRUE(norm(q - Vec2{9.9, 4.0}) < 2.0 || norm(q) < 2.0) << to_string(q);
    near_obstacle += norm(q - Vec2{9.9, 4.0}) < 2.0;
  }
  EXPECT_GT(near_obstacle, 300);
  EXPECT_LT(near_obstacle, 700);
}

TEST(CarpenterResample, DrawsInProportionToTheWeights) {
  std::mt19937_64 rng(9);
  std::vector<int> idx = carpenter_resample({0.0, 0.5, 0.0, 0.5}, 1000, rng);
  ASSERT_EQ(idx.size(), 1000u);
  EXPECT_TRUE(std::is_sorted(idx.begin(), idx.end()));
  const long ones = std::count(idx.begin(), idx.end(), 1);
  EXPECT_EQ(ones + std::count(idx.begin(), idx.end(), 3), 1000);
  EXPECT_NEAR(ones / 1000.0, 0.5, 0.06);
  idx = carpenter_resample({0.1, 0.2, 0.7}, 30000, rng);
  EXPECT_NEAR(std::count(idx.begin(), idx.end(), 0) / 30000.0, 0.1, 0.01);
  EXPECT_NEAR(std::count(idx.begin(), idx.end(), 2) / 30000.0, 0.7, 0.01);
  EXPECT_EQ(carpenter_resample({0.0, 0.0, 2.0}, 5, rng), std::vector<int>(5, 2));  // unnormalised
}

NeighbourCount brute_force_neighbours(const std::vector<Vec2>& p, const std::vector<double>& w,
                                      double r) {
  NeighbourCount best;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    int n = 0;
    for (int j = 0; j < static_cast<int>(p.size()); ++j) {
      const Vec2 d = p[j] - p[i];
      n += j != i && d.x * d.x + d.y * d.y <= r * r;
    }
    if (best.index < 0 || n > best.neighbours || (n == best.neighbours && w[i] > w[best.index]))
      best = {i, n};
  }
  return best;
}

TEST(MaximumNeighbours, PicksTheDensestParticle) {
  std::vector<Vec2> p{{1.0, 1.0}, {5.0, 5.0}, {5.2, 5.1}, {4.9, 4.8},
                      {5.1, 4.7}, {9.0, 1.0}, {5.6, 5.0}};
  std::vector<double> w(p.size(), 1.0);
  const NeighbourCount m = maximum_neighbours(p, w, 0.5);
  EXPECT_EQ(m.index, 2);  // (5.2, 5.1) reaches the other four; (5, 5) misses (5.6, 5)
  EXPECT_EQ(m.neighbours, 4);
  // Ties go to the larger weight.
  std::vector<Vec2> pair{{0.0, 0.0}, {0.3, 0.0}};
  EXPECT_EQ(maximum_neighbours(pair, {1.0, 2.0}, 0.5).index, 1);
  EXPECT_EQ(maximum_neighbours(pair, {1.0, 1.0}, 0.5).index, 0);
}

TEST(MaximumNeighbours, AgreesWithBruteForceOnRandomParticles) {
  std::mt19937_64 rng(21);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec2> p;
    std::vector<double> w;
    for (int i = 0; i < 500; ++i) {
      // Rounded coordinates make exact ties and equal x values common.
      p.push_back({std::round(uniform(rng, 0.0, 6.0) * 10.0) / 10.0,
                   std::round(uniform(rng, 0.0, 4.0) * 10.0) / 10.0});
      w.push_back(std::round(uniform01(rng) * 4.0));
    }
    const NeighbourCount fast = maximum_neighbours(p, w, 0.5);
    const NeighbourCount slow = brute_force_neighbours(p, w, 0.5);
    EXPECT_EQ(fast.index, slow.index);
    EXPECT_EQ(fast.neighbours, slow.neighbours);
  }
}

TEST_F(ParticleFilterTest, SameSeedGivesTheSameParticlesBitForBit) {
  auto run = [&](std::uint64_t seed) {
    ParticleFilter pf(area, options, seed);
    for (int i = 0; i < 40; ++i) {
      const Vec2 p{31.0 - 0.5 * i, 4.0 + std::sin(i)};
      pf.update(stop(p, i % 3 == 0 ? 400.0 + 10 * i : 0.0, kWind, 0.05));
    }
    return std::make_pair(pf.particles(), pf.weights());
  };
  const auto a = run(17), b = run(17), c = run(18);
  ASSERT_EQ(a.first.size(), b.first.size());
  for (std::size_t i = 0; i < a.first.size(); ++i) {
    EXPECT_EQ(a.first[i], b.first[i]);
    EXPECT_EQ(a.second[i], b.second[i]);
  }
  EXPECT_FALSE(a.first[0] == c.first[0] && a.first[1] == c.first[1]);
  // Initialisation: uniform over the area, weights 1/N.
  ParticleFilter pf(area, options, 17);
  double mx = 0.0;
  for (Vec2 q : pf.particles()) {
    EXPECT_TRUE(area.is_free(q));
    mx += q.x / 1000.0;
  }
  EXPECT_NEAR(mx, 16.0, 1.0);
  EXPECT_DOUBLE_EQ(pf.weights()[0], 1.0 / 1000);
}

TEST_F(ParticleFilterTest, OptionsAreValidatedByField) {
  auto field_of = [](ParticleFilterOptions o) -> std::string {
    try {
      o.validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  EXPECT_EQ(field_of(options), "");
  ParticleFilterOptions o;
  o.particles = 0;
  EXPECT_EQ(field_of(o), "pf.particles");
  o = {};
  o.alpha = 0.0;
  EXPECT_EQ(field_of(o), "pf.alpha");
  o = {};
  o.beta = 1.5;
  EXPECT_EQ(field_of(o), "pf.beta");
  o = {};
  o.resample_fraction = -0.1;
  EXPECT_EQ(field_of(o), "pf.resample_fraction");
  o = {};
  o.injection = 2.0;
  EXPECT_EQ(field_of(o), "pf.injection");
  o = {};
  o.jitter_variance = std::nan("");
  EXPECT_EQ(field_of(o), "pf.jitter_variance");
  o = {};
  o.mne_radius = 0.0;
  EXPECT_EQ(field_of(o), "pf.mne_radius");
  o = {};
  o.detection_limit = -1.0;
  EXPECT_EQ(field_of(o), "pf.detection_limit");
  o = {};
  o.ema_lambda = 1.1;
  EXPECT_EQ(field_of(o), "pf.ema_lambda");
  o = {};
  o.min_opening_deg = 0.0;
  EXPECT_EQ(field_of(o), "pf.min_opening_deg");
  o = {};
  o.alpha = 2.0;
  EXPECT_THROW(ParticleFilter(area, o, 1), OptionError);
  PfMethodOptions m;
  m.declare_iterations = -1;
  EXPECT_THROW(m.validate(), OptionError);
  SweepPatternOptions s;
  s.step = 0.0;
  EXPECT_THROW(s.validate(), OptionError);
  EXPECT_DOUBLE_EQ(pf_options_for(PfExploration::Gradient).alpha, 0.2);
  EXPECT_DOUBLE_EQ(pf_options_for(PfExploration::Gradient).beta, 0.8);
  EXPECT_DOUBLE_EQ(pf_options_for(PfExploration::Sweep).beta, 0.9);
}

TEST_F(ParticleFilterTest, NonFiniteObservationsAreInputErrors) {
  ParticleFilter pf(area, options, 1);
  const double nan = std::nan("");
  EXPECT_THROW(pf.update(stop({nan, 1.0}, 0.0)), InputError);
  EXPECT_THROW(pf.update(stop({1.0, 1.0}, nan)), InputError);
  EXPECT_THROW(pf.update(stop({1.0, 1.0}, 0.0, {nan, 0.0})), InputError);
  EXPECT_THROW(pf.update(stop({1.0, 1.0}, 0.0, kWind, nan)), InputError);
  auto method = make_pf_sweep(area);
  EXPECT_THROW(method->observe(stop({1.0, std::numeric_limits<double>::infinity()}, 0.0)),
               InputError);
  PredefinedSweep sweep(area);
  EXPECT_THROW(sweep.observe(stop({1.0, 1.0}, nan)), InputError);
}

TEST_F(ParticleFilterTest, CalmStopUpdatesOnlyTheThreshold) {
  ParticleFilter pf(area, options, 1);
  const std::vector<double> w = pf.weights();
  const FilterStep& s = pf.update(stop({20.0, 4.0}, 300.0, {0.0, 0.0}));
  EXPECT_FALSE(s.envelope.has_value());
  EXPECT_EQ(pf.weights(), w);
  EXPECT_DOUBLE_EQ(pf.threshold().average(), 300.0);
  EXPECT_EQ(pf.iterations(), 1);
}

TEST_F(ParticleFilterTest, SweepPatternIsABoustrophedonMovingUpwind) {
  const std::vector<Vec2> p = sweep_pattern(area, {32.0, 0.0}, kWind, 1.0);
  ASSERT_EQ(p.size(), 33u * 9u);
  EXPECT_EQ(p[0], (Vec2{32.0, 0.0}));
  EXPECT_EQ(p[8], (Vec2{32.0, 8.0}));
  EXPECT_EQ(p[9], (Vec2{31.0, 8.0}));
  EXPECT_EQ(p[17], (Vec2{31.0, 0.0}));
  EXPECT_EQ(p.back(), (Vec2{0.0, 8.0}));
  // A wind toward +y sweeps lines along x from y = 8 down to y = 0.
  const std::vector<Vec2> q = sweep_pattern(area, {0.0, 8.0}, {0.0, 1.0}, 2.0);
  ASSERT_EQ(q.size(), 5u * 17u);
  EXPECT_NEAR(q[0].x, 0.0, 1e-12);
  EXPECT_NEAR(q[0].y, 8.0, 1e-12);
  EXPECT_NEAR(q[16].x, 32.0, 1e-12);
  EXPECT_NEAR(q.back().y, 0.0, 1e-12);
  // Stops in obstacles are left out.
  map.obstacles.push_back({{10.5, 2.5}, {13.5, 2.5}, {13.5, 5.5}, {10.5, 5.5}});
  const std::vector<Vec2> r = sweep_pattern(area, {32.0, 0.0}, kWind, 1.0);
  EXPECT_EQ(r.size(), 33u * 9u - 9u);
  for (Vec2 s : r)
    EXPECT_TRUE(area.is_free(s));
}

TEST_F(ParticleFilterTest, PredefinedSweepEndsWhenSwept) {
  Map small = default_arena(3.0, 2.0);
  SearchArea a{&small};
  PredefinedSweep sweep(a);
  Vec2 robot{3.0, 0.0};
  std::vector<Vec2> visited;
  while (true) {
    sweep.observe(stop(robot, 0.0));
    if (sweep.stopped()) break;
    robot = sweep.next(robot).goal;
    visited.push_back(robot);
  }
  EXPECT_EQ(sweep.stopped_by(), "swept");
  EXPECT_EQ(visited.size(), 11u);  // 12 stops less the start
  EXPECT_EQ(visited.front(), (Vec2{3.0, 1.0}));
  EXPECT_EQ(visited.back(), (Vec2{0.0, 0.0}));
  SweepPatternOptions o;
  o.max_steps = 3;
  PredefinedSweep short_sweep(a, o);
  for (int i = 0; i < 3; ++i) {
    EXPECT_FALSE(short_sweep.stopped());
    short_sweep.observe(stop(robot, 0.0));
    if (i < 2) short_sweep.next(robot);
  }
  EXPECT_EQ(short_sweep.stopped_by(), "max_samples");
}

// An explorer that stays put and stops after `limit` observations.
class StayPut : public LocalizationMethod {
 public:
  explicit StayPut(int limit) : limit_(limit) {}
  std::string name() const override { return "stay"; }
  void observe(const Observation&) override { ++seen_; }
  Move next(Vec2 robot) override { return Move{robot, {}, 0.0}; }
  std::optional<Vec2> estimate() const override { return std::nullopt; }
  std::string stopped_by() const override { return seen_ >= limit_ ? "lost" : ""; }

 private:
  int limit_, seen_ = 0;
};

TEST_F(ParticleFilterTest, MethodStopsByDeclarationExplorerOrBudget) {
  PfMethodOptions o;
  o.declare_iterations = 0;
  o.max_steps = 5;
  ParticleFilterMethod budget(area, std::make_unique<StayPut>(100), o);
  EXPECT_EQ(budget.name(), "pf-stay");
  EXPECT_FALSE(budget.estimate().has_value());
  for (int i = 0; i < 5; ++i)
    budget.observe(stop({20.0, 4.0}, 0.0));
  EXPECT_EQ(budget.stopped_by(), "max_samples");
  EXPECT_TRUE(budget.estimate().has_value());

  ParticleFilterMethod lost(area, std::make_unique<StayPut>(3), o, "pf-test");
  EXPECT_EQ(lost.name(), "pf-test");
  for (int i = 0; i < 3; ++i)
    lost.observe(stop({20.0, 4.0}, 0.0));
  EXPECT_EQ(lost.stopped_by(), "lost");

  // No detection: no declaration however still the MNE; after one, 4 steady MNEs declare.
  o.declare_iterations = 4;
  o.max_steps = 100;
  o.filter.resample_fraction = 0.0;  // the particles never move, so neither does the MNE
  ParticleFilterMethod declare(area, std::make_unique<StayPut>(100), o);
  for (int i = 0; i < 10; ++i)
    declare.observe(stop({20.0, 4.0}, 0.0));
  EXPECT_FALSE(declare.stopped());
  declare.observe(stop({20.0, 4.0}, 500.0));  // z = 1
  for (int i = 0; i < 2; ++i)
    declare.observe(stop({20.0, 4.0}, 0.0));
  EXPECT_FALSE(declare.stopped());
  declare.observe(stop({20.0, 4.0}, 0.0));
  EXPECT_EQ(declare.stopped_by(), "declared");
}

// A fake plume from (8, 4) in a wind along +x: readings inside a cone widening downwind, falling
// off with distance; the PF driven by the predefined sweep from (32, 0) ends near the source.
double cone_plume(Vec2 p) {
  const double dx = p.x - 8.0;
  if (dx < -0.2 || std::abs(p.y - 4.0) > 0.3 + 0.15 * std::max(dx, 0.0)) return 0.0;
  return 3000.0 / (1.0 + std::max(dx, 0.0));
}

TEST_F(ParticleFilterTest, ClosedLoopSweepLocalizesAConePlume) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    PfMethodOptions o;
    o.seed = seed;
    auto method = make_pf_sweep(area, o);
    Vec2 robot{32.0, 0.0};
    int stops = 0;
    while (true) {
      method->observe(stop(robot, cone_plume(robot), kWind, 0.075));
      ++stops;
      if (method->stopped()) break;
      robot = method->next(robot).goal;
    }
    EXPECT_EQ(method->stopped_by(), "swept");
    EXPECT_EQ(stops, 33 * 9);
    ASSERT_TRUE(method->estimate().has_value());
    const Vec2 e = *method->estimate();
    EXPECT_LT(norm(e - Vec2{8.0, 4.0}), 1.5) << "seed " << seed << ": " << to_string(e) << " after "
                                             << stops << " stops, " << method->stopped_by();
  }
}

}  // namespace
}  // namespace plumekit::methods
