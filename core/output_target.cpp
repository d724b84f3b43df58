#include "core/output_target.hpp"

#include <stdio.h>  // renameat2
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fcntl.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/sha256.hpp"
#include "core/temporary_files.hpp"

namespace plumekit {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPngKeyword = "Software";
constexpr const char* kPngText = "plumekit";

// Absolute, with symbolic links and "." / ".." resolved as far as the path exists.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

// Whether `inner` is `outer` or lies inside it (both resolved).
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin(), o = outer.begin();
  for (; o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

std::string quoted(const fs::path& p) {
  return p.string();
}

// The rule's checks that do not depend on what the target is.
void check_placement(const fs::path& target, const std::vector<fs::path>& inputs) {
  if (target.empty()) throw InputError("the output path is empty");
  const fs::path t = resolved(target);
  const fs::path cwd = resolved(fs::current_path());
  if (within(cwd, t))
    throw InputError(
        quoted(target) + ": is " +
        (t == cwd ? std::string("the current folder") : "a folder holding the current folder") +
        "; name a new or empty folder for the output");
  for (const fs::path& input : inputs) {
    if (input.empty()) continue;
    const fs::path in = resolved(input);
    if (t == in)
      throw InputError(quoted(target) + ": is also an input of this command (" + quoted(input) +
                       "); name another output");
    if (within(t, in))
      throw InputError(quoted(target) + ": lies inside the input " + quoted(input) +
                       "; name an output outside it");
    if (within(in, t))
      throw InputError(quoted(target) + ": holds the input " + quoted(input) +
                       "; name an output that does not contain the inputs");
  }
  // The nearest existing ancestor must be a folder we may write in.
  fs::path parent = t.parent_path();
  std::error_code ec;
  while (!parent.empty() && !fs::exists(fs::symlink_status(parent, ec)) &&
         parent != parent.root_path())
    parent = parent.parent_path();
  if (parent.empty()) parent = t.root_path();
  if (!fs::is_directory(parent, ec))
    throw InputError(quoted(target) + ": cannot be created, since " + quoted(parent) +
                     " is a file, not a folder");
  if (::access(parent.c_str(), W_OK | X_OK) != 0)
    throw InputError(quoted(target) + ": cannot write in " + quoted(parent) +
                     " (permission denied); choose another place");
}

// The first few names of a list, for messages.
std::string some_entries(const std::vector<std::string>& names) {
  std::string s;
  const std::size_t shown = std::min<std::size_t>(names.size(), 3);
  for (std::size_t i = 0; i < shown; ++i)
    s += (i ? ", " : "") + names[i];
  if (names.size() > shown) s += " and " + std::to_string(names.size() - shown) + " more";
  return s;
}

// A file as the marker records it; `bound` is false for an older marker's bare name.
struct MarkedFile {
  bool bound = false;
  std::uintmax_t size = 0;
  std::string sha256;
};

struct Marker {
  bool present = false, readable = false;
  std::string command;
  std::map<std::string, MarkedFile> files;
};

constexpr const char* kOldMarkerFormat = "plumekit-output/1";

Marker read_marker(const fs::path& dir) {
  Marker m;
  std::error_code ec;
  const fs::path f = dir / kOutputMarker;
  if (!fs::is_regular_file(fs::symlink_status(f, ec))) return m;
  m.present = true;
  try {
    const auto j = nlohmann::json::parse(read_file(f));
    const std::string format = j.at("format").get<std::string>();
    if (format != kOutputMarkerFormat && format != kOldMarkerFormat) return m;
    m.command = j.at("command").get<std::string>();
    if (j.contains("files"))
      for (const auto& e : j.at("files")) {
        if (e.is_string()) {
          m.files[e.get<std::string>()] = MarkedFile{};
          continue;
        }
        m.files[e.at("path").get<std::string>()] = {true, e.at("size").get<std::uintmax_t>(),
                                                    e.at("sha256").get<std::string>()};
      }
    m.readable = true;
  } catch (const std::exception&) {
  }
  return m;
}

// The regular files under `dir`, relative, with '/' separators; anything that is
// not a regular file or a folder (a link, a socket) is reported as foreign.
void list_files(const fs::path& dir, const fs::path& rel, std::vector<std::string>& files,
                std::vector<std::string>& other) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const fs::path r = rel / e.path().filename();
    const fs::file_status s = e.symlink_status();
    if (fs::is_directory(s))
      list_files(e.path(), r, files, other);
    else if (fs::is_regular_file(s))
      files.push_back(r.generic_string());
    else
      other.push_back(r.generic_string());
  }
}

