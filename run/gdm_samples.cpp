#include "run/gdm_samples.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace plumekit::run {

namespace fs = std::filesystem;

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

std::string lower(std::string text) {
  for (char& c : text)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// The column of each field the header names, in any case ("X", "Reading").
std::map<std::string, std::size_t> header_columns(const std::string& line,
                                                  const std::string& where) {
  std::map<std::string, std::size_t> col;
  const std::vector<std::string> names = split_commas(line);
  for (std::size_t c = 0; c < names.size(); ++c) {
    const std::string name = lower(names[c]);
    if (col.count(name) && !name.empty())
      throw InputError(where + ": the header names '" + name + "' twice (columns " +
                       std::to_string(col[name] + 1) + " and " + std::to_string(c + 1) + ")");
    col[name] = c;
  }
  for (const char* need : {"x", "y", "reading"})
    if (!col.count(need))
      throw InputError(where + ": the header names no '" + need +
                       "' column (expected x,y,reading[,u,v]; it reads '" + line + "')");
  if (col.count("u") != col.count("v"))
    throw InputError(where + ": the header names only one of 'u' and 'v'; give both or neither");
  return col;
}

}  // namespace

std::vector<methods::Sample> parse_samples_csv(std::string_view text, const std::string& name,
                                               const Map& map) {
  // A byte order mark, as spreadsheet programs write before UTF-8 text.
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  std::istringstream in{std::string(text)};
  std::string line;
  std::map<std::string, std::size_t> col;
  std::vector<methods::Sample> samples;
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
    methods::Sample s;
    s.position = map.from_frame({field("x"), field("y")});
    s.reading = field("reading");
    if (col.count("u")) s.wind = Vec2{field("u"), field("v")};
    if (const methods::SampleFault fault = methods::sample_fault(map, s); !fault.column.empty())
      throw InputError(where + ", column '" + fault.column + "': " + fault.reason);
    samples.push_back(s);
  }
  if (col.empty()) throw InputError(name + ": no header line (expected x,y,reading[,u,v])");
  if (samples.empty()) throw InputError(name + ": no samples after the header");
  return samples;
}

std::vector<methods::Sample> read_samples_csv(const std::filesystem::path& file, const Map& map) {
  return parse_samples_csv(read_file(file), file.string(), map);
}

nlohmann::json parse_run_json(std::string_view text, const std::string& name) {
  nlohmann::json run;
  try {
    run = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // a parse error, or a number beyond a double
    throw InputError(name + ": not JSON (" + e.what() + ")");
  }
  if (!run.is_object())
    throw InputError(name + ": not a JSON object (a `plumekit localize --out` run.json?)");
  return run;
}

fs::path find_run_map(const nlohmann::json& run, const fs::path& run_file,
                      const std::vector<fs::path>& shipped) {
  const std::string name = run_file.string();
  const auto map = run.find("map");
  if (map == run.end() || !map->is_string() || map->get<std::string>().empty())
    throw InputError(name +
                     ": records no map; give the map the run was made on: plumekit gdm MAP --run " +
                     name);
  const fs::path recorded = map->get<std::string>();
  std::vector<fs::path> tried{recorded};
  if (recorded.is_relative()) {
    std::error_code ec;
    for (fs::path dir = fs::absolute(run_file, ec).parent_path(); !ec && !dir.empty();
         dir = dir.parent_path()) {
      tried.push_back(dir / recorded);
      if (dir == dir.root_path()) break;
    }
    if (!recorded.has_parent_path())
      for (const fs::path& dir : shipped)
        tried.push_back(dir / recorded);
  }
  for (const fs::path& p : tried) {
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return p;
  }
  std::string places;
  for (std::size_t k = 0; k < tried.size(); ++k)
    places += (k ? ", " : "") + tried[k].string();
  throw InputError(name + ": the run's map '" + recorded.string() +
                   "' is not a file here (looked for " + places +
                   "); give the map the run was made on: plumekit gdm MAP --run " + name);
}

namespace {

// One step's sample; `where` names it.
methods::Sample step_sample(const nlohmann::json& step, const std::string& where, const Map& map) {
  methods::Sample out;
  try {
    const auto& p = step.at("recorded_position");
    const auto& w = step.at("wind");
    if (p.size() != 2 || w.size() != 2)
      throw InputError(where + ": recorded_position and wind need two numbers each");
    out.position = map.from_frame({p.at(0).get<double>(), p.at(1).get<double>()});
    out.reading = step.at("value").get<double>();
    out.wind = Vec2{w.at(0).get<double>(), w.at(1).get<double>()};
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where + ": needs recorded_position [x, y], value and wind [u, v] (" +
                     e.what() + ")");
  }
  // The run's fields of sample_fault's columns.
  static const std::map<std::string, std::string> field{{"x", "recorded_position[0]"},
                                                        {"y", "recorded_position[1]"},
                                                        {"reading", "value"},
                                                        {"u", "wind[0]"},
                                                        {"v", "wind[1]"}};
  if (const methods::SampleFault f = methods::sample_fault(map, out); !f.column.empty())
    throw InputError(where + ", " + field.at(f.column) + ": " + f.reason);
  return out;
}

// The samples of one "steps" list; `where` names it.
void add_steps(const nlohmann::json& steps, const std::string& where, const Map& map,
               std::vector<methods::Sample>& samples) {
  if (!steps.is_array()) throw InputError(where + ": not a list of steps");
  for (std::size_t n = 0; n < steps.size(); ++n)
    samples.push_back(step_sample(steps[n], where + "[" + std::to_string(n) + "]", map));
}

}  // namespace

std::vector<methods::Sample> run_samples(const nlohmann::json& run, const std::string& name,
                                         const Map& map) {
  std::vector<methods::Sample> samples;
  // A team's top-level steps are those of the robot whose estimate it declared: the members'
  // lists hold every robot's.
  if (const auto team = run.find("team"); team != run.end()) {
    const auto members = team->find("members");
    if (!team->is_object() || members == team->end() || !members->is_array() || members->empty())
      throw InputError(name + ": \"team\" has no \"members\" list");
    for (std::size_t k = 0; k < members->size(); ++k) {
      const std::string where = name + ": team.members[" + std::to_string(k) + "]";
      const auto& member = (*members)[k];
      if (!member.is_object() || !member.contains("steps"))
        throw InputError(where + ": no \"steps\" list");
      add_steps(member["steps"], where + ".steps", map, samples);
    }
  } else {
    if (!run.contains("steps"))
      throw InputError(name + ": no \"steps\" list (a `plumekit localize --out` run.json?)");
    add_steps(run["steps"], name + ": steps", map, samples);
  }
  if (samples.empty()) throw InputError(name + ": the run has no steps");
  return samples;
}

std::vector<methods::Sample> read_run_samples(const fs::path& file, const Map& map) {
  return run_samples(parse_run_json(read_file(file), file.string()), file.string(), map);
}

}  // namespace plumekit::run
