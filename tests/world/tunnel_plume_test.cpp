// The 3-D tunnel plume (world/tunnel_plume.hpp): its long-run mean is Arya's Gaussian of seed 004
// Eq. 7.1 with the filaments' spread, mass leaves only through the outlet, and bad input is
// refused.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/grid.hpp"
#include "world/tunnel_plume.hpp"

namespace plumekit::dataset {
namespace {

world::FilamentOptions steady_options() {
  world::FilamentOptions o = world::tunnel_filament_options();
  o.meander_speed = 0.0;  // the mean is then exactly the Gaussian's
  o.release_per_second = 400.0;
  return o;
}

// Eq. 7.1 with sigma^2 = R0^2 / 2 + 2 D_eq d / u (a filament's own size and its walk and growth).
double gaussian_mean(const world::FilamentOptions& o, double u, Vec3 source, Vec3 p) {
  const double d = p.x - source.x;
  const double s2 =
      0.5 * o.initial_radius * o.initial_radius + 2.0 * o.equivalent_diffusivity() * d / u;
  const double r2 = (p.y - source.y) * (p.y - source.y) + (p.z - source.z) * (p.z - source.z);
  return o.release_rate / (2.0 * kPi * u * s2) * std::exp(-r2 / (2.0 * s2));
}

TEST(TunnelPlume, LongRunMeanIsTheGaussianOfEq71) {
  const world::Tunnel tunnel;  // 10 x 4 x 2 m, 0.9 m/s
  const world::FilamentOptions o = steady_options();
  const Vec3 source{1.0, 2.0, 1.0};
  world::TunnelPlume plume(tunnel, source, o, 7);
  ASSERT_TRUE(world::spin_up(plume, o));
  const Vec3 points[] = {{3.0, 2.0, 1.0}, {3.0, 2.25, 1.0}, {5.0, 2.0, 1.2}, {5.0, 1.7, 0.9}};
  double sum[4] = {0, 0, 0, 0};
  const int steps = 3000;  // 300 s
  for (int s = 0; s < steps; ++s) {
    plume.step();
    for (int k = 0; k < 4; ++k)
      sum[k] += plume.concentration_at(points[k]);
  }
  for (int k = 0; k < 4; ++k) {
    const double expected = gaussian_mean(o, tunnel.speed, source, points[k]);
    EXPECT_NEAR(sum[k] / steps, expected, 0.1 * expected) << "point " << k;
  }
  // Upwind of the source there is (almost) no gas: the walk's reach against 0.9 m/s is millimetres.
  EXPECT_LT(plume.concentration_at({0.5, 2.0, 1.0}),
            1e-3 * gaussian_mean(o, 0.9, source, points[0]));
}

TEST(TunnelPlume, FilamentsStayInsideAndLeaveThroughTheOutlet) {
  world::Tunnel tunnel;
  tunnel.length = 4.0;
  const world::FilamentOptions o = steady_options();
  world::TunnelPlume plume(tunnel, {0.5, 0.3, 1.7}, o, 3);  // near a side wall and the ceiling
  for (int s = 0; s < 200; ++s)
    plume.step();
  // 20 s at 0.9 m/s cross the 4 m tunnel: a steady count, far below the 8000 released.
  EXPECT_LT(plume.filaments().size(), 2500u);
  EXPECT_GT(plume.filaments().size(), 1000u);
  for (const world::Filament3& f : plume.filaments())
    ASSERT_TRUE(tunnel.box().contains(f.position));
}

TEST(TunnelPlume, RefusesBadInput) {
  const world::Tunnel tunnel;
  EXPECT_THROW(world::TunnelPlume(tunnel, {1.0, 2.0, 2.5}, steady_options(), 1), InputError);
  EXPECT_THROW(world::TunnelPlume(tunnel, {1.0, NAN, 1.0}, steady_options(), 1), InputError);
  world::FilamentOptions map_world;  // the 2-D defaults: occlusion on
  try {
    world::TunnelPlume(tunnel, {1.0, 2.0, 1.0}, map_world, 1);
    FAIL() << "occlusion in a tunnel without a map";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "plume.world");
  }
  world::Tunnel flat = tunnel;
  flat.height = 0.1;
  try {
    world::TunnelPlume(flat, {1.0, 2.0, 0.05}, steady_options(), 1);
    FAIL() << "a tunnel 10 cm high";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "tunnel.height");
  }
}

TEST(TunnelPlume, SameSeedSameConcentrations) {
  const world::Tunnel tunnel;
  world::TunnelPlume a(tunnel, {1.0, 2.0, 1.0}, world::tunnel_filament_options(), 5);
  world::TunnelPlume b(tunnel, {1.0, 2.0, 1.0}, world::tunnel_filament_options(), 5);
  world::TunnelPlume c(tunnel, {1.0, 2.0, 1.0}, world::tunnel_filament_options(), 6);
  for (int s = 0; s < 100; ++s)
    a.step(), b.step(), c.step();
  EXPECT_EQ(a.concentration_at({4.0, 2.0, 1.0}), b.concentration_at({4.0, 2.0, 1.0}));
  EXPECT_NE(a.concentration_at({4.0, 2.0, 1.0}), c.concentration_at({4.0, 2.0, 1.0}));
}

TEST(TunnelPlume, APlanesGridIsTheConcentrationAtItsCellCentres) {
  const world::Tunnel tunnel;
  world::TunnelPlume plume(tunnel, {1.0, 2.0, 1.0}, world::tunnel_filament_options(), 5);
  for (int s = 0; s < 300; ++s)
    plume.step();
  const GridShape top{50, 20, tunnel.length, tunnel.width},
      side{50, 10, tunnel.length, tunnel.height};
  std::vector<float> above, beside;
  plume.concentration_on(top, world::TunnelPlume::Plane::Top, 1.1, above);
  plume.concentration_on(side, world::TunnelPlume::Plane::Side, 1.9, beside);
  double peak = 0.0;
  for (int j = 0; j < top.ny; ++j)
    for (int i = 0; i < top.nx; ++i) {
      const Vec2 c = top.centre(i, j);
      const double want = plume.concentration_at({c.x, c.y, 1.1});
      peak = std::max(peak, want);
      EXPECT_NEAR(above[top.index(i, j)], want, 1e-5 * want + 1e-9) << i << ", " << j;
    }
  for (int j = 0; j < side.ny; ++j)
    for (int i = 0; i < side.nx; ++i) {
      const Vec2 c = side.centre(i, j);
      const double want = plume.concentration_at({c.x, 1.9, c.y});
      EXPECT_NEAR(beside[side.index(i, j)], want, 1e-5 * want + 1e-9) << i << ", " << j;
    }
  EXPECT_GT(peak, 100.0);  // the plane cuts the plume
}

}  // namespace
}  // namespace plumekit::dataset
