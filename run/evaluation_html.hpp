#pragma once
// report.html of an evaluation (docs/report.md): one self-contained page, readable offline, to
// browse it: the summary across methods and maps, sortable, the box plots, each map's runs, and
// any run's way drawn on its map (and its replay, where one was recorded). The page is the data
// (format plumekit-report/1) and run/report_page/'s script and styles, compiled in.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/evaluation.hpp"

namespace plumekit::run {

inline constexpr const char* kReportFormat = "plumekit-report/1";
inline constexpr const char* kReportFile = "report.html";

// One method's evaluation as the page shows it.
struct ReportMethod {
  std::string name;                      // the registry's ("ste")
  nlohmann::ordered_json summary;        // its summary.json (the label comes from its settings)
  const EvaluationResult* result;        // its runs, in run order
  const nlohmann::ordered_json* tracks;  // its tracks.json (run/run_tracks.hpp), parallel to them
  // Each run's replay folder relative to the page (evaluate --replays), or none at all.
  std::vector<std::string> replays;
};

// The page's data: the title, the first method's settings (what every method shared, and its
// method), each method's label and summary, the maps, and one row and track per run.
nlohmann::ordered_json report_data(const std::vector<ReportMethod>& methods);

// The whole page.
std::string evaluation_html(const std::vector<ReportMethod>& methods);

}  // namespace plumekit::run
