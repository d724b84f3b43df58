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
  const Temporary tmp(path);
  {
    std::ofstream out(tmp.path(), std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw InputError(path.string() + ": cannot write (permission, or the disk is full?)");
  }
  fs::rename(tmp.path(), path, ec);
  if (ec)
    throw InputError(path.string() + ": cannot move the finished file into place: " + ec.message());
}

AtomicDirectory::AtomicDirectory(std::filesystem::path target)
    : target_(std::move(target)), temporary_(std::make_unique<Temporary>(target_)) {
  std::filesystem::create_directory(temporary_->path());
}

AtomicDirectory::~AtomicDirectory() = default;

const std::filesystem::path& AtomicDirectory::path() const {
  return temporary_->path();
}

void AtomicDirectory::commit() {
  std::filesystem::remove_all(target_);  // an incomplete or corrupt earlier copy of our own
  temporary_->move_to(target_);
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
