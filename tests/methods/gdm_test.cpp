// Kernel DM+V and DM+V/W against their formulas (seed 000 eqs. 7.1-7.14), and the scores.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/thread_pool.hpp"
#include "map/map.hpp"
#include "methods/gdm_estimates.hpp"
#include "methods/kernel_dmv.hpp"
#include "run/gdm_score.hpp"
#include "support/uniform_wind.hpp"

namespace plumekit::methods {
namespace {

constexpr double kPi = 3.14159265358979323846;

// An empty 10 x 4 m arena: cells of 0.1 m, so (i + 0.5) / 10 is a cell centre.
Map open_arena() {
  return default_arena(10.0, 4.0);
}

double gauss(double d2_over_var, double norm) {
  return norm * std::exp(-0.5 * d2_over_var);
}

TEST(KernelDmv, MeanAndConfidenceFollowTheFormulas) {
  // Two readings far apart (no overlap at 4 sigma), at cell centres.
  const std::vector<Sample> s{{{2.05, 2.05}, 0.0, {}}, {{8.05, 2.05}, 100.0, {}}};
  methods::GdmOptions o;
  const methods::GdmMaps m = methods::kernel_dmv(open_arena(), s, o);
  EXPECT_EQ(m.mean.shape.nx, 100);
  EXPECT_EQ(m.samples, 2);
  EXPECT_DOUBLE_EQ(m.background_mean, 50.0);
  const double norm = 1.0 / (2.0 * kPi * 0.16);
  // At the second reading's cell: Omega = the kernel's peak; alpha = 1 - exp(-Omega / 1).
  const double omega = norm, alpha = 1.0 - std::exp(-omega);
  EXPECT_NEAR(m.weight(80, 20), omega, 1e-12);
  EXPECT_NEAR(m.confidence(80, 20), alpha, 1e-12);
  EXPECT_NEAR(m.mean(80, 20), alpha * 100.0 + (1.0 - alpha) * 50.0, 1e-9);
  // Half a metre away (5 cells): the kernel's value there.
  EXPECT_NEAR(m.weight(85, 20), gauss(0.25 / 0.16, norm), 1e-12);
  // Beyond every kernel: the background, no confidence.
  EXPECT_EQ(m.weight(50, 20), 0.0);
  EXPECT_DOUBLE_EQ(m.mean(50, 20), 50.0);
  EXPECT_DOUBLE_EQ(m.confidence(50, 20), 0.0);
  // The min background (seed 000 ch. 8).
  o.background = Background::Min;
  EXPECT_DOUBLE_EQ(methods::kernel_dmv(open_arena(), s, o).mean(50, 20), 0.0);
}

TEST(KernelDmv, VarianceIsTheSpreadOfReadingsAroundTheMean) {
  // Two readings in one cell, 0 and 10: the mean there is 5 (the background too), each departs
  // by 5, so the variance is 25 there and, as background, everywhere.
  const std::vector<Sample> s{{{5.05, 2.05}, 0.0, {}}, {{5.05, 2.05}, 10.0, {}}};
  const methods::GdmMaps m = methods::kernel_dmv(open_arena(), s, methods::GdmOptions{});
  EXPECT_NEAR(m.mean(50, 20), 5.0, 1e-12);
  EXPECT_NEAR(m.background_variance, 25.0, 1e-12);
  EXPECT_NEAR(m.variance(50, 20), 25.0, 1e-9);
  EXPECT_NEAR(m.variance(10, 10), 25.0, 1e-9);
}

TEST(KernelDmvW, KernelsStretchAlongTheWindAndKeepTheirArea) {
  methods::GdmOptions o;
  o.wind_stretch = 0.6;  // with |u| = 1: a = 1.0, b = 0.4 / 2.5 = 0.16, a b = sigma^2
  const double a = 1.0, b = 0.16, norm = 1.0 / (2.0 * kPi * a * b);
  const methods::GdmMaps east =
      methods::kernel_dmv(open_arena(), {{{5.05, 2.05}, 1.0, Vec2{1.0, 0.0}}}, o);
  EXPECT_NEAR(norm, 1.0 / (2.0 * kPi * 0.16), 1e-12);  // the same peak as the round kernel
  EXPECT_NEAR(east.weight(55, 20), gauss(0.25 / (a * a), norm), 1e-12);  // 0.5 m downwind
  EXPECT_NEAR(east.weight(50, 25), gauss(0.25 / (b * b), norm), 1e-12);  // 0.5 m across
  EXPECT_GT(east.weight(55, 20), 100.0 * east.weight(50, 25));
  // A wind from the south turns the ellipse by 90 degrees.
  const methods::GdmMaps north =
      methods::kernel_dmv(open_arena(), {{{5.05, 2.05}, 1.0, Vec2{0.0, 2.0}}}, o);
  const double a2 = 0.4 + 0.6 * 2.0, b2 = 0.16 / a2;
  EXPECT_NEAR(north.weight(50, 25), gauss(0.25 / (a2 * a2), 1.0 / (2.0 * kPi * a2 * b2)), 1e-12);
  // Without a wind, or with gamma 0, a kernel is round (Kernel DM+V).
  const methods::GdmMaps still = methods::kernel_dmv(open_arena(), {{{5.05, 2.05}, 1.0, {}}}, o);
  EXPECT_NEAR(still.weight(55, 20), still.weight(50, 25), 1e-15);
}

TEST(KernelDmv, ObstacleCellsAreNaNAndBadInputIsRefused) {
  Map map = open_arena();
  map.obstacles.push_back({{4.0, 1.0}, {6.0, 1.0}, {6.0, 3.0}, {4.0, 3.0}});
  const methods::GdmMaps m =
      methods::kernel_dmv(map, {{{2.05, 2.05}, 1.0, {}}}, methods::GdmOptions{});
  EXPECT_TRUE(std::isnan(m.mean(50, 20)) && std::isnan(m.variance(50, 20)));
  EXPECT_TRUE(std::isfinite(m.mean(20, 20)));
  EXPECT_THROW(methods::kernel_dmv(map, {}, methods::GdmOptions{}), InputError);
  EXPECT_THROW(methods::kernel_dmv(map, {{{2.0, 2.0}, std::nan(""), {}}}, methods::GdmOptions{}),
               InputError);
  methods::GdmOptions bad;
  bad.kernel_width = 0.0;
  try {
    methods::kernel_dmv(map, {{{2.0, 2.0}, 1.0, {}}}, bad);
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "gdm.kernel_width");
  }
  EXPECT_THROW(methods::parse_background("median"), OptionError);
}

TEST(KernelDmv, TheLargestAcceptedReadingsGiveFiniteMaps) {
  // A thousand readings of +-kMaxReading at one point under a narrow kernel: plain sums of their
  // squared departures (4e300 each, times a peak weight of 1.6e5) would overflow to inf.
  std::vector<Sample> s;
  for (int k = 0; k < 1000; ++k)
    s.push_back({{5.05, 2.05}, k % 2 ? methods::kMaxReading : -methods::kMaxReading, {}});
  methods::GdmOptions o;
  o.kernel_width = 1e-3;
  const methods::GdmMaps m = methods::kernel_dmv(open_arena(), s, o);
  for (const Grid<double>* g : {&m.mean, &m.variance, &m.confidence})
    for (double v : g->values)
      ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(m.variance(50, 20), 1e299);
  EXPECT_TRUE(std::isfinite(m.background_variance));
}

TEST(KernelDmv, AbsurdSamplesAreRefusedAndOutsideOnesCounted) {
  const auto message = [](const Sample& s) {
    try {
      methods::kernel_dmv(open_arena(), {s}, methods::GdmOptions{});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({{5.0, 2.0}, 1e308, {}}).find("sample 1, reading: 1e+308 is beyond"),
            std::string::npos);
  EXPECT_NE(message({{1e300, 2.0}, 1.0, {}}).find("sample 1, x: 1e+300 m lies more than"),
            std::string::npos);
  EXPECT_NE(message({{5.0, -11.0}, 1.0, {}}).find("sample 1, y:"), std::string::npos);
  EXPECT_NE(message({{5.0, 2.0}, 1.0, Vec2{0.0, 1e300}}).find("sample 1, v:"), std::string::npos);
  EXPECT_EQ(message({{-9.0, 2.0}, 1.0, {}}), "");  // within a side of the arena: counted
  const methods::GdmMaps m =
      methods::kernel_dmv(open_arena(), {{{-0.5, 2.0}, 1.0, {}}, {{5.0, 2.0}, 2.0, {}}}, {});
  EXPECT_EQ(m.samples, 2);
  EXPECT_EQ(m.outside_arena, 1);
  EXPECT_GT(m.weight(0, 20), 0.01);  // its kernel reaches in
}

TEST(KernelDmv, TheSameBytesOnAnyNumberOfThreadsWithProgress) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-1.0, 11.0), y(-1.0, 5.0), r(0.0, 1000.0), u(-2.0, 2.0);
  std::vector<Sample> s;
  for (int k = 0; k < 3000; ++k)
    s.push_back({{x(rng), y(rng)}, r(rng), Vec2{u(rng), u(rng)}});
  methods::GdmOptions o;
  o.wind_stretch = 0.4;
  Map map = open_arena();
  map.obstacles.push_back({{4.0, 1.0}, {6.0, 1.0}, {6.0, 3.0}, {4.0, 3.0}});
  const methods::GdmMaps serial = methods::kernel_dmv(map, s, o);
  for (int threads : {1, 2, 5}) {
    ThreadPool pool(threads);
    std::vector<double> seen;
    const methods::GdmMaps m =
        methods::kernel_dmv(map, s, o, {&pool, [&](double f) { seen.push_back(f); }});
    for (auto [a, b] : {std::pair{&serial.mean, &m.mean},
                        {&serial.variance, &m.variance},
                        {&serial.confidence, &m.confidence},
                        {&serial.weight, &m.weight}})
      EXPECT_EQ(std::memcmp(a->values.data(), b->values.data(), a->values.size() * sizeof(double)),
                0)
          << threads << " threads";
    ASSERT_FALSE(seen.empty());
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
    EXPECT_EQ(seen.back(), 1.0);
  }
}

