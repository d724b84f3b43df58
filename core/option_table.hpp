#pragma once
// Options declared once. Each options struct has one table: per option its
// dotted name ("flow.nu", the field OptionErrors name), its CLI flag, the
// struct's field, the allowed range and the help text. The default is read
// from a default-constructed struct, never written down a second time.
// validate(), the CLI flags (apps/cli.hpp, add_table_flags), the Python
// properties (python/options.hpp, bind_table) and docs/options.md
// (`plumekit options --markdown`) are all made from the table.
#include <cstdio>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "core/option_check.hpp"

namespace plumekit {

// An enum field, read and written by its names through the library's own
// to_string and parser (which throws OptionError on an unknown name).
template <class T>
struct EnumField {
  std::function<std::string(const T&)> get;
  std::function<void(T&, const std::string&)> set;
  std::string names;  // "upwind, central, vanleer"
};

template <class T, class E>
EnumField<T> enum_field(E T::*field, const char* (*name)(E), E (*parse)(const std::string&),
                        std::string names) {
  return {[field, name](const T& o) { return std::string(name(o.*field)); },
          [field, parse](T& o, const std::string& text) { o.*field = parse(text); },
          std::move(names)};
}

// An optional number whose unset value is chosen elsewhere (by the plume model, the method):
// `unset` says what it then is, computed by the code that chooses it, so that the docs and
// --help never repeat a number ("200 for the surrogate, 150 for physics, 30 for gaussian").
template <class T>
struct OptionalField {
  std::optional<double> T::*field;
  std::function<std::string()> unset;
};

template <class T>
OptionalField<T> optional_field(std::optional<double> T::*field,
                                std::function<std::string()> unset) {
  return {field, std::move(unset)};
}

template <class T>
using OptionField = std::variant<double T::*, int T::*, bool T::*, std::string T::*, EnumField<T>,
                                 OptionalField<T>>;

// What a number is checked against (core/option_check.hpp's checks).
struct OptionRange {
  enum class Kind { None, Real, Count };
  Kind kind = Kind::None;
  double lo = 0.0, hi = 0.0;
  bool lo_open = false, hi_open = false;
  std::string unit;
  bool zero_is_auto = false;  // 0 is allowed besides the range: "chosen for you"
};

inline OptionRange real_range(double lo, double hi, std::string unit, bool lo_open = false,
                              bool hi_open = false) {
  return {OptionRange::Kind::Real, lo, hi, lo_open, hi_open, std::move(unit), false};
}
// 0 < value <= hi
inline OptionRange positive(double hi, std::string unit) {
  return real_range(0.0, hi, std::move(unit), true, false);
}
// 0 <= value <= hi
inline OptionRange non_negative(double hi, std::string unit) {
  return real_range(0.0, hi, std::move(unit));
}
inline OptionRange count_range(long long lo, long long hi) {
  return {OptionRange::Kind::Count, double(lo), double(hi), false, false, "", false};
}
inline OptionRange zero_or(OptionRange range) {
  range.zero_is_auto = true;
  return range;
}

template <class T>
struct OptionEntry {
  OptionEntry(std::string name, std::string flag, OptionField<T> field, OptionRange range,
              std::string help, std::string advice = "", std::string allowed = "")
      : name(std::move(name)),
        flag(std::move(flag)),
        field(std::move(field)),
        range(std::move(range)),
        help(std::move(help)),
        advice(std::move(advice)),
        allowed(std::move(allowed)) {}

  std::string name;  // "flow.nu"; its last part is the Python keyword
  std::string flag;  // "--nu"; empty: not a CLI flag
  OptionField<T> field;
  OptionRange range;
  std::string help;
  // Ends a range error; "{default}" stands for the default value. Empty:
  // "the default is <default> <unit>".
  std::string advice;
  // The docs' "allowed" column where the range depends on another field
  // ("at least ste.gaussian.a_min"), which the struct's validate() checks.
  std::string allowed;

  std::string key() const { return name.substr(name.rfind('.') + 1); }
};

template <class T>
struct OptionTable {
  std::string title;  // docs/options.md's heading: "Flow (cfd::FlowOptions)"
  std::vector<OptionEntry<T>> entries;

