#pragma once
// Reads the published reference tables in tests/data/reference (copied from
// the project's shared reference set: '#' comment lines, a header, numbers).
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace plumekit::test {

using Table = std::map<std::string, std::vector<double>>;

inline Table read_reference(const std::string& name) {
  std::ifstream in(std::string(PLUMEKIT_TEST_DATA) + "/reference/" + name);
  Table table;
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream s(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(s, cell, ','))
      cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    for (std::size_t k = 0; k < cells.size() && k < header.size(); ++k)
      table[header[k]].push_back(std::stod(cells[k]));
  }
  return table;
}

}  // namespace plumekit::test
