#pragma once
// The one output rule of every plumekit command that writes (docs/commands.md, "Where
// output goes"): a command writes into a path only if it does not exist, is
// empty, or holds this command's own earlier output. Anything else is an
// InputError (exit 2) naming the path and what is in it, raised before any
// work is done, so plumekit never deletes or overwrites what it did not write.
//
// - Output folders carry a marker, .plumekit-output.json, naming the command
//   and each file it wrote with its size and SHA-256. A folder is this
//   command's own earlier output when its marker names the command and every
//   file in it is one the marker lists, with that size and SHA-256: a marker
//   copied or edited to list a user's file does not make it plumekit's. A
//   marker of an older plumekit lists names only (format plumekit-output/1);
//   a folder holding files under such a marker is refused, since nothing proves
//   plumekit wrote them (delete it by hand once).
// - One run at a time writes an output: the file "<output>.plumekit-lock"
//   beside it is flock'd for the run (OutputLock); another run wanting the
//   same output meanwhile fails at once. Folders written in place (datasets)
//   take it shared, since the parts of a split run may write one folder at once.
// - Output files (PNG pictures, map JSON, videos) carry their mark inside: a
//   PNG "Software" text chunk, a map's "generated_by" key, an MP4's top-level
//   "free" box holding plumekit_mark() (players skip it). An empty file counts as
//   new.
// - The output may not be the current folder or contain it, be an input, lie
//   inside an input folder or contain an input; a file is never taken for a
//   folder, nor the reverse.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/temporary_files.hpp"

namespace plumekit {

inline constexpr const char* kOutputMarker = ".plumekit-output.json";
inline constexpr const char* kOutputMarkerFormat = "plumekit-output/2";
inline constexpr const char* kOutputLockTag = ".plumekit-lock";

// The lock of one output (see above). The lock file holds plumekit's text
// only; a file of that name holding anything else is someone else's: refused
// (InputError), never removed. Released (and its file removed, unless another
// run shares it) on release() or destruction; an interrupt does the same.
class OutputLock {
 public:
  OutputLock() = default;
  explicit OutputLock(const std::filesystem::path& target, bool shared = false);
  ~OutputLock() { release(); }
  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  void release();

 private:
  void acquire(const std::filesystem::path& target, bool shared);

  std::filesystem::path file_;
  int fd_ = -1;
};

// An output folder written whole: files go into a temporary sibling, which
// replaces the target in one step on commit(). Until then the target is left
// as it was; without commit() (an error, an interrupt) the temporary and any
// parent folders it created are removed. A folder made of several outputs
// (evaluate --method a,b) is one OutputDirectory whose open() folder holds an
// OutputDirectory per part, each committed before the whole.
class OutputDirectory {
 public:
  // Checks `target` for `command` ("evaluate", "flow", ...) against the rule
  // and locks it (OutputLock), creating only missing parent folders (removed
  // again without commit()). `inputs` are the files and folders the command reads.
  OutputDirectory(std::filesystem::path target, std::string command,
                  std::vector<std::filesystem::path> inputs = {});
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Creates the temporary folder (and missing parents); write the files here.
  const std::filesystem::path& open();
  // Writes the marker listing every file, moves the folder into place and
  // releases the lock.
  void commit();

  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_;
  std::string command_;
  std::vector<std::filesystem::path> created_parents_;
  OutputLock lock_;
  std::unique_ptr<Temporary> temporary_;
  bool committed_ = false;
};

// A folder written in place over a long, resumable run (dataset generate and
// merge). `own_entry` says whether a top-level name is one such a run writes;
// a folder is accepted when it is new, empty, or marked by one of `commands`
// (or unmarked, from before markers, with `legacy_mark` present) and holds only
// own entries. Its marker lists no files: the run changes them as it goes, and
// it removes only its own temporaries (temporary_files.hpp) and the entries it
// verifies by their own checksums. Creates the folder and its marker; returns
// whether it existed, and the lock, shared, to hold for the run.
struct OutputClaim {
  bool existed = false;
  OutputLock lock;
};
OutputClaim claim_output_directory(const std::filesystem::path& target, const std::string& command,
                                   const std::vector<std::string>& commands,
                                   const std::function<bool(const std::string&)>& own_entry,
                                   const std::string& legacy_mark,
                                   const std::vector<std::filesystem::path>& inputs = {});

// Checks an output file path against the rule, writing nothing.
void check_output_file(const std::filesystem::path& target,
                       const std::vector<std::filesystem::path>& inputs = {});
// Creates missing parent folders, then under the output's lock checks again and
// writes `bytes` atomically.
void write_output_file(const std::filesystem::path& target, std::string_view bytes);

// Whether a file carries plumekit's mark (see the top of this file).
bool written_by_plumekit(const std::filesystem::path& file);
// PNG bytes with a "Software: plumekit" text chunk after the header chunk.
std::string mark_png(std::string png);
// The mark's text, "Software\0plumekit": a PNG's tEXt chunk holds it, and the "free" box that
// marks an MP4 plumekit wrote (core/animation.cpp).
std::string plumekit_mark();

// How an input is named in a file plumekit writes (provenance): relative to
// the current folder when inside it, else its last component, so that no
// output records an absolute path of the machine that made it.
std::string provenance_path(const std::filesystem::path& input);

// A file name made from text that came from a file (a map's name): letters,
// digits, '-', '_' and '.' kept, anything else '_', no leading '.', at most 80
// characters, never empty. Names already in `taken` get "-2", "-3", ...; the
// result is added to `taken`.
std::string safe_file_name(const std::string& text, std::vector<std::string>& taken);

}  // namespace plumekit
