#pragma once
// Running OpenFOAM's programs on a case, and reading simpleFoam's log.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace plumekit::cfd {

// The full path of `name` on $PATH, or "" when it is not there.
std::string find_program(const std::string& name);

// Runs program args[0] (found on $PATH) with args[1...] and `-case DIR` in
// the case folder, output to DIR/log.<log_name>. The environment gets
// WM_PROJECT_DIR=/usr/share/openfoam (Debian's programs need it) and lets
// Open MPI run as root. Returns the wall seconds; InputError with the log's
// tail when the program fails or cannot start.
double run_foam_program(const std::vector<std::string>& args, const std::filesystem::path& dir,
                        const std::string& log_name);

// What simpleFoam's log says.
struct SimpleFoamLog {
  int processes = 1;                        // "nProcs : N" (parallel runs print it)
  int iterations = 0;                       // the last "Time = N"
  bool converged = false;                   // "SIMPLE solution converged"
  bool diverged = false;                    // a residual is nan or inf
  std::map<std::string, double> residuals;  // the last initial residual per equation
};
SimpleFoamLog parse_simplefoam_log(const std::string& text);

// The last `lines` lines of a file ("" if unreadable).
std::string file_tail(const std::filesystem::path& file, int lines);

}  // namespace plumekit::cfd
