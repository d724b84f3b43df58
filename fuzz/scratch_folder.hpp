#pragma once
// The readers that take a path (a ROS map, a part folder, a wind folder) get each input as files in
// one private folder per process: in /dev/shm when there is one, to keep the disk out of it, and
// removed at exit.
#include <stdlib.h>  // mkdtemp

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

namespace plumekit::fuzz {

// The process's folder, plumekit-fuzz-TAG-XXXXXX, made on the first call (whose `tag` names it).
inline const std::filesystem::path& scratch_folder(std::string_view tag) {
  namespace fs = std::filesystem;
  static const fs::path dir = [tag] {
    std::string pattern = (fs::is_directory("/dev/shm") ? std::string("/dev/shm")
                                                        : fs::temp_directory_path().string()) +
                          "/plumekit-fuzz-" + std::string(tag) + "-XXXXXX";
    if (!mkdtemp(pattern.data())) std::abort();
    return fs::path(pattern);
  }();
  static const bool removed_at_exit = std::atexit([] {
                                        std::error_code ec;
                                        fs::remove_all(dir, ec);
                                      }) == 0;
  (void)removed_at_exit;
  return dir;
}

// `bytes` as the whole of `path`; a write that fails is the harness's fault, so it aborts.
inline void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) std::abort();
}

}  // namespace plumekit::fuzz
