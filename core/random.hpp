#pragma once
// Random variates whose values are fixed by this file, not by the standard
// library: the C++ standard leaves the algorithms of std::*_distribution open,
// so the same seed could give other bytes with another compiler. The formulas
// are those of libstdc++ (GCC 12), so switching to them kept every dataset and
// evaluation byte-identical on the build machine.
#include <random>

namespace plumekit {

// A uniform double in [0, 1) from one 64-bit draw: (x / 2^64), and the largest
// double below 1 when that rounds to 1.
double uniform01(std::mt19937_64& rng);

// A uniform double in [lo, hi): uniform01 * (hi - lo) + lo.
double uniform(std::mt19937_64& rng, double lo, double hi);

// Standard normal variates by Marsaglia's polar method. Each accepted pair gives
// two variates; the second is kept for the next call, so one sampler must be
// used for one stream, and a fresh sampler starts a fresh pair.
class NormalSampler {
 public:
  double operator()(std::mt19937_64& rng);

 private:
  double saved_ = 0.0;
  bool saved_available_ = false;
};

// mean + sd * z, z from `sampler`.
double normal(NormalSampler& sampler, std::mt19937_64& rng, double mean, double sd);

}  // namespace plumekit
