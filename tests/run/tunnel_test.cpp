// Seed 004's 3-D systems in the tunnel: the 3-D plume model (Eq. 7.1), the 6-D posterior
// concentrating on a known source, the 6 candidate moves, the tunnel world's readings, and whole
// runs of the 3-D STE, the surge-spiral and the 2-D surge-cast (run/tunnel_run.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "run/tunnel_run.hpp"
#include "ste/ste_3d.hpp"
#include "world/tunnel_world.hpp"

namespace plumekit::ste {
namespace {

const Box3 kTunnel{{0, 0, 0}, {10, 4, 2}};

TEST(GaussianPlume3d, IsEq71) {
  const double m[6] = {1.0, 2.0, 1.0, 1000.0, 0.1, 0.05};  // x, y, z, Q, a, b
  const double u = 0.9;
  EXPECT_EQ(gaussian_plume_3d(m, {0.9, 2.0, 1.0}, u), 0.0);  // upwind
  EXPECT_EQ(gaussian_plume_3d(m, {1.0, 2.0, 1.0}, u), 0.0);  // at the source's x
  const double sigma = 0.1 * 3.0 + 0.05;                     // 3 m downwind
  const double axis = 1000.0 / (2.0 * kPi * u * sigma * sigma);
  EXPECT_NEAR(gaussian_plume_3d(m, {4.0, 2.0, 1.0}, u), axis, 1e-9 * axis);
  // Isotropic: 0.2 m across or 0.2 m up read alike, exp(-0.04 / (2 sigma^2)) of the axis.
  const double off = axis * std::exp(-0.04 / (2.0 * sigma * sigma));
  EXPECT_NEAR(gaussian_plume_3d(m, {4.0, 2.2, 1.0}, u), off, 1e-9 * axis);
  EXPECT_NEAR(gaussian_plume_3d(m, {4.0, 2.0, 0.8}, u), off, 1e-9 * axis);
}

TEST(Ste3dEstimator, PosteriorConcentratesOnAKnownSource) {
  const double truth[6] = {2.0, 1.4, 0.7, 800.0, 0.08, 0.1};
  Ste3dOptions o;
  o.likelihood.sigma_rel = 0.0;  // noise-free samples of the model itself
  Ste3dEstimator est(kTunnel, o, 11);
  Posterior3 first;
  int n = 0;
  // A 3 x 5 x 4 lattice behind the source, the model's exact readings.
  for (double x : {3.0, 4.5, 6.0})
    for (double y : {0.8, 1.1, 1.4, 1.7, 2.0})
      for (double z : {0.4, 0.7, 1.0, 1.3}) {
        est.add({x, y, z}, gaussian_plume_3d(truth, {x, y, z}, 0.9), 0.9);
        if (++n == 1) first = est.posterior();
      }
  Posterior3 post;
  for (int k = 0; k < 5; ++k)
    post = est.posterior();  // the chain continues: it settles on the truth
  EXPECT_NEAR(post.expected[0], truth[0], 0.25);
  EXPECT_NEAR(post.expected[1], truth[1], 0.05);
  EXPECT_NEAR(post.expected[2], truth[2], 0.05);
  EXPECT_LT(post.entropy, 0.02 * post.max_entropy);  // certain enough to declare
  EXPECT_GT(first.entropy, 5.0 * post.entropy + 0.5);
  EXPECT_NEAR(post.max_entropy, std::log(20.0 * 20.0 * 10.0), 1e-12);  // 0.5 x 0.2 x 0.2 m bins
  double mass = 0.0;
  for (double p : post.marginal)
    mass += p;
  EXPECT_NEAR(mass, 1.0, 1e-9);
  EXPECT_LT(norm(post.map - Vec3{truth[0], truth[1], truth[2]}), 0.3);
}

TEST(Ste3dEstimator, RefusesBadSamples) {
  Ste3dEstimator est(kTunnel, {}, 1);
  EXPECT_THROW(est.add({1, 1, NAN}, 5.0, 0.9), InputError);
  EXPECT_THROW(est.add({1, 1, 1}, -1.0, 0.9), InputError);
  EXPECT_THROW(est.add({1, 1, 1}, 5.0, 0.0), InputError);
  Ste3dOptions bad;
  bad.alpha = 1.5;
  try {
    Ste3dEstimator(kTunnel, bad, 1);
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "tunnel.ste.alpha");
  }
}

TEST(Decide3d, SixMovesOneAxisAtATimeAndTheMapPull) {
  Ste3dOptions o;
  Ste3dEstimator est(kTunnel, o, 3);
  est.add({5.0, 2.0, 1.0}, 300.0, 0.9);
  const Posterior3 post = est.posterior();
  const Vec3 robot{5.0, 2.0, 1.0};
  const Decision3 d = decide_3d(robot, est, post, kTunnel, o, 0.1);
  ASSERT_EQ(d.candidates.size(), 6u);
  for (const Vec3& c : d.candidates) {
    const Vec3 v = c - robot;
    const int moved = (v.x != 0) + (v.y != 0) + (v.z != 0);
    EXPECT_EQ(moved, 1);
    EXPECT_NEAR(norm(v), 0.5, 1e-12);
  }
  // V = 0.5 V_KLD + 0.5 V_MAP (inside the tunnel here).
  const Vec3 expected = robot + 0.5 * (d.kld_target - robot) + 0.5 * (d.source_target - robot);
  EXPECT_NEAR(norm(d.goal - expected), 0.0, 1e-12);
  // Against the floor and a side wall only 4 moves stay inside.
  const Decision3 corner = decide_3d({5.0, 0.3, 0.3}, est, post, kTunnel, o, 0.1);
  EXPECT_EQ(corner.candidates.size(), 4u);
  EXPECT_TRUE(kTunnel.contains(corner.goal));
}

run::TunnelOptions fast_options(const std::string& method) {
  run::TunnelOptions o;
  o.method = method;
  return o;
}

TEST(TunnelWorld, StopsReadTheMeanOfTheirReadingsAndNoiseIsClipped) {
  run::TunnelOptions o = fast_options("ste-3d");
  world::TunnelWorld a(o.tunnel, {1.0, 2.0, 1.0}, o.world, 9);
  world::TunnelWorld b(o.tunnel, {1.0, 2.0, 1.0}, o.world, 9);
  const world::Reading3 ra = a.stop({4.0, 2.0, 1.0}), rb = b.stop({4.0, 2.0, 1.0});
  EXPECT_EQ(ra.gas, rb.gas);  // deterministic
  EXPECT_GT(ra.gas, 100.0);   // on the plume's axis 3 m downwind
  EXPECT_NEAR(a.time(), 5.0, 1e-9);
  EXPECT_NEAR(ra.wind.x, 0.9, 0.1);
  // Far off the plume nothing, and noise never reads below 0.
  o.world.noise = 50.0;
  world::TunnelWorld noisy(o.tunnel, {1.0, 2.0, 1.0}, o.world, 9);
  const world::Reading3 off = noisy.stop({4.0, 0.2, 0.2});
  EXPECT_GE(off.gas, 0.0);
  EXPECT_GT(off.gas, 0.0);  // the clipped noise's mean is positive
  // A move of 0.05 m at 0.05 m/s takes 1 s: 10 readings.
  const double t = noisy.time();
  noisy.move({4.0, 0.2, 0.2}, {4.0, 0.25, 0.2}, 0.05);
  EXPECT_NEAR(noisy.time() - t, 1.0, 1e-9);
}

TEST(TunnelWorld, RefusesWhatNeedsAMap) {
  run::TunnelOptions o;
  o.world.rotor_disc = 0.5;
  try {
    o.validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "tunnel.world.rotor_disc");
  }
}

