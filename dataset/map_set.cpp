#include "dataset/map_set.hpp"

#include <cstdio>
#include <map>
#include <sstream>

#include "core/option_check.hpp"
#include "dataset/option_tables.hpp"
#include "map/map_json.hpp"

namespace plumekit::dataset {

const OptionTable<MapSetOptions>& map_set_option_table() {
  using O = MapSetOptions;
  static const OptionTable<O> table{
      "Map sets (dataset::MapSetOptions, `maps random`)",
      {{"maps.count", "--count,-n", &O::count, count_range(1, 1'000'000), "Number of maps"},
       {"maps.sources", "--sources", &O::sources, count_range(0, 1'000'000),
        "Random sources to store in each map"}}};
  return table;
}

void MapSetOptions::validate() const {
  plumekit::validate(map_set_option_table(), *this);
  map.validate();
}

std::vector<RandomMap> random_map_set(const MapSetOptions& o) {
  o.validate();
  std::vector<RandomMap> maps;
  for (int i = 0; i < o.count; ++i) {
    maps.push_back(random_map(o.map, o.seed, i));
    maps.back().map.sources =
        random_sources(maps.back().map, o.sources, o.source_clearance, o.seed, i);
  }
  return maps;
}

Report write_map_set(const std::filesystem::path& dir, const std::string& out,
                     const MapSetOptions& o, std::vector<RandomMap>& maps) {
  std::map<std::string, int> families;
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < maps.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "map-%05zu.json", i);
    maps[i].map.generated_by = "plumekit maps random";
    write_map(maps[i].map, dir / name);
    ++families[maps[i].family];
    files.push_back({{"file", name}, {"family", maps[i].family}});
  }
  Report r;
  r.json = {{"ok", true}, {"out", out}, {"seed", o.seed}, {"maps", files}};
  std::ostringstream text;
  text << "wrote " << maps.size() << " maps to " << out << ":";
  for (const auto& [f, n] : families)
    text << " " << n << " " << f;
  r.text = text.str();
  return r;
}

}  // namespace plumekit::dataset
