#pragma once
// What `plumekit map import-ros` reports: the JSON summary and the text for
// people. Both name option fields ("ros.unknown"); the CLI puts its flags in.
#include <string>

#include <nlohmann/json.hpp>

#include "map/ros_import.hpp"

namespace plumekit {

nlohmann::ordered_json ros_import_json(const RosImport& in, const std::string& yaml,
                                       const std::string& out);
// The human summary, without in.warnings: the caller prints those on stderr.
std::string ros_import_text(const RosImport& in, const std::string& out);

}  // namespace plumekit