std::string command_name(const std::string& command) {
  return "plumekit " + command;
}

// Throws unless `dir` (an existing folder) is empty or this command's own output.
void drop_nested_outputs(const fs::path& target, const std::string& command,
                         std::vector<std::string>& files);
void check_marked_files(const fs::path& target, const Marker& m,
                        const std::vector<std::string>& files,
                        const std::vector<std::string>& other);

void check_existing_folder(const fs::path& target, const std::string& command) {
  std::vector<std::string> files, other;
  list_files(target, "", files, other);
  if (files.empty() && other.empty()) return;
  const Marker m = read_marker(target);
  if (!m.present || !m.readable) {
    std::vector<std::string> all = other;
    all.insert(all.end(), files.begin(), files.end());
    std::sort(all.begin(), all.end());
    throw InputError(quoted(target) + ": holds files plumekit did not write (" + some_entries(all) +
                     "); name a new or empty folder, plumekit never deletes them");
  }
  if (m.command != command)
    throw InputError(quoted(target) + ": holds the output of `" + command_name(m.command) +
                     "`, not of `" + command_name(command) + "`; name another folder");
  std::sort(files.begin(), files.end());
  drop_nested_outputs(target, command, files);
  check_marked_files(target, m, files, other);
}

// Removes from `files` those of nested outputs of `command` (evaluate --method
// a,b: a folder per method, each with its own marker, which may be rewritten
// alone), after checking each of those as an output folder of its own.
void drop_nested_outputs(const fs::path& target, const std::string& command,
                         std::vector<std::string>& files) {
  const std::string suffix = std::string("/") + kOutputMarker;
  std::vector<std::string> nested;
  for (const std::string& f : files)
    if (f.size() > suffix.size() && f.compare(f.size() - suffix.size(), suffix.size(), suffix) == 0)
      if (const std::string sub = f.substr(0, f.size() - suffix.size() + 1);
          read_marker(target / sub).command == command &&
          std::none_of(nested.begin(), nested.end(),
                       [&](const std::string& n) { return sub.rfind(n, 0) == 0; }))
        nested.push_back(sub);  // sorted: an outer folder comes before those inside it
  for (const std::string& sub : nested)
    check_existing_folder(target / sub, command);
  files.erase(std::remove_if(files.begin(), files.end(),
                             [&](const std::string& f) {
                               return std::any_of(
                                   nested.begin(), nested.end(),
                                   [&](const std::string& n) { return f.rfind(n, 0) == 0; });
                             }),
              files.end());
}

// Throws unless every file but the marker is listed by `m` with its size and SHA-256.
void check_marked_files(const fs::path& target, const Marker& m,
                        const std::vector<std::string>& files,
                        const std::vector<std::string>& other) {
  std::vector<std::string> foreign = other;
  for (const std::string& f : files)
    if (f != kOutputMarker && !m.files.count(f)) foreign.push_back(f);
  if (!foreign.empty())
    throw InputError(quoted(target) + ": holds the output of an earlier `" +
                     command_name(m.command) + "` and files it did not write (" +
                     some_entries(foreign) +
                     "); move them away or name another folder, plumekit never deletes them");
  for (const std::string& f : files) {
    if (f == kOutputMarker) continue;
    const MarkedFile& mf = m.files.at(f);
    if (!mf.bound)
      throw InputError(quoted(target) + ": its " + kOutputMarker +
                       " is an older plumekit's, which lists " + f +
                       " without its SHA-256, so nothing proves plumekit wrote it; plumekit never "
                       "deletes such files: delete the folder yourself or name another folder");
    std::error_code ec;
    const fs::path p = target / f;
    if (fs::file_size(p, ec) != mf.size || ec || sha256_file(p) != mf.sha256)
      throw InputError(quoted(target) + ": " + f +
                       " is not the file plumekit wrote there (its size or SHA-256 differs from " +
                       kOutputMarker +
                       "); plumekit never deletes a file it cannot prove it wrote: move it away "
                       "or name another folder");
  }
}

