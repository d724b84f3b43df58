#pragma once
// The map reader's refusals, for the map format tests: the message a text
// gets, and a check that it names the file, the key and the fault.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "map/map_json.hpp"

namespace plumekit::test {

// The InputError message for parsing `text` as "bad.json", or "" if it parsed.
inline std::string map_error_of(const std::string& text) {
  try {
    parse_map(text, "bad.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

inline void expect_map_rejected(const std::string& text, const std::string& key,
                                const std::string& fault) {
  const std::string msg = map_error_of(text);
  ASSERT_FALSE(msg.empty()) << "accepted: " << text;
  EXPECT_EQ(msg.rfind("bad.json: ", 0), 0u) << msg;
  EXPECT_NE(msg.find(key), std::string::npos) << "key '" << key << "' not named in: " << msg;
  EXPECT_NE(msg.find(fault), std::string::npos) << "fault '" << fault << "' not named in: " << msg;
}

}  // namespace plumekit::test
