#include "core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace plumekit {

void write_file_atomic(const std::filesystem::path& path, std::string_view bytes) {
  namespace fs = std::filesystem;
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(path.string() + ": output directory " + dir.string() + " does not exist");
  const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw InputError(path.string() + ": cannot write (permission or disk full?)");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(path.string() + ": cannot move the finished file into place: " + ec.message());
  }
}

AtomicDirectory::AtomicDirectory(std::filesystem::path target) : target_(std::move(target)) {
  // Unique per process and object, so parallel writers never share a temporary.
  static std::atomic<int> counter{0};
  temporary_ =
      target_.parent_path() / (target_.filename().string() + ".tmp-" + std::to_string(::getpid()) +
                               "-" + std::to_string(counter++));
  std::filesystem::remove_all(temporary_);
  std::filesystem::create_directories(temporary_);
}

AtomicDirectory::~AtomicDirectory() {
  std::error_code ec;
  if (!committed_) std::filesystem::remove_all(temporary_, ec);
}

void AtomicDirectory::commit() {
  std::filesystem::remove_all(target_);  // an incomplete or corrupt earlier copy
  std::filesystem::rename(temporary_, target_);
  committed_ = true;
}

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string() + ": no such file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(path.string() + ": cannot read");
  return text.str();
}

}  // namespace plumekit