void check_folder_target(const fs::path& target, const std::string& command,
                         const std::vector<fs::path>& inputs) {
  check_placement(target, inputs);
  std::error_code ec;
  const fs::file_status s = fs::status(target, ec);
  if (!fs::exists(s)) return;
  if (!fs::is_directory(s))
    throw InputError(quoted(target) +
                     ": is a file, but this output is a folder; name a new or empty folder");
  check_existing_folder(target, command);
}

// Missing folders of `dir`, outermost first.
std::vector<fs::path> missing_folders(const fs::path& dir) {
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(fs::symlink_status(p, ec));
       p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.root_path() || p.parent_path() == p) break;
  }
  std::reverse(missing.begin(), missing.end());
  return missing;
}

// Removes the folders of `folders` (outermost first) that are empty, and forgets them.
void remove_created_folders(const std::vector<fs::path>& folders) {
  for (auto it = folders.rbegin(); it != folders.rend(); ++it) {
    std::error_code ec;
    fs::remove(*it, ec);  // only if still empty
    forget_created_folder(*it);
  }
}

// Creates `folders` (outermost first), each registered for removal on an interrupt.
void create_folders(const std::vector<fs::path>& folders, const fs::path& target) {
  for (std::size_t i = 0; i < folders.size(); ++i) {
    std::error_code ec;
    fs::create_directory(folders[i], ec);
    if (ec) {
      remove_created_folders({folders.begin(), folders.begin() + static_cast<long>(i)});
      throw InputError(quoted(target) + ": cannot create the folder " + quoted(folders[i]) + ": " +
                       ec.message());
    }
    register_created_folder(folders[i]);
  }
}

void forget_created_folders(const std::vector<fs::path>& folders) {
  for (const fs::path& f : folders)
    forget_created_folder(f);
}

// The marker of a folder written whole binds each file by size and SHA-256;
// one written in place (files == nullptr) lists none.
void write_marker(const fs::path& dir, const std::string& command,
                  const std::vector<std::string>* files) {
  nlohmann::ordered_json j{{"format", kOutputMarkerFormat}, {"command", command}};
  if (files) {
    j["files"] = nlohmann::ordered_json::array();
    for (const std::string& f : *files)
      j["files"].push_back(
          {{"path", f}, {"size", fs::file_size(dir / f)}, {"sha256", sha256_file(dir / f)}});
  }
  write_file_atomic(dir / kOutputMarker, j.dump(2) + "\n");
}

bool same_file_kind_or_new(const fs::path& target) {
  std::error_code ec;
  const fs::file_status s = fs::status(target, ec);
  if (!fs::exists(s)) return true;
  if (fs::is_directory(s))
    throw InputError(quoted(target) + ": is a folder, but this output is a file; name a file");
  if (!fs::is_regular_file(s))
    throw InputError(quoted(target) + ": is not a regular file; name another output file");
  return false;
}

const char kPngSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};

bool png_has_mark(const std::string& bytes) {
  if (bytes.size() < 8 || bytes.compare(0, 8, std::string(kPngSignature, 8)) != 0) return false;
  const std::string want = plumekit_mark();
  std::size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const std::uint32_t length = get_be32(bytes, at);
    const std::string type = bytes.substr(at + 4, 4);
    if (length > bytes.size() - at - 12) return false;
    if (type == "tEXt" && bytes.compare(at + 8, length, want) == 0) return true;
    if (type == "IDAT" || type == "IEND") return false;
    at += 12 + length;
  }
  return false;
}

}  // namespace

// ---- OutputLock ----------------------------------------------------------------

