#pragma once
// Seeding shared by every stage. Counter-based: every random stream is derived
// from (seed, indices, purpose) by SplitMix64, so a result's random numbers never
// depend on which thread or shard made it, or in what order.
#include <cstdint>

namespace plumekit {

// The seed every command uses when none is given.
inline constexpr std::uint64_t kDefaultSeed = 1;

// SplitMix64's finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mix.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// Purposes keep the streams of one (map, source) of a dataset apart.
enum class Stream : std::uint64_t { MapGeometry = 1, Sources = 2, Filaments = 3, InletSpeed = 4 };

inline std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t map_index,
                                 std::uint64_t source_index, Stream stream) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ map_index);
  h = splitmix64(h ^ source_index);
  return splitmix64(h ^ static_cast<std::uint64_t>(stream));
}

}  // namespace plumekit
