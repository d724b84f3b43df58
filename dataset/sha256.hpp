#pragma once
// SHA-256 (FIPS 180-4), for the shard checksums in dataset manifests: the
// digest `sha256sum` prints, so anyone can check a shard without plumekit.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace plumekit::dataset {

class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  std::string hex_digest();  // 64 lowercase hex digits; finishes the hash

 private:
  void block(const unsigned char* p);
  std::uint32_t h_[8];
  unsigned char buf_[64];
  std::size_t used_ = 0;
  std::uint64_t length_ = 0;  // bytes
};

std::string sha256_hex(std::string_view bytes);
// Of a file's contents; InputError naming the file when it cannot be read.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace plumekit::dataset
