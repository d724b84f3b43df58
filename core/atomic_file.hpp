#pragma once
// Output files appear whole or not at all: bytes go to a temporary file in the
// same directory, which is renamed over the target only once fully written.
#include <filesystem>
#include <memory>
#include <string_view>

namespace plumekit {

class Temporary;

void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

// A directory whose files appear all at once: they are written into a fresh
// temporary sibling (path()), which replaces `target` on commit(). If never
// committed (an exception, an interrupt), the temporary is removed. For a
// folder inside plumekit's own output (a dataset's shard); a folder the user
// names goes through OutputDirectory (output_target.hpp), which never removes
// what plumekit did not write.
class AtomicDirectory {
 public:
  explicit AtomicDirectory(std::filesystem::path target);
  ~AtomicDirectory();
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;

  const std::filesystem::path& path() const;
  void commit();

 private:
  std::filesystem::path target_;
  std::unique_ptr<Temporary> temporary_;
};

// Whole file as a string; InputError naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace plumekit
