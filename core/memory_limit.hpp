#pragma once
// The process-wide memory limit, and the guard that big allocations pass
// first. Notes on core's safety rules (core has no README):
//
// - Limit: by default half the machine's physical memory (sysconf), so that
//   one plumekit run cannot push the machine into swap or the OOM killer; 4 GiB
//   where the physical memory is unknown. The environment variable
//   PLUMEKIT_MAX_MEMORY ("4G", "512M", "1e9") replaces the default; the CLI's
//   memory flag calls set_memory_limit(), which replaces both.
// - Guard: before each big allocation the code estimates its peak (flow grid
//   and sparse LU, filaments, rasterized grids, rendered images, imported ROS
//   maps) and calls check_memory(), which throws MemoryLimitError (an
//   InputError: exit 2) naming what, the estimate, the limit and a setting
//   that would fit. The estimates are upper bounds calibrated on measured peak
//   RSS (docs/design/flow-solver.md, docs/design/dataset.md); they exist to refuse runs that
//   would take many gigabytes in seconds, not to account for every byte.
// - Options: every options struct has validate(), which checks each field
//   (core/option_check.hpp) and throws OptionError naming the field's dotted
//   name ("flow.cell"); library messages never name a CLI flag.
// - map validation of huge arenas: map_grid_check() (map/rasterize.hpp)
//   coarsens its grid so that it never holds more than a bounded number of
//   cells, and says which cell size it used.
#include <string>

#include "core/error.hpp"

namespace plumekit {

// A planned allocation above the memory limit.
class MemoryLimitError : public InputError {
 public:
  MemoryLimitError(const std::string& message, double needed, double limit)
      : InputError(message), needed_(needed), limit_(limit) {}
  double needed_bytes() const { return needed_; }
  double limit_bytes() const { return limit_; }

 private:
  double needed_, limit_;
};

// Physical memory of the machine in bytes, 0 when unknown.
double physical_memory_bytes();
// Half the physical memory (4 GiB if unknown), or PLUMEKIT_MAX_MEMORY when set.
// InputError naming the variable when it does not parse.
double default_memory_limit();
// The limit in force: set_memory_limit()'s value, else the default.
double memory_limit();
// Sets the limit for this process (thread-safe). OptionError("memory.limit")
// unless it is finite and at least 1 MiB.
void set_memory_limit(double bytes);

// Bytes from "4G", "4GB", "4GiB", "512M", "100k", "1e9", "2.5T" (K/M/G/T are
// powers of 1024; a plain number is bytes). OptionError naming `field`
// otherwise, or when it is not positive and finite.
double parse_memory_size(const std::string& text, const std::string& field = "memory.limit");

// "1.5 GiB", "88 MiB", "512 B": for messages.
std::string format_bytes(double bytes);
// The smallest whole size in the parse_memory_size() syntax that holds
// `bytes`: "15G", "700M". What to suggest as a new limit.
std::string suggest_limit(double bytes);

bool fits_in_memory(double bytes);
// Throws MemoryLimitError when `bytes` exceeds the limit:
// "WHAT needs about 14.2 GiB of memory, more than the limit of 11.7 GiB; FIX,
// or raise the memory limit to at least 15G". `fix` names the setting that
// would fit, by its field name (e.g. "use a larger flow.cell: 0.12 m fits").
void check_memory(double bytes, const std::string& what, const std::string& fix);

}  // namespace plumekit
