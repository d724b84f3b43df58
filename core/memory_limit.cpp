#include "core/memory_limit.hpp"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/option_check.hpp"

namespace plumekit {

namespace {

constexpr double kKiB = 1024.0, kMiB = kKiB * 1024, kGiB = kMiB * 1024, kTiB = kGiB * 1024;

// 0 until set_memory_limit() is called.
std::atomic<double> g_limit{0.0};

}  // namespace

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 0.0;
  return static_cast<double>(pages) * static_cast<double>(page);
}

double default_memory_limit() {
  if (const char* env = std::getenv("PLUMEKIT_MAX_MEMORY"); env && *env)
    return parse_memory_size(env, "PLUMEKIT_MAX_MEMORY");
  const double physical = physical_memory_bytes();
  return physical > 0.0 ? 0.5 * physical : 4.0 * kGiB;
}

double memory_limit() {
  const double set = g_limit.load();
  return set > 0.0 ? set : default_memory_limit();
}

void set_memory_limit(double bytes) {
  check_range("memory.limit", bytes, kMiB, 1e18, "bytes", "give a size such as 4G or 512M");
  g_limit.store(bytes);
}

double parse_memory_size(const std::string& text, const std::string& field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double number = std::strtod(begin, &end);
  std::string suffix(end);
  for (char& c : suffix)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  double unit = 0.0;
  if (suffix.empty() || suffix == "B")
    unit = 1.0;
  else if (suffix == "K" || suffix == "KB" || suffix == "KIB")
    unit = kKiB;
  else if (suffix == "M" || suffix == "MB" || suffix == "MIB")
    unit = kMiB;
  else if (suffix == "G" || suffix == "GB" || suffix == "GIB")
    unit = kGiB;
  else if (suffix == "T" || suffix == "TB" || suffix == "TIB")
    unit = kTiB;
  if (end == begin || unit == 0.0 || !(std::isfinite(number) && number > 0.0))
    throw OptionError(field, "'" + text +
                                 "' is not a memory size; give a positive number of bytes with "
                                 "an optional K, M, G or T (powers of 1024), e.g. 4G or 512M");
  return number * unit;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int k = 0;
  while (bytes >= 1024.0 && k < 5) {
    bytes /= 1024.0;
    ++k;
  }
  char text[48];
  std::snprintf(text, sizeof text, bytes < 10.0 && k > 0 ? "%.1f %s" : "%.0f %s", bytes, units[k]);
  return text;
}

std::string suggest_limit(double bytes) {
  if (bytes < kGiB) return std::to_string(static_cast<long long>(std::ceil(bytes / kMiB))) + "M";
  if (bytes < 1024 * kGiB)
    return std::to_string(static_cast<long long>(std::ceil(bytes / kGiB))) + "G";
  if (bytes < 1e9 * kTiB)
    return std::to_string(static_cast<long long>(std::ceil(bytes / kTiB))) + "T";
  return compact(bytes);
}

bool fits_in_memory(double bytes) {
  return bytes <= memory_limit();
}

void check_memory(double bytes, const std::string& what, const std::string& fix) {
  const double limit = memory_limit();
  if (bytes <= limit) return;
  std::string message = what + " needs about " + format_bytes(bytes) +
                        " of memory, more than the limit of " + format_bytes(limit) + "; ";
  if (!fix.empty()) message += fix + ", or ";
  message += "raise the memory limit to at least " + suggest_limit(bytes);
  throw MemoryLimitError(message, bytes, limit);
}

}  // namespace plumekit
