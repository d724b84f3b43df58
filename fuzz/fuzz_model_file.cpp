// Fuzzes the plumekit-cnn/1 model file reader (surrogate/model_file: parse_model_file) with
// arbitrary bytes. Bad input must end in InputError; anything else escaping is a bug, and libFuzzer
// reports it as a crash. An accepted model must be complete: one weight and bias array per layer,
// each of the size its layer says.
//
// The file ends in a SHA-256 of everything before it, which random mutations almost never keep
// right. So each input is read twice: as it is (the checks up to the checksum), and with its last
// 32 bytes replaced by the true digest, which takes the mutated header and tensors past the
// checksum into the architecture, shape and value checks.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "fuzz/reseal.hpp"
#include "surrogate/model_file.hpp"

namespace {

void read_and_check(std::string_view bytes) {
  try {
    const auto model = plumekit::surrogate::parse_model_file(bytes, "fuzz.pkcnn");
    if (model.weights.size() != model.layers.size() || model.biases.size() != model.layers.size())
      std::abort();
    for (std::size_t k = 0; k < model.layers.size(); ++k)
      if (model.weights[k].size() != model.layers[k].weight_count() ||
          model.biases[k].size() != static_cast<std::size_t>(model.layers[k].out))
        std::abort();
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
