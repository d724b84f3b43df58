#pragma once
// Errors that cross module boundaries. The CLI maps them to exit codes:
// InputError -> 2 (the user's input is wrong), anything else -> 1 (our fault).
#include <stdexcept>
#include <string>

namespace plumekit {

// The input (a file, a flag, a value in a file) is wrong. The message names the
// file, the key and the fault, so the user knows what to change.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace plumekit
