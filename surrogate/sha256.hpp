#pragma once
// SHA-256 (FIPS 180-4): the checksum of plumekit-cnn model files. Python's hashlib writes it, so
// the engine needs no library beyond the standard one to check it.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace plumekit::surrogate {

using Sha256Digest = std::array<std::uint8_t, 32>;

Sha256Digest sha256(std::string_view bytes);

// Lower-case hexadecimal, 64 characters.
std::string to_hex(const Sha256Digest& digest);

}  // namespace plumekit::surrogate
