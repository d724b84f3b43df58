#pragma once
// Temporary files and folders that plumekit writes before moving them into
// place, and what it must undo when a run stops early.
//
// Every temporary is a folder "<target name>.plumekit-tmp-<pid>-<n>" beside
// the target, created empty (never reused) and holding, from its creation, the
// marker file ".plumekit-temporary" whose text names the folder. What is being
// written (a file or a folder) is "<temporary>/<target name>", which commit
// renames onto the target: the same parent file system, so one atomic step.
// The marker never reaches the target.
//
// - Ctrl-C (SIGINT), SIGTERM and SIGHUP remove every registered temporary,
//   release the output locks (output_target.hpp) and remove the folders a run
//   created for its output if they are empty again (install_interrupt_cleanup).
// - A temporary left by a run killed outright (SIGKILL, power loss) is removed
//   by the next run that writes beside it (remove_stale_temporaries), but only
//   when all of these hold, so that a user's folder is never taken for one by
//   its name: it is a folder (not a link), its process is gone, it holds the
//   marker with exactly the text plumekit writes for that name, and nothing
//   but the marker and "<target name>".
#include <filesystem>
#include <string>

namespace plumekit {

inline constexpr const char* kTemporaryTag = ".plumekit-tmp-";
inline constexpr const char* kTemporaryMarker = ".plumekit-temporary";

// A fresh marked temporary folder beside `target`, registered for removal on
// an interrupt; removed with whatever it still holds when destroyed.
class Temporary {
 public:
  explicit Temporary(const std::filesystem::path& target);
  ~Temporary();
  Temporary(const Temporary&) = delete;
  Temporary& operator=(const Temporary&) = delete;

  // Where to write: "<folder>/<target name>" (not created).
  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& folder() const { return folder_; }
  // Renames path() onto `target` (replacing a file, or an empty folder).
  void move_to(const std::filesystem::path& target) const;

 private:
  std::filesystem::path folder_, path_;
};

// Removes the stale temporaries (see above) of `target` beside it; returns how many.
int remove_stale_temporaries(const std::filesystem::path& target);
// Removes the stale temporaries of any target in `dir`; returns how many.
int remove_stale_temporaries_in(const std::filesystem::path& dir);

// The whole text of an output lock file (core/output_target.hpp).
inline constexpr const char* kLockFileText = "plumekit-lock/1\n";
// An output lock (an open, flock'd file descriptor and its path): on an
// interrupt it is removed if no other process holds it too. Registered with
// fd -1 before the file is created, it is removed on an interrupt if it holds
// kLockFileText and nobody holds it (an interrupt while it is being made).
void register_lock(const std::filesystem::path& lock_file, int fd);
void forget_lock(const std::filesystem::path& lock_file);
// A folder a run created for its output: removed on an interrupt if empty.
// Register parents before the folders inside them.
void register_created_folder(const std::filesystem::path& folder);
void forget_created_folder(const std::filesystem::path& folder);

// Handles SIGINT, SIGTERM and SIGHUP (those not ignored): a thread removes
// every registered temporary and exits with 128 + the signal number. Call
// once from main().
void install_interrupt_cleanup();

}  // namespace plumekit
