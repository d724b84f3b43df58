#include "run/comparison.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/csv.hpp"
#include "run/report.hpp"

namespace plumekit::run {

namespace {

using nlohmann::ordered_json;

// A summary's number, or NaN where it is null or missing (a time no run reached).
double number(const ordered_json& o, const std::string& key) {
  return o.contains(key) && o[key].is_number() ? o[key].get<double>() : std::nan("");
}

std::string fixed(double v, int digits, const std::string& unit = "") {
  if (!std::isfinite(v)) return "–";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v << unit;
  return s.str();
}

// "93 % (91–95)": a share with its 95 % interval.
std::string share(const ordered_json& o, const std::string& key) {
  std::string s = fixed(100 * number(o, key), 0, " %");
  const std::string ci = key + "_ci95";
  if (o.contains(ci) && o[ci].is_array() && o[ci].size() == 2)
    s += " (" + fixed(100 * o[ci][0].get<double>(), 0) + "–" +
         fixed(100 * o[ci][1].get<double>(), 0) + ")";
  return s;
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

}  // namespace

Comparison compare_methods(const std::vector<MethodRow>& methods) {
  Comparison c;
  c.rows = ordered_json::array();
  std::ostringstream md, csv;
  md << "| method | runs | within 0.5 m | within 1 m | median error | samples | distance | "
        "median mission | time to 1 m | mission / shortest way | GSL-Bench (1 m in 300 s) | "
        "decision step | its time |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  csv << "method,runs,success_0_5m,success_1_0m,median_error_m,median_samples,median_distance_m,"
         "median_mission_s,median_time_to_1m_s,median_mission_over_optimum,gsl_bench_success,"
         "median_step_s,model_build_s,decisions_s\n";
  for (const MethodRow& m : methods) {
    const ordered_json& o = m.summary.at("overall");
    const std::string name = summary_label(m.summary);
    const double own = m.model_build_s + m.decisions_s;
    md << "| " << name << " | " << o.value("runs", 0) << " | " << share(o, "success_0_5m") << " | "
       << share(o, "success_1_0m") << " | " << fixed(number(o, "median_error_m"), 2, " m") << " | "
       << fixed(number(o, "median_samples"), 0) << " | "
       << fixed(number(o, "median_distance_m"), 1, " m") << " | "
       << fixed(number(o, "median_mission_s"), 0, " s") << " | "
       << fixed(number(o, "median_time_to_1m_s"), 0, " s") << " | "
       << fixed(number(o, "median_mission_over_optimum"), 1) << " | "
       << share(o, "gsl_bench_success") << " | " << fixed(1000 * m.median_step_s, 2, " ms") << " | "
       << fixed(own, 1, " s") << " |\n";
    csv << csv_field(name) << "," << o.value("runs", 0);
    for (const char* key : {"success_0_5m", "success_1_0m", "median_error_m", "median_samples",
                            "median_distance_m", "median_mission_s", "median_time_to_1m_s",
                            "median_mission_over_optimum", "gsl_bench_success"})
      csv << "," << csv_number(number(o, key));
    csv << "," << csv_number(m.median_step_s) << "," << csv_number(m.model_build_s) << ","
        << csv_number(m.decisions_s) << "\n";
    ordered_json row{{"method", name}};
    for (const char* key :
         {"runs", "success_0_5m", "success_0_5m_ci95", "success_1_0m", "success_1_0m_ci95",
          "median_error_m", "median_samples", "median_distance_m", "median_mission_s",
          "median_time_to_1m_s", "median_mission_over_optimum", "gsl_bench_success"})
      row[key] = o.contains(key) ? o[key] : ordered_json(nullptr);
    row["median_step_s"] = m.median_step_s;
    row["model_build_s"] = m.model_build_s;
    row["decisions_s"] = m.decisions_s;
    c.rows.push_back(row);
  }
  c.markdown = md.str();
  c.csv = csv.str();
  return c;
}

}  // namespace plumekit::run
