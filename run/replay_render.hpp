#pragma once
// A replay drawn as an animation (docs/replay.md): per frame, the world as a person would see it
// (the plume's concentration over the map, every robot with its path so far, each stop coloured by
// its reading and each reading on the way), the method's belief as it stood then, the readings
// over time, and a header with the clock, the estimate and its error.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "core/animation.hpp"
#include "run/replay.hpp"

namespace plumekit::run {

class ReplayPainter {
 public:
  // Frames of `size` pixels (each side even, at least 640 x 360).
  ReplayPainter(const Replay& replay, cv::Size size = {1280, 720});
  ~ReplayPainter();
  ReplayPainter(const ReplayPainter&) = delete;
  ReplayPainter& operator=(const ReplayPainter&) = delete;
  // Frame `k` of the replay (0 .. replay.frames() - 1).
  cv::Mat frame(int k);

  class Panels;

 private:
  const Replay& replay_;
  cv::Size size_;
  std::unique_ptr<Panels> panels_;
};

struct AnimateOptions {
  double fps = 10.0;  // video frames per second; one replay frame each
  cv::Size size{1280, 720};
  bool progress = false;  // a progress bar on stderr
};

// Draws every frame of `replay` into `target` (core/animation.hpp: .mp4, or .png/.apng);
// `flag` names the option that gave the target, for its errors.
AnimationWriter::Written animate_replay(const Replay& replay, const std::filesystem::path& target,
                                        const std::string& flag,
                                        const AnimateOptions& options = {});

// An animation in a command's report: {"file", "format", "frames"} (and "note" when an MP4 became
// an animated PNG) for the JSON, "wrote FILE (N frames)[; note]" for the text.
void report_animation(const AnimationWriter::Written& written, nlohmann::ordered_json& json,
                      std::string& text);

// A plume alone as it moves (`plumekit plume --animate`): the map, the gas on a replay's log scale,
// the source, a clock. frames[k] holds the concentration on `grid` (row 0 at y = 0) at
// k * every_s.
AnimationWriter::Written animate_plume(const Map& map, Vec2 source, const GridShape& grid,
                                       const std::vector<std::vector<float>>& frames,
                                       double every_s, const std::string& title,
                                       const std::filesystem::path& target, const std::string& flag,
                                       const AnimateOptions& options = {});

}  // namespace plumekit::run