namespace {

fs::path lock_file_of(const fs::path& target) {
  const fs::path t = fs::absolute(target).lexically_normal();
  const fs::path file = t.has_filename() ? t : t.parent_path();
  return file.parent_path() / (file.filename().string() + kOutputLockTag);
}

// Puts the lock file in place whole (written beside it, then linked: never seen
// empty); does nothing if one appeared meanwhile.
void create_lock_file(const fs::path& file) {
  const Temporary tmp(file);
  write_file_atomic(tmp.path(), kLockFileText);
  if (::link(tmp.path().c_str(), file.c_str()) == 0 || errno == EEXIST) return;
  // A file system without hard links: create and fill it (then briefly empty).
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return;  // exists by now, or fails again when opened
  const ssize_t n = ::write(fd, kLockFileText, std::strlen(kLockFileText));
  (void)n;
  ::close(fd);
}

std::string read_fd(int fd) {
  char buf[64];
  const ssize_t n = ::pread(fd, buf, sizeof buf, 0);
  return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
}

bool same_file(int fd, const fs::path& file) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::lstat(file.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

}  // namespace

OutputLock::OutputLock(const fs::path& target, bool shared) : file_(lock_file_of(target)) {
  // Registered before it may be created, so that an interrupt while it is made removes it too.
  register_lock(file_, -1);
  try {
    acquire(target, shared);
  } catch (...) {
    forget_lock(file_);
    throw;
  }
}

void OutputLock::acquire(const fs::path& target, bool shared) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int fd = ::open(file_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0 && errno == ENOENT) {
      create_lock_file(file_);
      continue;
    }
    if (fd < 0)
      throw InputError(quoted(target) + ": cannot open its lock file " + quoted(file_) + ": " +
                       std::strerror(errno) + "; if it is yours, move it away");
    if (::flock(fd, (shared ? LOCK_SH : LOCK_EX) | LOCK_NB) != 0) {
      ::close(fd);
      throw InputError(quoted(target) + ": another plumekit run is writing it (it holds " +
                       quoted(file_) + "); wait for that run to end, or name another output");
    }
    if (!same_file(fd, file_)) {  // removed by the run that held it before: lock the new one
      ::close(fd);
      continue;
    }
    struct stat st {};
    const std::string text = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) ? read_fd(fd) : "?";
    if (text == kLockFileText) {
      fd_ = fd;
      register_lock(file_, fd_);
      return;
    }
    ::close(fd);
    if (text.empty() && attempt < 100) {  // being filled (no hard links)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }
    break;
  }
  throw InputError(quoted(file_) + ": exists beside the output " + quoted(target) +
                   " and was not written by plumekit; move it away (plumekit never deletes it)");
}

OutputLock::OutputLock(OutputLock&& other) noexcept
    : file_(std::move(other.file_)), fd_(other.fd_) {
  other.fd_ = -1;
}

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    release();
    file_ = std::move(other.file_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

void OutputLock::release() {
  if (fd_ < 0) return;
  forget_lock(file_);
  // Removed only when no other run shares it, and only while it is the file we locked.
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0 && same_file(fd_, file_)) ::unlink(file_.c_str());
  ::close(fd_);
  fd_ = -1;
}

// ---- OutputDirectory ---------------------------------------------------------

OutputDirectory::OutputDirectory(fs::path target, std::string command, std::vector<fs::path> inputs)
    : target_(std::move(target)), command_(std::move(command)) {
  check_placement(target_, inputs);
  // The lock file goes beside the target: its parent must exist first.
  created_parents_ = missing_folders(fs::absolute(target_).parent_path());
  create_folders(created_parents_, target_);
  try {
    lock_ = OutputLock(target_);
    check_folder_target(target_, command_, {});
  } catch (...) {
    lock_.release();
    remove_created_folders(created_parents_);
    throw;
  }
}

OutputDirectory::~OutputDirectory() {
  if (committed_) return;
  temporary_.reset();
  lock_.release();
  remove_created_folders(created_parents_);
}

const fs::path& OutputDirectory::open() {
  if (temporary_) return temporary_->path();
  const fs::path abs = fs::absolute(target_);
  remove_stale_temporaries(abs);
  temporary_ = std::make_unique<Temporary>(abs);
  std::error_code ec;
  fs::create_directory(temporary_->path(), ec);
  if (ec) throw InputError(quoted(target_) + ": cannot create a folder beside it: " + ec.message());
  return temporary_->path();
}

