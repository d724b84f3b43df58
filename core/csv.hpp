#pragma once
// CSV as RFC 4180 gives it: what plumekit writes (an evaluation's runs.csv and timings.csv, a
// tunnel evaluation's runs.csv) and reads back (`evaluate merge`). A map name may hold a comma, a
// quote or a line break; quoted, the file still parses (python's csv module reads it back).
// Ours rather than libcsv: docs/own-code.md.
#include <string>
#include <string_view>
#include <vector>

namespace plumekit {

// `text` as one CSV field: as it is, or in double quotes (inner quotes doubled) when it holds a
// comma, a double quote, CR or LF.
std::string csv_field(std::string_view text);

// The records of CSV text, each a list of unquoted fields. A record ends at a line break (LF or
// CRLF) outside quotes; the text's last line break is optional. InputError naming `name` and the
// line where a quoted field is not closed or a closing quote is followed by anything but a comma or
// the record's end.
std::vector<std::vector<std::string>> parse_csv(std::string_view text, const std::string& name);

}  // namespace plumekit
