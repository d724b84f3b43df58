// core/counter_random: SplitMix64's sequence (against its published values), uniforms in [0, 1),
// and Box-Muller normals checked against a long double Box-Muller of the same uniforms and by
// their statistics. The statistical bounds are 5 standard errors (or the 0.1% Kolmogorov-Smirnov
// value); the draws are fixed, so a pass or fail is the same on every run.
#include "core/counter_random.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <vector>

#include <gtest/gtest.h>

namespace plumekit {
namespace {

constexpr int kPairs = 1000000;
constexpr std::uint64_t kKey = 0x5EED5EED12345678ULL;

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

struct Pairs {
  std::vector<double> z0, z1;
};

Pairs draw_pairs(std::uint64_t key, std::uint64_t first_counter, int count) {
  Pairs p{std::vector<double>(count), std::vector<double>(count)};
  for (int k = 0; k < count; ++k)
    counter_normals(key, first_counter + k, p.z0[k], p.z1[k]);
  return p;
}

// The 1e6 pairs of kKey most tests look at, drawn once.
const Pairs& pairs() {
  static const Pairs p = draw_pairs(kKey, 0, kPairs);
  return p;
}

double mean(const std::vector<double>& xs) {
  double sum = 0.0;
  for (double x : xs)
    sum += x;
  return sum / xs.size();
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double ma = mean(a), mb = mean(b);
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

// sup |F_n - Phi| of the sample against the standard normal distribution.
double kolmogorov_smirnov(std::vector<double> xs) {
  std::sort(xs.begin(), xs.end());
  const double n = xs.size();
  double d = 0.0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double cdf = 0.5 * std::erfc(-xs[i] / std::sqrt(2.0));
    d = std::max({d, (i + 1) / n - cdf, cdf - i / n});
  }
  return d;
}

// Vigna's splitmix64.c from seed 1234567 (the values other ports test against).
TEST(CounterRandom, BitsAreSplitMix64sSequence) {
  const std::uint64_t want[] = {6457827717110365317ULL, 3203168211198807973ULL,
                                9817491932198370423ULL, 4593380528125082431ULL,
                                16408922859458223821ULL};
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(counter_bits(1234567, i), want[i]) << i;
  // And the generator written as a state stepped by the golden gamma, for any key.
  std::uint64_t state = kKey;
  for (std::uint64_t i = 0; i < 1000; ++i) {
    state += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    ASSERT_EQ(counter_bits(kKey, i), z ^ (z >> 31)) << i;
  }
}

TEST(CounterRandom, UniformIsTheTop53BitsInTheUnitInterval) {
  std::vector<double> us(kPairs);
  for (int i = 0; i < kPairs; ++i) {
    us[i] = counter_uniform(kKey, i);
    ASSERT_EQ(us[i], static_cast<double>(counter_bits(kKey, i) >> 11) * 0x1p-53) << i;
    ASSERT_GE(us[i], 0.0);
    ASSERT_LT(us[i], 1.0);
  }
  EXPECT_EQ(counter_uniform(0, 0), static_cast<double>(counter_bits(0, 0) >> 11) * 0x1p-53);
  // Uniform on [0, 1): mean 1/2, variance 1/12, and the variance of s^2 is (1/80 - 1/144) / n.
  const double m = mean(us);
  double var = 0.0;
  for (double u : us)
    var += (u - m) * (u - m);
  var /= kPairs - 1;
  EXPECT_NEAR(m, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / kPairs));
  EXPECT_NEAR(var, 1.0 / 12.0, 5.0 * std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / kPairs));
}

// Box-Muller of the same two uniforms in long double with libm: only round-off apart.
TEST(CounterRandom, NormalsAreBoxMullerOfTheStreamsUniforms) {
  double worst = 0.0;
  for (std::uint64_t c = 0; c < 200000; ++c) {
    const long double u0 = ((counter_bits(kKey, 2 * c) >> 11) + 1) * 0x1p-53L;
    const long double u1 = (counter_bits(kKey, 2 * c + 1) >> 11) * 0x1p-53L;
    const long double radius = std::sqrt(-2.0L * std::log(u0));
    const long double angle = 6.283185307179586476925286766559L * u1;
    double z0, z1;
    counter_normals(kKey, c, z0, z1);
    worst = std::max({worst, static_cast<double>(std::fabs(z0 - radius * std::cos(angle))),
                      static_cast<double>(std::fabs(z1 - radius * std::sin(angle)))});
  }
  EXPECT_LE(worst, 4e-15);  // 8e-16 here: a few units in the last place of |z| < 8.6
}

TEST(CounterRandom, NormalsAreFiniteAndWithinTheLargestRadius) {
  // u0 >= 2^-53, so |z| <= sqrt(-2 ln 2^-53).
  const double largest = std::sqrt(2.0 * 53.0 * std::log(2.0));
  for (const std::vector<double>* zs : {&pairs().z0, &pairs().z1})
    for (double z : *zs) {
      ASSERT_TRUE(std::isfinite(z));
      ASSERT_LE(std::fabs(z), largest);
    }
}

