#pragma once
// Temporary files and folders that plumekit writes before moving them into
// place. Every temporary is named "<target name>.plumekit-tmp-<pid>-<n>" and
// registered while it exists, so that
// - Ctrl-C (SIGINT), SIGTERM and SIGHUP remove them before the process exits
//   (install_interrupt_cleanup, called once by the program before any thread);
// - a temporary left by a run that was killed outright (SIGKILL, power loss)
//   is recognised by its dead process id and removed by the next run that
//   writes the same target (remove_stale_temporaries).
// Nothing else is ever removed: the pattern and a dead owner are both required.
#include <filesystem>
#include <string>

namespace plumekit {

// A fresh temporary path beside `target`, registered for removal on an interrupt.
std::filesystem::path make_temporary_path(const std::filesystem::path& target);
// The temporary is gone (renamed into place or removed): forget it.
void forget_temporary(const std::filesystem::path& temporary);

// Removes "<target name>.plumekit-tmp-<pid>-<n>" siblings of `target` whose
// process no longer runs. Returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& target);

// Handles SIGINT, SIGTERM and SIGHUP (those not ignored): a thread removes
// every registered temporary and exits with 128 + the signal number. Call
// once from main().
void install_interrupt_cleanup();

}  // namespace plumekit
