#pragma once
// NumPy .npy files (format 1.0), little-endian float32 or float64, C order:
// what numpy.load and torch.from_numpy read directly. Ours rather than xtensor's xnpy:
// docs/own-code.md.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace plumekit {

// Bytes of an .npy file holding `values` (converted to float32) with `shape`.
std::string npy_float32(const std::vector<double>& values, const std::vector<std::size_t>& shape);
std::string npy_float32(const std::vector<float>& values, const std::vector<std::size_t>& shape);
// float64 (for fields that must round-trip exactly) and int32 (for ids).
std::string npy_float64(const std::vector<double>& values, const std::vector<std::size_t>& shape);
std::string npy_int32(const std::vector<std::int32_t>& values,
                      const std::vector<std::size_t>& shape);

struct NpyArray {
  std::vector<std::size_t> shape;
  std::vector<double> values;  // converted from the file's float32/float64
};

// The shape of an .npy file (float32, float64 or int32) from its header, checked against the
// file's size; the data is not read. InputError naming the file otherwise.
std::vector<std::size_t> read_npy_shape(const std::filesystem::path& path);

// Reads a float32 or float64 C-order array; InputError naming the file otherwise.
NpyArray read_npy(const std::filesystem::path& path);
// The same from a file's bytes already read (to check them and parse the very
// bytes checked); `path` only names the file in messages.
NpyArray parse_npy(std::string_view bytes, const std::filesystem::path& path);

}  // namespace plumekit
