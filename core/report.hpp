#pragma once
// What a command reports when it finishes: the JSON summary printed with --json and the one human
// line printed without it. The libraries assemble both; apps/ only prints one of them.
#include <string>

#include <nlohmann/json.hpp>

namespace plumekit {

struct Report {
  nlohmann::ordered_json json;
  std::string text;
};

}  // namespace plumekit
