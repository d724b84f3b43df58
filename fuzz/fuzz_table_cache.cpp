// Fuzzes the surrogate table cache reader (ste/surrogate_plume: parse_table_cache) with arbitrary
// bytes. Bad input must end in InputError; anything else escaping is a bug, and libFuzzer reports
// it as a crash. An accepted table must hold rows x per finite, non-negative cells in each of its
// two plumes, and write back to the same bytes.
//
// The file ends in a SHA-256 of everything before it, which random mutations almost never keep
// right. So each input is read twice: as it is, and with its last 32 bytes replaced by the true
// digest, which takes the mutated header and plumes past the checksum.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "fuzz/reseal.hpp"
#include "ste/surrogate_plume.hpp"

namespace {

void read_and_check(std::string_view bytes) {
  try {
    const plumekit::ste::SurrogateTable t = plumekit::ste::parse_table_cache(bytes, "fuzz.bin");
    const std::size_t cells = std::size_t{t.rows} * t.per;
    if (t.mean.size() != cells || t.std.size() != cells) std::abort();
    for (std::size_t k = 0; k < cells; ++k)
      if (!std::isfinite(t.mean[k]) || t.mean[k] < 0 || !std::isfinite(t.std[k]) || t.std[k] < 0)
        std::abort();
    if (plumekit::ste::table_cache_bytes(t) != bytes) std::abort();
  } catch (const plumekit::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  read_and_check(bytes);
  if (const auto again = plumekit::fuzz::resealed(bytes)) read_and_check(*again);
  return 0;
}
