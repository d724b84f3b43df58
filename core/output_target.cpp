#include "core/output_target.hpp"

#include <stdio.h>  // renameat2
#include <unistd.h>
#include <zlib.h>

#include <fcntl.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
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

struct Marker {
  bool present = false, readable = false;
  std::string command;
  std::set<std::string> files;
};

Marker read_marker(const fs::path& dir) {
  Marker m;
  std::error_code ec;
  const fs::path f = dir / kOutputMarker;
  if (!fs::is_regular_file(fs::symlink_status(f, ec))) return m;
  m.present = true;
  try {
    const auto j = nlohmann::json::parse(read_file(f));
    if (j.at("format").get<std::string>() != kOutputMarkerFormat) return m;
    m.command = j.at("command").get<std::string>();
    if (j.contains("files"))
      for (const auto& name : j.at("files"))
        m.files.insert(name.get<std::string>());
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
  std::vector<std::string> foreign = other;
  for (const std::string& f : files)
    if (f != kOutputMarker && !m.files.count(f)) foreign.push_back(f);
  if (!foreign.empty())
    throw InputError(quoted(target) + ": holds the output of an earlier `" + command_name(command) +
                     "` and files it did not write (" + some_entries(foreign) +
                     "); move them away or name another folder, plumekit never deletes them");
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

void create_folders(const std::vector<fs::path>& folders, const fs::path& target) {
  for (const fs::path& f : folders) {
    std::error_code ec;
    fs::create_directory(f, ec);
    if (ec)
      throw InputError(quoted(target) + ": cannot create the folder " + quoted(f) + ": " +
                       ec.message());
  }
}

void write_marker(const fs::path& dir, const std::string& command,
                  const std::vector<std::string>* files) {
  nlohmann::ordered_json j{{"format", kOutputMarkerFormat}, {"command", command}};
  if (files) j["files"] = *files;
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

std::uint32_t be32(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
         std::uint32_t(p[3]);
}

void put_be32(std::string& s, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8)
    s.push_back(static_cast<char>((v >> shift) & 0xff));
}

const char kPngSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};

bool png_has_mark(const std::string& bytes) {
  if (bytes.size() < 8 || bytes.compare(0, 8, std::string(kPngSignature, 8)) != 0) return false;
  const std::string want = std::string(kPngKeyword) + '\0' + kPngText;
  std::size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
    const std::uint32_t length = be32(p);
    const std::string type = bytes.substr(at + 4, 4);
    if (length > bytes.size() - at - 12) return false;
    if (type == "tEXt" && bytes.compare(at + 8, length, want) == 0) return true;
    if (type == "IDAT" || type == "IEND") return false;
    at += 12 + length;
  }
  return false;
}

}  // namespace

// ---- OutputDirectory ---------------------------------------------------------

OutputDirectory::OutputDirectory(fs::path target, std::string command, std::vector<fs::path> inputs)
    : target_(std::move(target)), command_(std::move(command)) {
  check_folder_target(target_, command_, inputs);
}

OutputDirectory::~OutputDirectory() {
  if (committed_) return;
  std::error_code ec;
  if (!temporary_.empty()) {
    fs::remove_all(temporary_, ec);
    forget_temporary(temporary_);
  }
  for (auto it = created_parents_.rbegin(); it != created_parents_.rend(); ++it)
    fs::remove(*it, ec);  // only if still empty
}

const fs::path& OutputDirectory::open() {
  if (!temporary_.empty()) return temporary_;
  const fs::path abs = fs::absolute(target_);
  created_parents_ = missing_folders(abs.parent_path());
  create_folders(created_parents_, target_);
  remove_stale_temporaries(abs);
  temporary_ = make_temporary_path(abs);
  std::error_code ec;
  fs::create_directory(temporary_, ec);
  if (ec) throw InputError(quoted(target_) + ": cannot create a folder beside it: " + ec.message());
  return temporary_;
}

void OutputDirectory::commit() {
  open();
  std::vector<std::string> files, other;
  list_files(temporary_, "", files, other);
  std::sort(files.begin(), files.end());
  write_marker(temporary_, command_, &files);
  const fs::path abs = fs::absolute(target_);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(abs, ec))) {
    fs::rename(temporary_, abs, ec);
    if (ec)
      throw InputError(quoted(target_) + ": cannot move the output into place: " + ec.message());
  } else {
    // It was checked to be empty or our own output; check again (another run
    // may have written since), then swap the two folders in one step.
    check_existing_folder(abs, command_);
    if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, abs.c_str(), RENAME_EXCHANGE) != 0) {
      // File systems without the exchange: move the old folder aside first.
      const fs::path old = make_temporary_path(abs);
      fs::rename(abs, old, ec);
      if (!ec) fs::rename(temporary_, abs, ec);
      if (ec) throw InputError(quoted(target_) + ": cannot replace the folder: " + ec.message());
      fs::remove_all(old, ec);
      forget_temporary(old);
    } else {
      fs::remove_all(temporary_, ec);  // now the earlier output
    }
  }
  forget_temporary(temporary_);
  committed_ = true;
}

// ---- folders written in place -------------------------------------------------

bool claim_output_directory(const fs::path& target, const std::string& command,
                            const std::vector<std::string>& commands,
                            const std::function<bool(const std::string&)>& own_entry,
                            const std::string& legacy_mark, const std::vector<fs::path>& inputs) {
  check_placement(target, inputs);
  std::error_code ec;
  const fs::file_status s = fs::status(target, ec);
  bool existed = false;
  if (fs::exists(s)) {
    if (!fs::is_directory(s))
      throw InputError(quoted(target) +
                       ": is a file, but this output is a folder; name a new or empty folder");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(target))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    if (!names.empty()) {
      existed = true;
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
  }
  create_folders(missing_folders(fs::absolute(target)), target);
  const Marker m = read_marker(target);
  if (!m.readable) write_marker(target, command, nullptr);
  return existed;
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
  create_folders(missing_folders(abs.parent_path()), target);
  remove_stale_temporaries(abs);
  write_file_atomic(abs, bytes);
}

bool written_by_plumekit(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (png_has_mark(head)) return true;
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
  const std::string data = std::string(kPngKeyword) + '\0' + kPngText;
  std::string chunk;
  put_be32(chunk, static_cast<std::uint32_t>(data.size()));
  const std::string typed = "tEXt" + data;
  chunk += typed;
  put_be32(chunk, static_cast<std::uint32_t>(crc32(0L, reinterpret_cast<const Bytef*>(typed.data()),
                                                   static_cast<uInt>(typed.size()))));
  // After the signature (8) and the IHDR chunk (4 + 4 + 13 + 4).
  png.insert(33, chunk);
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
