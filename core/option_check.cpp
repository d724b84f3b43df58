#include "core/option_check.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.hpp"

namespace plumekit {

std::string compact(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

namespace {

std::string with_unit(double value, const std::string& unit) {
  return compact(value) + (unit.empty() ? "" : " " + unit);
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t k = 0; k < names.size(); ++k)
    s += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return s;
}

}  // namespace

std::string range_text(double lo, double hi, const std::string& unit, bool lo_open, bool hi_open) {
  if (std::isinf(hi)) return (lo_open ? "more than " : "at least ") + with_unit(lo, unit);
  if (!lo_open && !hi_open) return "from " + compact(lo) + " to " + with_unit(hi, unit);
  return std::string(lo_open ? "more than " : "at least ") + compact(lo) + " and " +
         (hi_open ? "less than " : "at most ") + with_unit(hi, unit);
}

void check_range(const std::string& field, double value, double lo, double hi,
                 const std::string& unit, const std::string& advice, bool lo_open, bool hi_open) {
  const bool above_lo = lo_open ? value > lo : value >= lo;
  const bool below_hi = hi_open ? value < hi : value <= hi;
  if (std::isfinite(value) && above_lo && below_hi) return;
  std::string message = "must be a finite number " + range_text(lo, hi, unit, lo_open, hi_open) +
                        ", got " + compact(value);
  if (!advice.empty()) message += "; " + advice;
  throw OptionError(field, message);
}

void check_positive(const std::string& field, double value, double hi, const std::string& unit,
                    const std::string& advice) {
  check_range(field, value, 0.0, hi, unit, advice, true, false);
}

void check_non_negative(const std::string& field, double value, double hi, const std::string& unit,
                        const std::string& advice) {
  check_range(field, value, 0.0, hi, unit, advice, false, false);
}

void check_count(const std::string& field, long long value, long long lo, long long hi,
                 const std::string& advice) {
  if (value >= lo && value <= hi) return;
  std::string message = "must be a whole number from " + std::to_string(lo) + " to " +
                        std::to_string(hi) + ", got " + std::to_string(value);
  if (!advice.empty()) message += "; " + advice;
  throw OptionError(field, message);
}

void check_name(const std::string& field, const std::string& name,
                const std::vector<std::string>& known) {
  for (const std::string& k : known)
    if (k == name) return;
  throw OptionError(field, "unknown name '" + name + "'; use " + join(known));
}

PartOfN parse_part(const std::string& field, const std::string& k_of_n) {
  int k = -1, n = 0;
  char slash = 0, extra = 0;
  std::istringstream in(k_of_n);
  if (!(in >> k >> slash >> n) || slash != '/' || (in >> extra) || n <= 0 || k < 0 || k >= n)
    throw OptionError(field, "expected K/N with 0 <= K < N, got '" + k_of_n + "'");
  return {k, n};
}

}  // namespace plumekit
