#pragma once
// Errors that cross module boundaries. The CLI maps them to exit codes:
// InputError -> 2 (the user's input is wrong), anything else -> 1 (our fault).
#include <stdexcept>
#include <string>
#include <utility>

namespace plumekit {

// The input (a file, a flag, a value in a file) is wrong. The message names the
// file, the key and the fault, so the user knows what to change.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An options field holds a value outside its allowed range. `field` is the
// option's dotted name in the library ("flow.cell", "plume.release_rate"); the
// message says the allowed range and the value. The CLI prints the flag bound
// to the field in place of the field's name, so library code never names a flag.
class OptionError : public InputError {
 public:
  OptionError(std::string field, const std::string& message)
      : InputError(field + ": " + message), field_(std::move(field)), message_(message) {}
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }  // without the field's name

 private:
  std::string field_;
  std::string message_;
};

}  // namespace plumekit
