// Issue 43 ("Own less"): core/sha256's OpenSSL EVP hashing against the hand-written FIPS 180-4
// code it replaced, kept here only as the named baseline. Short strings (a map's geometry key),
// a 4 KiB piece and a 1 MiB piece (sha256_file's read size), digests checked equal first.
//
//   build/bench/sha256_bench [--benchmark_repetitions=5]
//
// The last table is the time of the baseline over OpenSSL's for each size (>1: OpenSSL is faster).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "bench/baseline_ratio.hpp"
#include "core/sha256.hpp"

namespace {

// The hand-written SHA-256 that core/sha256.cpp held before issue 43, unchanged.
class HandWrittenSha256 {
 public:
  void update(std::string_view bytes) {
    length_ += bytes.size();
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    std::size_t n = bytes.size();
    while (n > 0) {
      const std::size_t take = std::min(n, 64 - used_);
      std::memcpy(buf_ + used_, p, take);
      used_ += take, p += take, n -= take;
      if (used_ == 64) {
        block(buf_);
        used_ = 0;
      }
    }
  }

  plumekit::Sha256Digest digest() {
    const std::uint64_t bits = length_ * 8;
    const unsigned char pad = 0x80;
    update(std::string_view(reinterpret_cast<const char*>(&pad), 1));
    const unsigned char zero = 0;
    while (used_ != 56)
      update(std::string_view(reinterpret_cast<const char*>(&zero), 1));
    unsigned char len[8];
    for (int k = 0; k < 8; ++k)
      len[k] = static_cast<unsigned char>(bits >> (56 - 8 * k));
    update(std::string_view(reinterpret_cast<const char*>(len), 8));
    plumekit::Sha256Digest out;
    for (int k = 0; k < 8; ++k)
      for (int b = 0; b < 4; ++b)
        out[4 * k + b] = static_cast<std::uint8_t>(h_[k] >> (24 - 8 * b));
    return out;
  }

 private:
  static std::uint32_t rotr(std::uint32_t x, int n) { return (x >> n) | (x << (32 - n)); }

  void block(const unsigned char* p) {
    static constexpr std::uint32_t kK[64] = {
        0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4,
        0xab1c5ed5, 0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe,
        0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f,
        0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7,
        0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc,
        0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b,
        0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116,
        0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
        0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7,
        0xc67178f2};
    std::uint32_t w[64];
    for (int t = 0; t < 16; ++t)
      w[t] = (std::uint32_t(p[4 * t]) << 24) | (std::uint32_t(p[4 * t + 1]) << 16) |
             (std::uint32_t(p[4 * t + 2]) << 8) | std::uint32_t(p[4 * t + 3]);
    for (int t = 16; t < 64; ++t) {
      const std::uint32_t s0 = rotr(w[t - 15], 7) ^ rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
      const std::uint32_t s1 = rotr(w[t - 2], 17) ^ rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
      w[t] = w[t - 16] + s0 + w[t - 7] + s1;
    }
    std::uint32_t a = h_[0], b = h_[1], c = h_[2], d = h_[3], e = h_[4], f = h_[5], g = h_[6],
                  h = h_[7];
    for (int t = 0; t < 64; ++t) {
      const std::uint32_t t1 =
          h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + kK[t] + w[t];
      const std::uint32_t t2 =
          (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
      h = g;
      g = f;
      f = e;
      e = d + t1;
      d = c;
      c = b;
      b = a;
      a = t1 + t2;
    }
    h_[0] += a, h_[1] += b, h_[2] += c, h_[3] += d, h_[4] += e, h_[5] += f, h_[6] += g, h_[7] += h;
  }

  std::uint32_t h_[8] = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                         0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  unsigned char buf_[64];
  std::size_t used_ = 0;
  std::uint64_t length_ = 0;
};

std::string message(std::size_t size) {
  std::string m(size, '\0');
  for (std::size_t i = 0; i < size; ++i)
    m[i] = static_cast<char>((i * 131 + 7) & 0xff);
  return m;
}

void baseline(benchmark::State& state) {
  const std::string m = message(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    HandWrittenSha256 h;
    h.update(m);
    benchmark::DoNotOptimize(h.digest());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * m.size()));
}

void library(benchmark::State& state) {
  const std::string m = message(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(plumekit::sha256(m));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * m.size()));
}

}  // namespace

BENCHMARK(baseline)->Name("sha256/baseline")->Arg(64)->Arg(4096)->Arg(1 << 20);
BENCHMARK(library)->Name("sha256/library")->Arg(64)->Arg(4096)->Arg(1 << 20);

int main(int argc, char** argv) {
  // The comparison means nothing unless both give the same digests.
  for (std::size_t size : {std::size_t(0), std::size_t(55), std::size_t(64), std::size_t(100003)}) {
    const std::string m = message(size);
    HandWrittenSha256 h;
    h.update(m);
    if (h.digest() != plumekit::sha256(m)) {
      std::fprintf(stderr, "sha256_bench: digests differ for %zu bytes\n", size);
      return 1;
    }
  }
  return plumekit_bench::run_with_ratios(argc, argv);
}
