// SHA-256 against the FIPS 180-2 / NIST example vectors, whole and in pieces.
#include "core/sha256.hpp"

#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace plumekit {
namespace {

TEST(Sha256, PublishedTestVectors) {
  EXPECT_EQ(to_hex(sha256("")), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(to_hex(sha256("abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // 56 bytes: the length no longer fits the first padding block.
  EXPECT_EQ(to_hex(sha256("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(to_hex(sha256("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmn"
                          "hijklmnoijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu")),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
  EXPECT_EQ(to_hex(sha256(std::string(1000000, 'a'))),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, IncrementalEqualsWhole) {
  Sha256 h;
  const std::string chunk(1000, 'a');
  for (int k = 0; k < 1000; ++k)
    h.update(chunk);
  EXPECT_EQ(h.hex_digest(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(sha256_hex("abc"), to_hex(sha256("abc")));
}

// Pieces that straddle the 64-byte block and the 56-byte padding boundary in every way, and empty
// pieces: each split gives the one-shot digest of the 448-bit and the 896-bit vectors.
TEST(Sha256, StreamingAtOddBoundariesEqualsOneShot) {
  const std::string vectors[] = {"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
                                 "abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmn"
                                 "hijklmnoijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu"};
  const std::string expected[] = {
      "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1",
      "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1"};
  for (int v = 0; v < 2; ++v) {
    const std::string& m = vectors[v];
    for (std::size_t a = 0; a <= m.size(); ++a)
      for (std::size_t b = a; b <= m.size(); b += 7) {
        Sha256 h;
        h.update(std::string_view(m).substr(0, a));
        h.update(std::string_view(m).substr(a, b - a));
        h.update("");
        h.update(std::string_view(m).substr(b));
        ASSERT_EQ(h.hex_digest(), expected[v]) << "split at " << a << " and " << b;
      }
  }
  // A million 'a' in pieces of 1, 63, 65, 127 and 4093 bytes in turn (primes and block +- 1).
  const std::string a(1000000, 'a');
  const std::size_t sizes[] = {1, 63, 65, 127, 4093};
  Sha256 h;
  for (std::size_t at = 0, k = 0; at < a.size(); ++k) {
    const std::size_t n = std::min(sizes[k % 5], a.size() - at);
    h.update(std::string_view(a).substr(at, n));
    at += n;
  }
  EXPECT_EQ(to_hex(h.digest()), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, MovedHasherGoesOn) {
  Sha256 h;
  h.update("ab");
  Sha256 moved = std::move(h);
  moved.update("c");
  EXPECT_EQ(moved.hex_digest(), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, FileOfBytesAndUnreadableFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("plumekit_sha256_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "abc.bin", std::ios::binary);
    out << "abc";
  }
  EXPECT_EQ(sha256_file(dir / "abc.bin"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  try {
    sha256_file(dir / "missing.bin");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.bin"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace plumekit
