#pragma once
// Output files appear whole or not at all: bytes go to a temporary file in the
// same directory, which is renamed over the target only once fully written.
#include <filesystem>
#include <string_view>

namespace plumekit {

void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

// Whole file as a string; InputError naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace plumekit