  const OptionEntry<T>& entry(const std::string& name) const {
    for (const OptionEntry<T>& e : entries)
      if (e.name == name) return e;
    throw std::logic_error("no option " + name + " in " + title);
  }
};

// A number as the docs and messages print it: %.10g ("0.01", "1e-08").
std::string option_number(double value);

// The value of `e` in `options` as text: numbers, true/false, names.
template <class T>
std::string value_text(const OptionEntry<T>& e, const T& options) {
  return std::visit(
      [&options](const auto& field) -> std::string {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, double T::*>) return option_number(options.*field);
        if constexpr (std::is_same_v<F, int T::*>) return std::to_string(options.*field);
        if constexpr (std::is_same_v<F, bool T::*>) return options.*field ? "true" : "false";
        if constexpr (std::is_same_v<F, std::string T::*>) return options.*field;
        if constexpr (std::is_same_v<F, EnumField<T>>) return field.get(options);
        if constexpr (std::is_same_v<F, OptionalField<T>>) {
          const std::optional<double>& value = options.*(field.field);
          return value ? option_number(*value) : field.unset();
        }
      },
      e.field);
}

// The default: the value in a default-constructed T (an unset optional's `unset` text).
template <class T>
std::string default_text(const OptionEntry<T>& e) {
  return value_text(e, T{});
}

// The range error's advice: `advice` with the default put in, or "the default is ...".
std::string option_advice(const std::string& advice, const std::string& default_value,
                          const std::string& unit);

// Checks the number of one entry in `options` against its range; OptionError
// naming the entry (core/option_check.hpp's messages).
template <class T>
void validate_entry(const OptionEntry<T>& e, const T& options) {
  const OptionRange& r = e.range;
  if (r.kind == OptionRange::Kind::None) return;
  double value = 0.0;
  if (const auto* d = std::get_if<double T::*>(&e.field)) value = options.**d;
  if (const auto* i = std::get_if<int T::*>(&e.field)) value = options.**i;
  if (const auto* o = std::get_if<OptionalField<T>>(&e.field)) {
    const std::optional<double>& set = options.*(o->field);
    if (!set) return;  // unset: the value chosen for it is checked where it is chosen
    value = *set;
  }
  if (r.zero_is_auto && value == 0.0) return;
  const std::string advice = option_advice(e.advice, default_text(e), r.unit);
  if (r.kind == OptionRange::Kind::Real)
    check_range(e.name, value, r.lo, r.hi, r.unit, advice, r.lo_open, r.hi_open);
  else
    check_count(e.name, (long long)value, (long long)r.lo, (long long)r.hi, advice);
}

// Every entry of `table`, in order.
template <class T>
void validate(const OptionTable<T>& table, const T& options) {
  for (const OptionEntry<T>& e : table.entries)
    validate_entry(e, options);
}

// One row of docs/options.md.
struct OptionRow {
  std::string name, flag, default_value, range, help;
};

// The allowed values in words: "more than 0 and at most 10 m^2/s", "0, or ...",
// "true or false", "one of upwind, central, vanleer".
std::string option_range_text(const OptionRange& range, bool is_bool, const std::string& names);

template <class T>
std::vector<OptionRow> option_rows(const OptionTable<T>& table) {
  std::vector<OptionRow> rows;
  for (const OptionEntry<T>& e : table.entries) {
    const auto* named = std::get_if<EnumField<T>>(&e.field);
    rows.push_back({e.name, e.flag, default_text(e),
                    !e.allowed.empty()
                        ? e.allowed
                        : option_range_text(e.range, std::holds_alternative<bool T::*>(e.field),
                                            named ? named->names : ""),
                    e.help});
  }
  return rows;
}

// One table in docs/options.md's form: a heading and a Markdown table.
std::string option_markdown(const std::string& title, const std::vector<OptionRow>& rows);

template <class T>
std::string option_markdown(const OptionTable<T>& table) {
  return option_markdown(table.title, option_rows(table));
}

}  // namespace plumekit
