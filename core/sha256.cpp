#include "core/sha256.hpp"

#include <openssl/evp.h>

#include <fstream>
#include <new>
#include <stdexcept>
#include <vector>

#include "core/error.hpp"

namespace plumekit {

namespace {

// OpenSSL fails only when it cannot allocate or its provider is broken: our fault, not the input's.
void check(int ok, const char* what) {
  if (ok != 1) throw std::runtime_error(std::string("SHA-256: OpenSSL ") + what + " failed");
}

// Fetched once: OpenSSL 3's EVP_sha256() looks the algorithm up again on every init,
// which costs more than hashing a short string.
const EVP_MD* sha256_method() {
  static EVP_MD* const md = EVP_MD_fetch(nullptr, "SHA256", nullptr);
  if (!md) throw std::runtime_error("SHA-256: OpenSSL has no SHA256 (EVP_MD_fetch failed)");
  return md;
}

}  // namespace

struct Sha256::Context {
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  ~Context() { EVP_MD_CTX_free(ctx); }
};

Sha256::Sha256() : ctx_(std::make_unique<Context>()) {
  if (!ctx_->ctx) throw std::bad_alloc();
  check(EVP_DigestInit_ex(ctx_->ctx, sha256_method(), nullptr), "EVP_DigestInit_ex");
}

Sha256::~Sha256() = default;
Sha256::Sha256(Sha256&&) noexcept = default;
Sha256& Sha256::operator=(Sha256&&) noexcept = default;

void Sha256::update(std::string_view bytes) {
  check(EVP_DigestUpdate(ctx_->ctx, bytes.data(), bytes.size()), "EVP_DigestUpdate");
}

Sha256Digest Sha256::digest() {
  Sha256Digest out;
  unsigned int size = 0;
  check(EVP_DigestFinal_ex(ctx_->ctx, out.data(), &size), "EVP_DigestFinal_ex");
  check(size == out.size(), "digest size");
  return out;
}

std::string Sha256::hex_digest() {
  return to_hex(digest());
}

Sha256Digest sha256(std::string_view bytes) {
  Sha256 h;
  h.update(bytes);
  return h.digest();
}

std::string to_hex(const Sha256Digest& digest) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (std::uint8_t v : digest) {
    out += kHex[v >> 4];
    out += kHex[v & 0xf];
  }
  return out;
}

std::string sha256_hex(std::string_view bytes) {
  Sha256 h;
  h.update(bytes);
  return h.hex_digest();
}

std::string sha256_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot read");
  Sha256 h;
  std::vector<char> buf(1 << 20);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    h.update(std::string_view(buf.data(), static_cast<std::size_t>(in.gcount())));
  }
  return h.hex_digest();
}

}  // namespace plumekit
