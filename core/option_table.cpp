#include "core/option_table.hpp"

#include <cstdio>

namespace plumekit {

std::string option_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

std::string option_advice(const std::string& advice, const std::string& default_value,
                          const std::string& unit) {
  if (advice.empty()) return "the default is " + default_value + (unit.empty() ? "" : " " + unit);
  std::string text = advice;
  const std::string mark = "{default}";
  for (std::size_t at = text.find(mark); at != std::string::npos; at = text.find(mark, at))
    text.replace(at, mark.size(), default_value);
  return text;
}

std::string option_range_text(const OptionRange& range, bool is_bool, const std::string& names) {
  if (is_bool) return "true or false";
  if (!names.empty()) return "one of " + names;
  std::string text;
  if (range.kind == OptionRange::Kind::Real)
    text = range_text(range.lo, range.hi, range.unit, range.lo_open, range.hi_open);
  else if (range.kind == OptionRange::Kind::Count)
    text = "whole number from " + option_number(range.lo) + " to " + option_number(range.hi);
  else
    return "any";
  return range.zero_is_auto ? "0, or " + text : text;
}

namespace {
// A cell of a Markdown table: no line breaks, no column bars.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}
}  // namespace

std::string option_markdown(const std::string& title, const std::vector<OptionRow>& rows) {
  std::string md = "## " + title + "\n\n| option | flag | default | allowed | meaning |\n" +
                   "|---|---|---|---|---|\n";
  for (const OptionRow& r : rows)
    md += "| `" + r.name + "` | " + (r.flag.empty() ? "" : "`" + r.flag + "`") + " | `" +
          cell(r.default_value) + "` | " + cell(r.range) + " | " + cell(r.help) + " |\n";
  return md;
}

}  // namespace plumekit