TEST(KernelDmv, AGridBeyondTheMemoryLimitIsRefusedNamingACellThatFits) {
  set_memory_limit(64.0 * 1024 * 1024);
  methods::GdmOptions o;
  o.cell = 0.0001;  // 4e9 cells on the 10 x 4 m arena
  std::string message;
  try {
    methods::kernel_dmv(open_arena(), {{{5.0, 2.0}, 1.0, {}}}, o);
  } catch (const MemoryLimitError& e) {
    message = e.what();
  }
  const auto at = message.find("use a larger gdm.cell (");
  ASSERT_NE(at, std::string::npos) << message;
  o.cell = std::stod(message.substr(at + 23));
  EXPECT_GT(o.cell, 0.005);
  EXPECT_EQ(methods::kernel_dmv(open_arena(), {{{5.0, 2.0}, 1.0, {}}}, o).samples, 1);
  set_memory_limit(default_memory_limit());
}

TEST(MapScore, KlDistanceIsZeroForTheSameMapAndSymmetric) {
  const GridShape g = GridShape::with_cell(2.0, 1.0, 0.5);
  Grid<double> a(g, 1.0), b(g, 1.0);
  a.values[0] = 5.0;
  b.values[3] = 5.0;
  EXPECT_NEAR(run::score_mean(a, a).kl_distance, 0.0, 1e-12);
  EXPECT_EQ(run::score_mean(a, a).rmse, 0.0);
  EXPECT_GT(run::score_mean(a, b).kl_distance, 0.1);
  EXPECT_NEAR(run::score_mean(a, b).kl_distance, run::score_mean(b, a).kl_distance, 1e-12);
  EXPECT_NEAR(run::score_mean(a, b).rmse, std::sqrt(2.0 * 16.0 / 8.0), 1e-12);
  // A map that leaves a cell empty still scores finite.
  Grid<double> c(g, 0.0);
  c.values[1] = 1.0;
  EXPECT_TRUE(std::isfinite(run::score_mean(c, a).kl_distance));
}

