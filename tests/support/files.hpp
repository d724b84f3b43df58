#pragma once
// Small file helpers for tests that check what a command left on disk.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace plumekit::test {

inline std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Writes `bytes` to `p`, creating its parent folders.
inline void put_file(const std::filesystem::path& p, const std::string& bytes) {
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

// Every entry under `dir` with its bytes ("<dir>" for folders), to compare a
// folder before and after a command byte for byte.
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    files[std::filesystem::relative(e.path(), dir).string()] =
        e.is_regular_file() ? file_bytes(e.path()) : std::string("<dir>");
  return files;
}

}  // namespace plumekit::test
