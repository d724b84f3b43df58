#pragma once
// The one output rule of every plumekit command that writes (README, "Where
// output goes"): a command writes into a path only if it does not exist, is
// empty, or holds this command's own earlier output. Anything else is an
// InputError (exit 2) naming the path and what is in it, raised before any
// work is done, so plumekit never deletes or overwrites what it did not write.
//
// - Output folders carry a marker, .plumekit-output.json, naming the command
//   and the files it wrote. A folder is this command's own earlier output when
//   its marker names the command and every file in it is one the marker lists.
// - Output files (PNG pictures, map JSON) carry their mark inside: a PNG
//   "Software" text chunk, a map's "generated_by" key. An empty file counts as
//   new.
// - The output may not be the current folder or contain it, be an input, lie
//   inside an input folder or contain an input; a file is never taken for a
//   folder, nor the reverse.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace plumekit {

inline constexpr const char* kOutputMarker = ".plumekit-output.json";
inline constexpr const char* kOutputMarkerFormat = "plumekit-output/1";

// An output folder written whole: files go into a temporary sibling, which
// replaces the target in one step on commit(). Until then the target is left
// as it was; without commit() (an error, an interrupt) the temporary and any
// parent folders it created are removed.
class OutputDirectory {
 public:
  // Checks `target` for `command` ("evaluate", "flow", ...) against the rule,
  // writing nothing. `inputs` are the files and folders the command reads.
  OutputDirectory(std::filesystem::path target, std::string command,
                  std::vector<std::filesystem::path> inputs = {});
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  // Creates the temporary folder (and missing parents); write the files here.
  const std::filesystem::path& open();
  // Writes the marker listing every file, then moves the folder into place.
  void commit();

  const std::filesystem::path& target() const { return target_; }

 private:
  std::filesystem::path target_, temporary_;
  std::string command_;
  std::vector<std::filesystem::path> created_parents_;
  bool committed_ = false;
};

// A folder written in place over a long, resumable run (dataset generate and
// merge). `own_entry` says whether a top-level name is one such a run writes;
// a folder is accepted when it is new, empty, or marked by one of `commands`
// (or unmarked, from before markers, with `legacy_mark` present) and holds only
// own entries. Creates the folder and its marker; returns whether it existed.
bool claim_output_directory(const std::filesystem::path& target, const std::string& command,
                            const std::vector<std::string>& commands,
                            const std::function<bool(const std::string&)>& own_entry,
                            const std::string& legacy_mark,
                            const std::vector<std::filesystem::path>& inputs = {});

// Checks an output file path against the rule, writing nothing.
void check_output_file(const std::filesystem::path& target,
                       const std::vector<std::filesystem::path>& inputs = {});
// Checks again, creates missing parent folders, and writes `bytes` atomically.
void write_output_file(const std::filesystem::path& target, std::string_view bytes);

// Whether a file carries plumekit's mark (see the top of this file).
bool written_by_plumekit(const std::filesystem::path& file);
// PNG bytes with a "Software: plumekit" text chunk after the header chunk.
std::string mark_png(std::string png);

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