// Readings of the true mean plume on a 0.5 m lattice give maps close to it, and the peaks find the
// source: the maps' meaning, on the world's own plume.
TEST(MapScore, DenseReadingsOfTheTruePlumeMapItAndFindTheSource) {
  const Map map = open_arena();
  const cfd::WindField wind = test::uniform_wind(10.0, 4.0, 0.05, 1.0);
  const Vec2 source{2.0, 2.0};
  methods::GdmOptions o;
  const GridShape g = GridShape::with_cell(map.width, map.height, o.cell);
  const Grid<double> truth = run::true_mean_plume(map, wind, source, g);
  std::vector<Sample> dense;
  for (double y = 0.25; y < 4.0; y += 0.5)
    for (double x = 0.25; x < 10.0; x += 0.5) {
      const int i = static_cast<int>(x / 0.1), j = static_cast<int>(y / 0.1);
      dense.push_back({{x, y}, truth(i, j), Vec2{1.0, 0.0}});
    }
  o.background = Background::Min;
  const methods::GdmMaps m = methods::kernel_dmv(map, dense, o);
  const run::MapScore s = run::score_mean(m.mean, truth);
  EXPECT_LT(s.kl_distance, 0.2);  // measured 0.15
  EXPECT_LT(s.rmse, 0.1 * s.truth_peak);
  // Sparse readings score worse.
  std::vector<Sample> sparse;
  for (std::size_t k = 0; k < dense.size(); k += 7)
    sparse.push_back(dense[k]);
  EXPECT_GT(run::score_mean(methods::kernel_dmv(map, sparse, o).mean, truth).kl_distance,
            s.kl_distance);
  const std::vector<methods::SourceEstimate> e = methods::source_estimates(m);
  ASSERT_EQ(e.size(), 6u);
  EXPECT_EQ(e[0].name, "peak mean");
  // The mean's peak lies downwind of the source, within the seeds' success radius (1.5 m): the
  // kernels average the steep rise at the source with the zeros upwind of it (measured 0.95 m).
  EXPECT_LT(norm(e[0].position - source), 1.5);
  EXPECT_GT(e[0].position.x, source.x);
}

}  // namespace
}  // namespace plumekit::methods