void OutputDirectory::commit() {
  const fs::path& written = open();
  std::vector<std::string> files, other;
  list_files(written, "", files, other);
  std::sort(files.begin(), files.end());
  write_marker(written, command_, &files);
  const fs::path abs = fs::absolute(target_);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(abs, ec))) {
    fs::rename(written, abs, ec);
    if (ec)
      throw InputError(quoted(target_) + ": cannot move the output into place: " + ec.message());
  } else {
    // It was checked to be empty or our own output; check again (it may have
    // changed by hand since), then swap the two folders in one step.
    check_existing_folder(abs, command_);
    if (::renameat2(AT_FDCWD, written.c_str(), AT_FDCWD, abs.c_str(), RENAME_EXCHANGE) != 0) {
      // File systems without the exchange: move the old folder aside first.
      const Temporary old(abs);
      fs::rename(abs, old.path(), ec);
      if (!ec) fs::rename(written, abs, ec);
      if (ec) throw InputError(quoted(target_) + ": cannot replace the folder: " + ec.message());
    }
  }
  temporary_.reset();  // now empty, or the earlier output
  lock_.release();
  forget_created_folders(created_parents_);
  committed_ = true;
}

// ---- folders written in place -------------------------------------------------

namespace {

// Throws unless the existing folder `target` may be written in place (see the header).
void check_claimed_folder(const fs::path& target, const std::string& command,
                          const std::vector<std::string>& commands,
                          const std::function<bool(const std::string&)>& own_entry,
                          const std::string& legacy_mark, const std::vector<std::string>& names) {
  std::error_code ec;
  const Marker m = read_marker(target);
  const bool legacy = !m.present && fs::is_regular_file(target / legacy_mark, ec);
  if (!legacy && !(m.readable && std::count(commands.begin(), commands.end(), m.command))) {
    if (m.readable)
      throw InputError(quoted(target) + ": holds the output of `" + command_name(m.command) +
                       "`, not of `" + command_name(command) + "`; name another folder");
    throw InputError(quoted(target) + ": holds files plumekit did not write (" +
                     some_entries(names) +
                     "); name a new or empty folder, plumekit never deletes them");
  }
  std::vector<std::string> foreign;
  for (const std::string& n : names)
    if (n != kOutputMarker && !own_entry(n)) foreign.push_back(n);
  if (!foreign.empty())
    throw InputError(quoted(target) + ": holds files `" + command_name(command) +
                     "` did not write (" + some_entries(foreign) +
                     "); move them away or name another folder");
}

}  // namespace

OutputClaim claim_output_directory(const fs::path& target, const std::string& command,
                                   const std::vector<std::string>& commands,
                                   const std::function<bool(const std::string&)>& own_entry,
                                   const std::string& legacy_mark,
                                   const std::vector<fs::path>& inputs) {
  check_placement(target, inputs);
  const std::vector<fs::path> parents = missing_folders(fs::absolute(target).parent_path());
  create_folders(parents, target);
  forget_created_folders(parents);  // they hold the output from now on
  OutputClaim claim{false, OutputLock(target, true)};
  std::error_code ec;
  const fs::file_status s = fs::status(target, ec);
  if (fs::exists(s)) {
    if (!fs::is_directory(s))
      throw InputError(quoted(target) +
                       ": is a file, but this output is a folder; name a new or empty folder");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(target))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    if (!names.empty()) {
      claim.existed = true;
      check_claimed_folder(target, command, commands, own_entry, legacy_mark, names);
    }
  }
  create_folders(missing_folders(fs::absolute(target)), target);
  forget_created_folders({fs::absolute(target)});
  const Marker m = read_marker(target);
  if (!m.readable) write_marker(target, command, nullptr);
  return claim;
}

// ---- output files ----------------------------------------------------------------

void check_output_file(const fs::path& target, const std::vector<fs::path>& inputs) {
  check_placement(target, inputs);
  if (same_file_kind_or_new(target)) return;
  std::error_code ec;
  if (fs::file_size(target, ec) == 0 && !ec) return;
  if (!written_by_plumekit(target))
    throw InputError(quoted(target) +
                     ": exists and was not written by plumekit; name a new file, plumekit never "
                     "overwrites it");
}

