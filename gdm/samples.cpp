#include "gdm/samples.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace plumekit::gdm {

namespace {

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string f;
  while (std::getline(in, f, ',')) {
    const auto first = f.find_first_not_of(" \t\r"), last = f.find_last_not_of(" \t\r");
    fields.push_back(first == std::string::npos ? "" : f.substr(first, last - first + 1));
  }
  if (!line.empty() && line.back() == ',') fields.push_back("");
  return fields;
}

// A finite number, or InputError naming where.
double number(const std::string& text, const std::string& where) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw InputError(where + ": '" + text + "' is not a finite number");
  return v;
}

// The column of each field the header names.
std::map<std::string, std::size_t> header_columns(const std::string& line,
                                                  const std::string& where) {
  std::map<std::string, std::size_t> col;
  const std::vector<std::string> names = split_commas(line);
  for (std::size_t c = 0; c < names.size(); ++c)
    col[names[c]] = c;
  for (const char* need : {"x", "y", "reading"})
    if (!col.count(need))
      throw InputError(where + ": the header names no '" + need +
                       "' column (expected x,y,reading[,u,v])");
  if (col.count("u") != col.count("v"))
    throw InputError(where + ": the header names only one of 'u' and 'v'; give both or neither");
  return col;
}

}  // namespace

std::vector<Sample> parse_samples_csv(std::string_view text, const std::string& name,
                                      const Map& map) {
  std::istringstream in{std::string(text)};
  std::string line;
  std::map<std::string, std::size_t> col;
  std::vector<Sample> samples;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
    const std::string where = name + ":" + std::to_string(line_no);
    if (col.empty()) {
      col = header_columns(line, where);
      continue;
    }
    const std::vector<std::string> f = split_commas(line);
    const auto field = [&](const char* key) {
      const std::size_t c = col.at(key);
      if (c >= f.size()) throw InputError(where + ": no value in column '" + key + "'");
      return number(f[c], where + ", column '" + key + "'");
    };
    Sample s;
    s.position = map.from_frame({field("x"), field("y")});
    s.reading = field("reading");
    if (col.count("u")) s.wind = Vec2{field("u"), field("v")};
    samples.push_back(s);
  }
  if (col.empty()) throw InputError(name + ": no header line (expected x,y,reading[,u,v])");
  if (samples.empty()) throw InputError(name + ": no samples after the header");
  return samples;
}

std::vector<Sample> read_samples_csv(const std::filesystem::path& file, const Map& map) {
  return parse_samples_csv(read_file(file), file.string(), map);
}

std::vector<Sample> read_run_samples(const std::filesystem::path& file, const Map& map) {
  const std::string name = file.string();
  nlohmann::json run;
  try {
    run = nlohmann::json::parse(read_file(file));
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(name + ": not JSON (" + e.what() + ")");
  }
  if (!run.is_object() || !run.contains("steps") || !run["steps"].is_array())
    throw InputError(name + ": no \"steps\" list (a `plumekit localize --out` run.json?)");
  std::vector<Sample> samples;
  const auto& steps = run["steps"];
  for (std::size_t n = 0; n < steps.size(); ++n) {
    const std::string where = name + ": steps[" + std::to_string(n) + "]";
    try {
      const auto& s = steps[n];
      const auto& p = s.at("recorded_position");
      const auto& w = s.at("wind");
      Sample out;
      out.position = map.from_frame({p.at(0).get<double>(), p.at(1).get<double>()});
      out.reading = s.at("value").get<double>();
      out.wind = Vec2{w.at(0).get<double>(), w.at(1).get<double>()};
      if (!std::isfinite(out.position.x) || !std::isfinite(out.position.y) ||
          !std::isfinite(out.reading) || !std::isfinite(out.wind->x) || !std::isfinite(out.wind->y))
        throw InputError(where + ": not finite");
      samples.push_back(out);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(where + ": needs recorded_position [x, y], value and wind [u, v] (" +
                       e.what() + ")");
    }
  }
  if (samples.empty()) throw InputError(name + ": \"steps\" is empty");
  return samples;
}

}  // namespace plumekit::gdm
