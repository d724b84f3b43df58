#include "core/temporary_files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>
#include <vector>

#include "core/error.hpp"

namespace plumekit {

namespace fs = std::filesystem;

namespace {

// Never destroyed: the interrupt thread may use them while static destructors run.
struct Registry {
  std::mutex mutex;
  std::set<std::string> temporaries;
  std::map<std::string, int> locks;          // path -> flock'd descriptor
  std::vector<std::string> created_folders;  // outermost first
};
Registry& registry() {
  static Registry* r = new Registry;
  return *r;
}

bool process_alive(long pid) {
  if (pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

void write_stderr(const char* text) {
  const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

// The marker's whole text for the temporary folder `folder_name`.
std::string marker_text(const std::string& folder_name) {
  return "plumekit-temporary/1\n" + folder_name + "\n";
}

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Whether `entry` in `dir` is a stale temporary of plumekit (see the header).
bool is_stale_temporary(const fs::path& entry) {
  const std::string name = entry.filename().string();
  const std::size_t at = name.rfind(kTemporaryTag);
  if (at == std::string::npos || at == 0) return false;
  const std::string target = name.substr(0, at),
                    rest = name.substr(at + std::strlen(kTemporaryTag));
  // <pid>-<n>, both decimal
  const std::size_t dash = rest.find('-');
  if (dash == std::string::npos || dash == 0 || dash + 1 == rest.size() || dash > 9) return false;
  if (rest.find_first_not_of("0123456789-") != std::string::npos ||
      rest.find('-', dash + 1) != std::string::npos)
    return false;
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(entry, ec))) return false;
  const long pid = std::stol(rest.substr(0, dash));
  if (pid == ::getpid() || process_alive(pid)) return false;
  const fs::path marker = entry / kTemporaryMarker;
  if (!fs::is_regular_file(fs::symlink_status(marker, ec))) return false;
  if (file_text(marker) != marker_text(name)) return false;
  for (fs::directory_iterator it(entry, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string inside = it->path().filename().string();
    if (inside != kTemporaryMarker && inside != target) return false;
  }
  return !ec;
}

int remove_stale_where(const fs::path& dir, const std::string& prefix) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) == 0 && is_stale_temporary(it->path()))
      stale.push_back(it->path());
  }
  int removed = 0;
  for (const fs::path& p : stale) {
    std::error_code rm;
    fs::remove_all(p, rm);
    if (!rm) ++removed;
  }
  return removed;
}

fs::path target_file(const fs::path& target) {
  return target.has_filename() ? target : target.parent_path();
}

}  // namespace

Temporary::Temporary(const fs::path& target) {
  static std::atomic<long> counter{0};
  const fs::path t = target_file(target);
  const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
  Registry& r = registry();
  // Held while the folder and its marker appear: an interrupt removes both or neither.
  std::lock_guard<std::mutex> lock(r.mutex);  // blocks for good once an interrupt is handled
  // A name taken (by a stale temporary of an earlier process with this pid, or
  // by anyone's folder) is skipped, never reused.
  for (int attempt = 0;; ++attempt) {
    const std::string name = t.filename().string() + kTemporaryTag + std::to_string(::getpid()) +
                             "-" + std::to_string(counter++);
    const fs::path folder = dir / name;
    std::error_code ec;
    if (!fs::create_directory(folder, ec)) {
      if ((!ec || ec == std::errc::file_exists) && attempt < 1000) continue;  // taken
      throw InputError(t.string() + ": cannot create a temporary folder beside it: " +
                       (ec ? ec.message() : std::string("every name is taken")));
    }
    std::ofstream out(folder / kTemporaryMarker, std::ios::binary);
    out << marker_text(name);
    out.close();
    if (!out) {
      fs::remove_all(folder, ec);
      throw InputError(t.string() + ": cannot write beside it (permission, or the disk is full?)");
    }
    r.temporaries.insert(folder.string());
    folder_ = folder;
    path_ = folder / t.filename();
    return;
  }
}

Temporary::~Temporary() {
  std::error_code ec;
  fs::remove_all(folder_, ec);
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.temporaries.erase(folder_.string());
}

void Temporary::move_to(const fs::path& target) const {
  fs::rename(path_, target_file(target));
}

int remove_stale_temporaries(const fs::path& target) {
  const fs::path t = target_file(target);
  const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
  return remove_stale_where(dir, t.filename().string() + kTemporaryTag);
}

int remove_stale_temporaries_in(const fs::path& dir) {
  return remove_stale_where(dir, "");
}

void register_lock(const fs::path& lock_file, int fd) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.locks[lock_file.string()] = fd;
}

void forget_lock(const fs::path& lock_file) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.locks.erase(lock_file.string());
}

void register_created_folder(const fs::path& folder) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.created_folders.push_back(folder.string());
}

void forget_created_folder(const fs::path& folder) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto& v = r.created_folders;
  v.erase(std::remove(v.begin(), v.end(), folder.string()), v.end());
}

namespace {

int interrupt_pipe[2] = {-1, -1};

// Runs on whichever thread the kernel picks (OpenBLAS starts its threads
// before main, so no signal mask can steer it): only hand the signal on.
void on_signal(int sig) {
  const unsigned char byte = static_cast<unsigned char>(sig);
  const ssize_t ignored = ::write(interrupt_pipe[1], &byte, 1);
  (void)ignored;
}

// Undoes what the registry records; the caller holds its mutex.
void clean_up(Registry& r) {
  std::error_code ec;
  for (const std::string& p : r.temporaries)
    fs::remove_all(p, ec);
  // A lock another run shares (dataset parts) stays for it.
  for (const auto& [path, fd] : r.locks) {
    if (fd >= 0) {
      if (::flock(fd, LOCK_EX | LOCK_NB) == 0) ::unlink(path.c_str());
      continue;
    }
    // Being made: ours to remove only while nobody holds it and it is a lock file.
    const int own = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (own < 0) continue;
    char buf[32];
    const ssize_t n = ::pread(own, buf, sizeof buf, 0);
    if (::flock(own, LOCK_EX | LOCK_NB) == 0 && n > 0 &&
        std::string(buf, static_cast<std::size_t>(n)) == kLockFileText)
      ::unlink(path.c_str());
    ::close(own);
  }
  for (auto it = r.created_folders.rbegin(); it != r.created_folders.rend(); ++it)
    fs::remove(*it, ec);  // only if empty
}

}  // namespace

void install_interrupt_cleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (::pipe(interrupt_pipe) != 0) return;
    std::thread([] {
      unsigned char sig = 0;
      while (::read(interrupt_pipe[0], &sig, 1) != 1) {
      }
      Registry& r = registry();
      r.mutex.lock();  // held until exit: no new temporary can appear
      clean_up(r);
      write_stderr(sig == SIGINT ? "\nplumekit: interrupted; temporary files removed\n"
                                 : "plumekit: stopped by a signal; temporary files removed\n");
      ::_exit(128 + sig);
    }).detach();
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      ::sigaction(sig, nullptr, &old);
      if (old.sa_handler == SIG_IGN) continue;  // nohup, or a background job's SIGINT
      struct sigaction action {};
      action.sa_handler = on_signal;
      sigemptyset(&action.sa_mask);
      ::sigaction(sig, &action, nullptr);
    }
  });
}

}  // namespace plumekit
