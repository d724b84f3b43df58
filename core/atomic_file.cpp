#include "core/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/temporary_files.hpp"

namespace plumekit {

void write_file_atomic(const std::filesystem::path& path, std::string_view bytes) {
  namespace fs = std::filesystem;
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(path.string() + ": output folder " + dir.string() + " does not exist");
  if (fs::is_directory(path, ec))
    throw InputError(path.string() + ": is a folder, but this output is a file; name a file");
  const fs::path tmp = make_temporary_path(path);
  struct Forget {
    const fs::path& p;
    ~Forget() { forget_temporary(p); }
  } forget{tmp};
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw InputError(path.string() + ": cannot write (permission, or the disk is full?)");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw InputError(path.string() + ": cannot move the finished file into place: " + why);
  }
}

AtomicDirectory::AtomicDirectory(std::filesystem::path target)
    : target_(std::move(target)), temporary_(make_temporary_path(target_)) {
  std::filesystem::remove_all(temporary_);
  std::filesystem::create_directories(temporary_);
}

AtomicDirectory::~AtomicDirectory() {
  std::error_code ec;
  if (!committed_) std::filesystem::remove_all(temporary_, ec);
  forget_temporary(temporary_);
}

void AtomicDirectory::commit() {
  std::filesystem::remove_all(target_);  // an incomplete or corrupt earlier copy of our own
  std::filesystem::rename(temporary_, target_);
  committed_ = true;
}

std::string read_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string() + ": is a folder, expected a file");
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string() + ": no such file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(path.string() + ": cannot read");
  return text.str();
}

}  // namespace plumekit
