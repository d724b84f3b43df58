#include "run/evaluation_html.hpp"

#include <cmath>
#include <stdexcept>

#include "run/report.hpp"
#include "run/report_page.hpp"  // generated from run/report_page/ (run/CMakeLists.txt)

namespace plumekit::run {

using nlohmann::ordered_json;

namespace {

// The columns of a run's row in the page's data (docs/report.md).
const std::vector<std::string> kRunColumns{"method",    "map",        "source",     "run",
                                           "seed",      "error_m",    "samples",    "distance_m",
                                           "mission_s", "stopped_by", "source_x",   "source_y",
                                           "start_x",   "start_y",    "estimate_x", "estimate_y"};

// The settings a summary.json shares with the page: everything but its figures.
ordered_json settings_of(const ordered_json& summary) {
  ordered_json s = ordered_json::object();
  for (const auto& [key, value] : summary.items())
    if (key != "ok" && key != "overall" && key != "maps" && !value.is_structured()) s[key] = value;
  return s;
}

std::string html_text(const std::string& text) {
  std::string out;
  for (char c : text)
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      default:
        out += c;
    }
  return out;
}

// Four significant digits are more than a table or a box plot shows.
double shown(double v) {
  return std::isfinite(v) ? std::round(v * 1e4) / 1e4 : v;
}

}  // namespace

ordered_json report_data(const std::vector<ReportMethod>& methods) {
  if (methods.empty()) throw std::logic_error("report_data: no method");
  const ordered_json& maps = methods.front().tracks->at("maps");
  const std::size_t runs = methods.front().result->runs.size();
  ordered_json j{{"format", kReportFormat}};
  j["title"] = "evaluate: " + std::to_string(maps.size()) +
               (maps.size() == 1 ? " map x " : " maps x ") + std::to_string(methods.size()) +
               (methods.size() == 1 ? " method, " : " methods, ") + std::to_string(runs) +
               " runs each";
  j["settings"] = settings_of(methods.front().summary);
  j["methods"] = ordered_json::array();
  j["maps"] = maps;
  ordered_json rows = ordered_json::array(), tracks = ordered_json::array(),
               replays = ordered_json::array();
  bool any_replay = false;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const ReportMethod& rm = methods[m];
    j["methods"].push_back(
        {{"name", rm.name},
         {"label", summary_label(rm.summary)},
         {"summary", {{"overall", rm.summary.at("overall")}, {"maps", rm.summary.at("maps")}}}});
    const ordered_json& runs_tracks = rm.tracks->at("runs");
    for (std::size_t k = 0; k < rm.result->runs.size(); ++k) {
      const RunRecord& r = rm.result->runs[k];
      const ordered_json& t = runs_tracks.at(k);
      const ordered_json& path = t.at("robots").at(0).at("path");
      rows.push_back({m, r.map_index, r.source_index, r.run, r.seed, shown(r.error_m), r.samples,
                      shown(r.distance_m), shown(r.mission_s), r.stopped_by, t.at("source").at(0),
                      t.at("source").at(1), path.at(0), path.at(1), t.at("estimate").at(0),
                      t.at("estimate").at(1)});
      tracks.push_back(t);
      if (k < rm.replays.size()) {
        replays.push_back(rm.replays[k]);
        any_replay = true;
      } else {
        replays.push_back(nullptr);
      }
    }
  }
  j["runs"] = {{"columns", kRunColumns}, {"rows", std::move(rows)}};
  j["tracks"] = std::move(tracks);
  if (any_replay) j["replays"] = std::move(replays);
  return j;
}

std::string evaluation_html(const std::vector<ReportMethod>& methods) {
  const ordered_json data = report_data(methods);
  // "</" inside a script element would end it; "<\/" is the same JSON string.
  std::string json = data.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
  std::string safe;
  safe.reserve(json.size() + 64);
  for (std::size_t i = 0; i < json.size(); ++i) {
    safe += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') safe += '\\';
  }
  return std::string(
             "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
             "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
             "<title>") +
         html_text(data.at("title").get<std::string>()) + "</title>\n<style>" +
         report_page::kStyle + "</style></head>\n<body>\n" +
         "<script type=\"application/json\" id=\"plumekit-data\">" + safe + "</script>\n<script>" +
         report_page::kScript + "</script>\n</body></html>\n";
}

}  // namespace plumekit::run
