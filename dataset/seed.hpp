#pragma once
// Moved to core/seed.hpp; this forwarding header goes once its users include that.
#include "core/seed.hpp"

namespace plumekit::dataset {
using plumekit::derive_seed;
using plumekit::splitmix64;
using plumekit::Stream;
}  // namespace plumekit::dataset