void write_output_file(const fs::path& target, std::string_view bytes) {
  check_output_file(target);
  const fs::path abs = fs::absolute(target);
  const std::vector<fs::path> parents = missing_folders(abs.parent_path());
  create_folders(parents, target);
  forget_created_folders(parents);
  const OutputLock lock(abs);
  check_output_file(target);  // another run may have written it meanwhile
  remove_stale_temporaries(abs);
  write_file_atomic(abs, bytes);
}

std::string plumekit_mark() {
  return std::string(kPngKeyword) + '\0' + kPngText;
}

namespace {

// Whether an MP4 file (an "ftyp" box first) has a top-level "free" box holding plumekit_mark().
bool mp4_has_mark(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string mark = plumekit_mark();
  const auto end = static_cast<std::uint64_t>(fs::file_size(file));
  std::uint64_t at = 0;
  for (int box = 0; at + 8 <= end && box < 100000; ++box) {
    unsigned char head[16];
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(reinterpret_cast<char*>(head), 8)) return false;
    std::uint64_t size =
        (std::uint64_t{head[0]} << 24) | (head[1] << 16) | (head[2] << 8) | head[3];
    const std::string type(reinterpret_cast<char*>(head) + 4, 4);
    if (box == 0 && type != "ftyp") return false;
    std::uint64_t header = 8;
    if (size == 1) {  // a 64-bit size follows
      if (!in.read(reinterpret_cast<char*>(head + 8), 8)) return false;
      size = 0;
      for (int k = 8; k < 16; ++k)
        size = (size << 8) | head[k];
      header = 16;
    } else if (size == 0) {
      size = end - at;  // to the end of the file
    }
    if (size < header || at + size > end) return false;
    if (type == "free" && size - header == mark.size()) {
      std::string payload(mark.size(), '\0');
      if (in.read(payload.data(), static_cast<std::streamsize>(payload.size())) && payload == mark)
        return true;
    }
    at += size;
  }
  return false;
}

}  // namespace

bool written_by_plumekit(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (png_has_mark(head)) return true;
  if (head.size() >= 8 && head.compare(4, 4, "ftyp") == 0) return mp4_has_mark(file);
  // A JSON document (a map) whose top-level "generated_by" names plumekit.
  const std::size_t first = head.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || head[first] != '{') return false;
  try {
    const auto j = nlohmann::json::parse(read_file(file));
    return j.is_object() && j.contains("generated_by") && j["generated_by"].is_string() &&
           j["generated_by"].get<std::string>().rfind("plumekit", 0) == 0;
  } catch (const std::exception&) {
    return false;
  }
}

std::string mark_png(std::string png) {
  if (png.size() < 33 || png.compare(0, 8, std::string(kPngSignature, 8)) != 0) return png;
  // After the signature (8) and the IHDR chunk (4 + 4 + 13 + 4).
  png.insert(33, png_chunk("tEXt", plumekit_mark()));
  return png;
}

std::string provenance_path(const fs::path& input) {
  if (input.empty()) return "";
  const fs::path in = resolved(input), cwd = resolved(fs::current_path());
  if (within(in, cwd)) return in.lexically_relative(cwd).generic_string();
  return in.filename().empty() ? in.parent_path().filename().string() : in.filename().string();
}

std::string safe_file_name(const std::string& text, std::vector<std::string>& taken) {
  std::string s;
  for (unsigned char c : text) {
    if (s.size() >= 80) break;
    // A '.' only after a plain character: no leading dot, no "..".
    const bool plain = std::isalnum(c) || c == '-' || c == '_';
    const bool dot_ok = c == '.' && !s.empty() && s.back() != '.' && s.back() != '_';
    s.push_back(plain || dot_ok ? static_cast<char>(c) : '_');
  }
  if (s.empty()) s = "unnamed";
  std::string name = s;
  for (int k = 2; std::count(taken.begin(), taken.end(), name); ++k)
    name = s + "-" + std::to_string(k);
  taken.push_back(name);
  return name;
}

}  // namespace plumekit
