// The loops scripts/check_vectorized.sh asks GCC to vectorize (issue 45): the fast world draws
// its normals and takes its exponentials in loops like these. Compiled only by that script.
#include <cstdint>

#include "core/counter_random.hpp"
#include "core/fast_math.hpp"

void probe_counter_normals(std::uint64_t key, const std::uint64_t* __restrict counters,
                           double* __restrict z0, double* __restrict z1, int n) {
  for (int k = 0; k < n; ++k)  // probe-loop: counter_normals
    plumekit::counter_normals(key, counters[k], z0[k], z1[k]);
}

void probe_exp_neg(const double* __restrict x, double* __restrict y, int n) {
  for (int k = 0; k < n; ++k)  // probe-loop: exp_neg
    y[k] = plumekit::fast::exp_neg(x[k]);
}
