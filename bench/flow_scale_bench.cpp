// Flow speed and memory at building scale (issue 16): each map solved at one
// cell size by the flow policy (cfd::solve_wind, as `plumekit flow` solves it)
// on one core. Every solve runs in a forked child, so its peak resident memory
// is its own (wait4's ru_maxrss), and its wall time is the solve's alone.
// Prints, per map: the cells, the median wall time over the repeats, the peak
// memory, Newton's counts, and the ratio of the median to the baseline's (the
// first map, a 10 x 4 m arena), all measured in the same run. Repeats go
// round the maps in turn, so every map sees the same machine state.
//
//   ./build/bench/flow_scale_bench [--repeats 3] [--cell 0.05] [MAP.json ...]
//
// Without maps: data/maps/cluttered-1.json (the baseline), then
// bench/maps/tb3_world.json (bench/maps/README.md). Maps given on the command
// line: the first is the baseline. Issue 16's targets: tb3_world <= 3 s,
// <= 500 MB and <= 12x the baseline; depot <= 5 s and <= 1 GB; warehouse
// (about 600k cells) <= 30 s and <= 4 GB.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "cfd/flow_policy.hpp"
#include "core/statistics.hpp"
#include "map/map_json.hpp"

namespace {

// What a child reports through its pipe.
struct Solve {
  double seconds = 0.0;  // the solve's wall time
  int nx = 0, ny = 0, iterations = 0, factorizations = 0;
  bool ok = false;
  char linear_solver[16] = {};
};

struct Measured {
  Solve solve;
  double peak_mb = 0.0;  // the child's peak resident memory
};

Solve solve_here(const std::string& path, double cell) {
  Solve s;
  try {
    const plumekit::Map map = plumekit::read_map(path);
    plumekit::cfd::FlowOptions options;
    options.cell = cell;
    const auto t = std::chrono::steady_clock::now();
    const plumekit::cfd::WindResult w = plumekit::cfd::solve_wind(map, options);
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    s.nx = w.flow.summary.nx;
    s.ny = w.flow.summary.ny;
    s.iterations = w.flow.summary.iterations;
    s.factorizations = w.flow.summary.factorizations;
    std::snprintf(s.linear_solver, sizeof s.linear_solver, "%s",
                  w.flow.summary.linear_solver.c_str());
    s.ok = true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
  }
  return s;
}

// One solve in a forked child: its report and its own peak memory.
Measured measure(const std::string& path, double cell) {
  int fds[2];
  if (pipe(fds) != 0) std::abort();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const Solve s = solve_here(path, cell);
    const ssize_t written = write(fds[1], &s, sizeof s);
    _exit(written == sizeof s ? 0 : 1);
  }
  close(fds[1]);
  Measured m;
  const ssize_t got = read(fds[0], &m.solve, sizeof m.solve);
  close(fds[0]);
  int status = 0;
  rusage ru{};
  wait4(pid, &status, 0, &ru);
  if (got != sizeof m.solve) m.solve.ok = false;
  m.peak_mb = ru.ru_maxrss / 1024.0;
  return m;
}

std::string stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return name.substr(0, name.rfind('.'));
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 3;
  double cell = 0.05;
  std::vector<std::string> maps;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--repeats") && k + 1 < argc)
      repeats = std::max(1, std::atoi(argv[++k]));
    else if (!std::strcmp(argv[k], "--cell") && k + 1 < argc)
      cell = std::atof(argv[++k]);
    else
      maps.push_back(argv[k]);
  }
  if (maps.empty())
    for (const char* m : {"data/maps/cluttered-1.json", "bench/maps/tb3_world.json"})
      maps.push_back(std::string(PLUMEKIT_SOURCE_DIR) + "/" + m);
  std::vector<std::vector<Measured>> runs(maps.size());
  for (int r = 0; r < repeats; ++r)
    for (std::size_t m = 0; m < maps.size(); ++m) {
      runs[m].push_back(measure(maps[m], cell));
      const Measured& x = runs[m].back();
      std::printf("  repeat %d %-14s %7.2f s %7.0f MB%s\n", r + 1, stem(maps[m]).c_str(),
                  x.solve.seconds, x.peak_mb, x.solve.ok ? "" : "  FAILED");
      std::fflush(stdout);
    }
  std::printf("cell %g m, %d repeat(s), medians; ratio: median time over the baseline's (%s)\n",
              cell, repeats, stem(maps[0]).c_str());
  std::printf("%-14s %11s %9s %9s %7s %6s %6s %s\n", "map", "grid", "cells", "time", "ratio",
              "peak", "iters", "factorizations, solver");
  double baseline = 0.0;
  for (std::size_t m = 0; m < maps.size(); ++m) {
    std::vector<double> seconds, peak;
    for (const Measured& x : runs[m]) {
      seconds.push_back(x.solve.seconds);
      peak.push_back(x.peak_mb);
    }
    const Solve& s = runs[m].back().solve;
    const double t = plumekit::median(seconds);
    if (m == 0) baseline = t;
    const std::string grid = std::to_string(s.nx) + " x " + std::to_string(s.ny);
    std::printf("%-14s %11s %9d %7.2f s %6.1fx %4.0f MB %6d %6d, %s\n", stem(maps[m]).c_str(),
                grid.c_str(), s.nx * s.ny, t, baseline > 0.0 ? t / baseline : 0.0,
                plumekit::median(peak), s.iterations, s.factorizations, s.linear_solver);
  }
  return 0;
}
