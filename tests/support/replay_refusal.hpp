#pragma once
// The replay tests' refusals (tests/run/replay_test.cpp, tunnel_replay_test.cpp): what
// read_replay says of a folder, and what it says once one piece of the folder's replay.json is
// replaced.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "run/replay.hpp"

namespace plumekit::run {

// The message of read_replay's refusal of `dir`, or "(accepted)".
inline std::string replay_refusal(const std::filesystem::path& dir) {
  try {
    read_replay(dir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// The refusal of `dir` once its replay.json is `json` with the first `from` replaced by `to`.
inline std::string replay_refusal_with(const std::filesystem::path& dir, const std::string& json,
                                       const std::string& from, const std::string& to) {
  std::string j = json;
  const std::size_t at = j.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) j.replace(at, from.size(), to);
  write_file_atomic(dir / kReplayFile, j);
  return replay_refusal(dir);
}

}  // namespace plumekit::run
