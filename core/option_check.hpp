#pragma once
// Range checks for options structs: each throws OptionError naming the field
// (its dotted library name, e.g. "flow.cell"), the allowed range, the value
// given and what to do. The messages never name a CLI flag: the CLI puts the
// flag bound to the field in place of the field's name.
#include <string>
#include <vector>

namespace plumekit {

// A double in %g style with up to 4 significant digits ("0.05", "1e+300",
// "nan", "inf"), so that DBL_MAX and the like never print as 300 digits.
std::string compact(double value);

// The allowed range in words, as check_range's messages say it: "more than 0
// and at most 10 m", "from 1e-14 to 0.1", "at least 1 m".
std::string range_text(double lo, double hi, const std::string& unit, bool lo_open = false,
                       bool hi_open = false);

// `value` must be finite and lo <= value <= hi (lo_open / hi_open: strictly).
// `unit` follows the numbers in the message ("m", "m^2/s", "" for none).
// `advice` ends the message (what to do), e.g. "the default is 0.05 m".
void check_range(const std::string& field, double value, double lo, double hi,
                 const std::string& unit, const std::string& advice = "", bool lo_open = false,
                 bool hi_open = false);

// Shorthands: 0 < value <= hi; 0 <= value <= hi.
void check_positive(const std::string& field, double value, double hi, const std::string& unit,
                    const std::string& advice = "");
void check_non_negative(const std::string& field, double value, double hi, const std::string& unit,
                        const std::string& advice = "");

// An integer count: lo <= value <= hi.
void check_count(const std::string& field, long long value, long long lo, long long hi,
                 const std::string& advice = "");

// `name` must be one of `known`; the message lists them.
void check_name(const std::string& field, const std::string& name,
                const std::vector<std::string>& known);

// "K/N", a part of a run split N ways (--shard): 0 <= K < N, both integers.
struct PartOfN {
  int k = 0, n = 1;
};
PartOfN parse_part(const std::string& field, const std::string& k_of_n);

}  // namespace plumekit