TEST(TunnelRun, SteFindsTheSourceIn3d) {
  const run::TunnelOptions o = fast_options("ste-3d");
  const Vec3 source{1.0, 1.5, 0.6};
  const run::TunnelRun r = run::run_tunnel(o, source, {8.0, 2.5, 1.5}, 21);
  EXPECT_EQ(r.stopped_by, "entropy");
  EXPECT_LT(r.error_m(), 0.5);
  EXPECT_LT(r.error().z, 0.2);  // Fig. 11.3: 10-20 cm
  EXPECT_EQ(r.estimate.x, r.steps.back().estimate.x);
  EXPECT_GT(r.distance_m, 0.0);
  for (const run::TunnelStep& s : r.steps)
    EXPECT_TRUE(o.tunnel.box().contains(s.position));
  // Deterministic.
  const run::TunnelRun again = run::run_tunnel(o, source, {8.0, 2.5, 1.5}, 21);
  EXPECT_EQ(again.estimate.x, r.estimate.x);
  EXPECT_EQ(again.steps.size(), r.steps.size());
}

TEST(TunnelRun, TrackersEndFoundOrOutOfTime) {
  for (const std::string m : {"surge-spiral", "surge-cast-2d"}) {
    run::TunnelOptions o = fast_options(m);
    o.time_limit_s = 120.0;
    const Vec3 source{1.0, 2.0, 1.0};
    const Vec3 start = run::random_tunnel_start(o, source, 4);
    EXPECT_NEAR(start.x, 9.9, 1e-12);  // 10 m downwind, cut to the 10 m tunnel's margin
    if (m == "surge-cast-2d") {
      EXPECT_NEAR(start.z, 0.9, 1e-12);  // 10 cm below the source
    }
    const run::TunnelRun r = run::run_tunnel(o, source, start, 4);
    EXPECT_TRUE(r.stopped_by == "found" || r.stopped_by == "time_limit") << r.stopped_by;
    if (r.stopped_by == "time_limit") {
      EXPECT_GE(r.mission_s, 120.0);
    }
    // One decision per second, 5 cm apart.
    ASSERT_GT(r.steps.size(), 10u);
    EXPECT_NEAR(r.steps[5].time_s - r.steps[4].time_s, 1.0, 1e-6);
    EXPECT_LE(norm(r.steps[5].position - r.steps[4].position), 0.05 + 1e-9);
    for (const run::TunnelStep& s : r.steps) {
      EXPECT_TRUE(o.tunnel.box().contains(s.position));
      if (m == "surge-cast-2d") {
        EXPECT_NEAR(s.position.z, 0.9, 1e-9);
      }
    }
    EXPECT_LE(r.closest_m(), norm(start - source));
    // The first reading within 0.5 m, or -1 when the robot never came that close.
    const double t = r.time_within(0.5);
    EXPECT_EQ(t<0.0, r.closest_m()> 0.5);
    EXPECT_EQ(r.time_within(100.0), r.steps.front().time_s);
  }
}

TEST(TunnelRun, RefusesPointsOutsideTheTunnelAndUnknownMethods) {
  const run::TunnelOptions o;
  try {
    run::run_tunnel(o, {1.0, 2.0, 2.5}, {5, 2, 1}, 1);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tunnel.source"), std::string::npos) << e.what();
  }
  EXPECT_THROW(run::run_tunnel(o, {1.0, 2.0, 1.0}, {5, 2, NAN}, 1), InputError);
  EXPECT_THROW(run::parse_tunnel_method("ste"), OptionError);
  EXPECT_THROW(run::parse_tunnel_methods("ste-3d,ste-3d"), OptionError);
  EXPECT_EQ(run::parse_tunnel_methods("all").size(), 3u);
}

}  // namespace
}  // namespace plumekit::ste