TEST(CounterRandom, NormalsHaveTheStandardNormalsMoments) {
  std::vector<double> zs = pairs().z0;
  zs.insert(zs.end(), pairs().z1.begin(), pairs().z1.end());
  const double n = zs.size();
  const double m = mean(zs);
  double m2 = 0.0, m3 = 0.0, m4 = 0.0;
  for (double z : zs) {
    const double d = z - m, d2 = d * d;
    m2 += d2;
    m3 += d2 * d;
    m4 += d2 * d2;
  }
  m2 /= n, m3 /= n, m4 /= n;
  // The standard errors of a normal sample's mean, variance, skewness and excess kurtosis.
  EXPECT_NEAR(m, 0.0, 5.0 * std::sqrt(1.0 / n));
  EXPECT_NEAR(m2, 1.0, 5.0 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m3 / std::pow(m2, 1.5), 0.0, 5.0 * std::sqrt(6.0 / n));
  EXPECT_NEAR(m4 / (m2 * m2) - 3.0, 0.0, 5.0 * std::sqrt(24.0 / n));
}

TEST(CounterRandom, EachNormalOfThePairPassesKolmogorovSmirnov) {
  const double critical = 1.95 / std::sqrt(static_cast<double>(kPairs));  // 0.1%
  EXPECT_LT(kolmogorov_smirnov(pairs().z0), critical);
  EXPECT_LT(kolmogorov_smirnov(pairs().z1), critical);
}

TEST(CounterRandom, NormalsOfAPairAndOfNeighbouringCountersAreUncorrelated) {
  const double bound = 5.0 / std::sqrt(static_cast<double>(kPairs));
  const std::vector<double>&z0 = pairs().z0, &z1 = pairs().z1;
  EXPECT_LT(std::fabs(correlation(z0, z1)), bound);
  // Pair c against pair c + 1.
  const std::vector<double> z0_now(z0.begin(), z0.end() - 1), z0_next(z0.begin() + 1, z0.end());
  const std::vector<double> z1_now(z1.begin(), z1.end() - 1), z1_next(z1.begin() + 1, z1.end());
  EXPECT_LT(std::fabs(correlation(z0_now, z0_next)), bound);
  EXPECT_LT(std::fabs(correlation(z1_now, z1_next)), bound);
  EXPECT_LT(std::fabs(correlation(z1_now, z0_next)), bound);
}

TEST(CounterRandom, StreamsWhoseKeysDifferInOneBitAreUncorrelated) {
  const double bound = 5.0 / std::sqrt(static_cast<double>(kPairs));
  for (int bit : {0, 1, 17, 32, 63}) {
    const Pairs other = draw_pairs(kKey ^ (std::uint64_t{1} << bit), 0, kPairs);
    EXPECT_LT(std::fabs(correlation(pairs().z0, other.z0)), bound) << bit;
    EXPECT_LT(std::fabs(correlation(pairs().z1, other.z1)), bound) << bit;
    EXPECT_LT(std::fabs(correlation(pairs().z0, other.z1)), bound) << bit;
  }
}

// A pair is a function of (key, counter) alone: drawn alone, backwards, it has the same bits as
// in the forward loop.
TEST(CounterRandom, SameKeyAndCounterGiveTheSameBitsInAnyOrder) {
  const Pairs forward = draw_pairs(kKey, 1000, 10000);
  for (int k = 9999; k >= 0; --k) {
    double z0, z1;
    counter_normals(kKey, 1000 + k, z0, z1);
    ASSERT_EQ(bits(z0), bits(forward.z0[k])) << k;
    ASSERT_EQ(bits(z1), bits(forward.z1[k])) << k;
  }
  EXPECT_EQ(counter_bits(kKey, 77), counter_bits(kKey, 77));
  EXPECT_NE(counter_bits(kKey, 77), counter_bits(kKey, 78));
}

// Fixed values, so that a change of formula is caught. Recorded from this implementation (GCC 12,
// -O3 -march=native). They are compared to 1e-14, not bit for bit: whether the compiler fuses a
// multiply and an add (FMA contraction: on under -march=native, off without FMA or with
// -ffp-contract=off) moves about 4% of the normals by one unit in the last place (at most 9e-16
// in 1e6 pairs), while any change of formula moves them far more than 1e-14.
TEST(CounterRandom, FixedValues) {
  struct Fixed {
    std::uint64_t key, counter;
    double z0, z1;
  };
  const Fixed fixed[] = {
      {42, 0, 0.41471975043153053, 0.6526812221519428},
      {42, 1, -0.89188621362775644, 1.3268335628141061},
      {42, 1000000, 0.92145265031919887, 2.8441025569917149},
      {0x0123456789ABCDEFULL, 0, 1.1186819870407612, -1.9248120524117756},
      {0x0123456789ABCDEFULL, 1, -1.2042172457172178, -1.3841997366722889},
      {0x0123456789ABCDEFULL, 1000000, 0.21560171348430227, 0.75918381392063472},
  };
  for (const Fixed& f : fixed) {
    double z0, z1;
    counter_normals(f.key, f.counter, z0, z1);
    EXPECT_NEAR(z0, f.z0, 1e-14) << f.key << " " << f.counter;
    EXPECT_NEAR(z1, f.z1, 1e-14) << f.key << " " << f.counter;
  }
}

}  // namespace
}  // namespace plumekit
