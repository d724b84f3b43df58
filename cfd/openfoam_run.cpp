#include "cfd/openfoam_run.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

extern char** environ;

namespace plumekit::cfd {

namespace fs = std::filesystem;

namespace {

// The child's environment: ours, with OpenFOAM's and Open MPI's settings.
std::vector<std::string> foam_environment(const fs::path& dir) {
  const std::map<std::string, std::string> set = {
      {"WM_PROJECT_DIR", "/usr/share/openfoam"},
      {"OMPI_ALLOW_RUN_AS_ROOT", "1"},
      {"OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"},
      // Containers often forbid the cross-memory attach Open MPI's shared
      // memory transport tries first.
      {"OMPI_MCA_btl_vader_single_copy_mechanism", "none"},
      {"PWD", dir.string()},  // else OpenFOAM warns that PWD is not the working folder
  };
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string entry = *e;
    if (!set.count(entry.substr(0, entry.find('=')))) env.push_back(entry);
  }
  for (const auto& [key, value] : set)
    env.push_back(key + "=" + value);
  return env;
}

std::vector<char*> c_strings(std::vector<std::string>& v) {
  std::vector<char*> out;
  for (std::string& s : v)
    out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

// fork + exec with everything prepared before the fork (only async-signal-
// safe calls in the child). Returns the wait status.
int spawn_and_wait(const std::string& path, std::vector<std::string> args,
                   std::vector<std::string> env, const fs::path& dir, const fs::path& log) {
  std::vector<char*> argv = c_strings(args), envp = c_strings(env);
  const std::string dir_s = dir.string(), log_s = log.string();
  const pid_t pid = fork();
  if (pid < 0) throw InputError(std::string("cannot start ") + path + ": " + std::strerror(errno));
  if (pid == 0) {
    const int fd = open(log_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || chdir(dir_s.c_str()) != 0) _exit(127);
    dup2(fd, 1);
    dup2(fd, 2);
    const int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, 0);
    execve(path.c_str(), argv.data(), envp.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw InputError("waiting for " + path + ": " + std::strerror(errno));
  }
  return status;
}

}  // namespace

std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string d;
  while (std::getline(dirs, d, ':')) {
    const fs::path candidate = fs::path(d.empty() ? "." : d) / name;
    if (access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate))
      return candidate.string();
  }
  return "";
}

std::string file_tail(const fs::path& file, int lines) {
  std::ifstream in(file);
  std::deque<std::string> last;
  std::string line;
  while (std::getline(in, line)) {
    last.push_back(line);
    if (static_cast<int>(last.size()) > lines) last.pop_front();
  }
  std::string out;
  for (const std::string& l : last)
    out += "  " + l + "\n";
  return out;
}

double run_foam_program(const std::vector<std::string>& args, const fs::path& dir,
                        const std::string& log_name) {
  const std::string path = find_program(args[0]);
  if (path.empty())
    throw InputError(args[0] +
                     " is not on PATH: install Debian's openfoam package (and "
                     "openmpi-bin for flow.ranks > 1): scripts/install-deps.sh");
  std::vector<std::string> argv = args;
  argv.insert(argv.end(), {"-case", dir.string()});
  const fs::path log = dir / ("log." + log_name);
  const auto t0 = std::chrono::steady_clock::now();
  const int status = spawn_and_wait(path, argv, foam_environment(dir), dir, log);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                              : "signal " + std::to_string(WTERMSIG(status));
    std::string command;
    for (const std::string& a : args)
      command += (command.empty() ? "" : " ") + a;
    throw InputError("OpenFOAM's `" + command + "` failed (" + how + "); the end of its log:\n" +
                     file_tail(log, 15));
  }
  return seconds;
}

SimpleFoamLog parse_simplefoam_log(const std::string& text) {
  SimpleFoamLog log;
  std::istringstream in(text);
  std::string line;
  const std::string solving = "Solving for ", initial = "Initial residual = ";
  while (std::getline(in, line)) {
    if (line.rfind("nProcs : ", 0) == 0) {
      log.processes = std::atoi(line.c_str() + 9);
    } else if (line.rfind("Time = ", 0) == 0) {
      log.iterations = std::atoi(line.c_str() + 7);
    } else if (line.find("SIMPLE solution converged") != std::string::npos) {
      log.converged = true;
    } else if (const auto s = line.find(solving); s != std::string::npos) {
      const auto comma = line.find(',', s);
      const auto r = line.find(initial, s);
      if (comma == std::string::npos || r == std::string::npos) continue;
      const double value = std::strtod(line.c_str() + r + initial.size(), nullptr);
      log.residuals[line.substr(s + solving.size(), comma - s - solving.size())] = value;
      if (!std::isfinite(value)) log.diverged = true;
    }
  }
  return log;
}

}  // namespace plumekit::cfd
