#include "core/temporary_files.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>
#include <thread>

namespace plumekit {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTag = ".plumekit-tmp-";

// Never destroyed: the interrupt thread may use them while static destructors run.
struct Registry {
  std::mutex mutex;
  std::set<std::string> paths;
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

}  // namespace

fs::path make_temporary_path(const fs::path& target) {
  static std::atomic<long> counter{0};
  const fs::path t = target.has_filename() ? target : target.parent_path();
  fs::path tmp = t.parent_path() / (t.filename().string() + kTag + std::to_string(::getpid()) +
                                    "-" + std::to_string(counter++));
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);  // blocks for good once an interrupt is handled
  r.paths.insert(tmp.string());
  return tmp;
}

void forget_temporary(const fs::path& temporary) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.paths.erase(temporary.string());
}

int remove_stale_temporaries(const fs::path& target) {
  const fs::path t = target.has_filename() ? target : target.parent_path();
  const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
  const std::string prefix = t.filename().string() + kTag;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return 0;
  int removed = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    // <pid>-<n>, both decimal
    const std::string rest = name.substr(prefix.size());
    const std::size_t dash = rest.find('-');
    if (dash == std::string::npos || dash == 0) continue;
    if (rest.find_first_not_of("0123456789-") != std::string::npos) continue;
    if (process_alive(std::stol(rest.substr(0, dash)))) continue;
    std::error_code rm;
    fs::remove_all(it->path(), rm);
    if (!rm) ++removed;
  }
  return removed;
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
      for (const std::string& p : r.paths) {
        std::error_code ec;
        fs::remove_all(p, ec);
      }
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
