#include "core/csv.hpp"

#include "core/error.hpp"

namespace plumekit {

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

std::vector<std::vector<std::string>> parse_csv(std::string_view text, const std::string& name) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  int line = 1;
  std::size_t i = 0;
  const auto fail = [&](const std::string& what) {
    throw InputError(name + ":" + std::to_string(line) + ": " + what +
                     " (CSV as RFC 4180: a field with a comma, quote or line break is quoted, "
                     "its quotes doubled)");
  };
  while (i < text.size()) {
    if (text[i] == '"') {  // a quoted field, to its closing quote
      const int opened = line;
      for (++i;; ++i) {
        if (i >= text.size()) {
          line = opened;
          fail("a quoted field is not closed");
        }
        if (text[i] == '"') {
          if (i + 1 < text.size() && text[i + 1] == '"') {
            field += '"';
            ++i;
            continue;
          }
          ++i;
          break;
        }
        line += text[i] == '\n';
        field += text[i];
      }
      if (i < text.size() && text[i] != ',' && text[i] != '\n' && text.compare(i, 2, "\r\n") != 0)
        fail("text after a quoted field's closing quote");
    } else {
      while (i < text.size() && text[i] != ',' && text[i] != '\n' &&
             text.compare(i, 2, "\r\n") != 0)
        field += text[i++];
    }
    record.push_back(std::move(field));
    field.clear();
    if (i < text.size() && text[i] == ',') {
      ++i;
      if (i == text.size()) record.emplace_back();  // "a," ends in an empty field
      continue;
    }
    i += i < text.size() && text[i] == '\r' ? 2 : 1;  // the record's line break, or the end
    ++line;
    records.push_back(std::move(record));
    record.clear();
  }
  if (!record.empty()) records.push_back(std::move(record));
  return records;
}

}  // namespace plumekit
