#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal
// (so logs and pipes stay clean).
#include <string>

namespace plumekit {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  // fraction in [0, 1]; note is shown after the bar.
  void update(double fraction, const std::string& note = "");
  void finish();

 private:
  std::string label_;
  bool enabled_;
  bool open_ = false;
};

}  // namespace plumekit
