#pragma once
// A solved wind as Python holds it: the field, the map it belongs to, and its reports.
#include <memory>

#include <nlohmann/json.hpp>

#include "cfd/wind_field.hpp"
#include "map/map.hpp"

namespace plumekit::python {

struct Wind {
  std::shared_ptr<const Map> map;
  cfd::WindField field;
  nlohmann::ordered_json summary;       // flow_report_json: what `flow --json` prints
  nlohmann::ordered_json file_summary;  // wind.json's summary when saved
};

}  // namespace plumekit::python
