#include "core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace plumekit {

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), enabled_(::isatty(2)) {}

ProgressBar::~ProgressBar() {
  finish();
}

void ProgressBar::update(double fraction, const std::string& note) {
  if (!enabled_) return;
  const int width = 30;
  const int filled = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * width + 0.5);
  std::fprintf(stderr, "\r%s [%s%s] %3d%% %s\033[K", label_.c_str(),
               std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
               static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100 + 0.5), note.c_str());
  std::fflush(stderr);
  open_ = true;
}

void ProgressBar::finish() {
  if (open_) std::fputc('\n', stderr);
  open_ = false;
}

}  // namespace plumekit
