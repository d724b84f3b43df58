#pragma once
// Formats whose last 32 bytes are a SHA-256 of the rest (model files, table
// caches): a mutated input almost never passes the checksum, so the targets
// also read each input with its checksum recomputed, to reach the parser behind it.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "core/sha256.hpp"

namespace plumekit::fuzz {

// `bytes` with its trailing SHA-256 replaced by the digest of what precedes it;
// nothing when there are fewer than 32 bytes.
inline std::optional<std::string> resealed(std::string_view bytes) {
  constexpr std::size_t kDigest = 32;
  if (bytes.size() < kDigest) return std::nullopt;
  std::string out(bytes);
  const Sha256Digest digest = sha256(bytes.substr(0, bytes.size() - kDigest));
  out.replace(bytes.size() - kDigest, kDigest, reinterpret_cast<const char*>(digest.data()),
              kDigest);
  return out;
}

}  // namespace plumekit::fuzz
