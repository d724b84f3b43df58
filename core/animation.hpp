#pragma once
// Animations: a sequence of frames written as one file, for the replays of runs and plumes
// (docs/replay.md).
//
// - ".mp4": H.264 in MP4 through FFmpeg's libraries, from the module libplumekit_video
//   (core/video_plugin.cpp) that is loaded only here, so that no other command loads FFmpeg.
//   When the module or the encoder is missing, the animation is written as an animated PNG
//   beside it ("run.mp4" -> "run.png") and the result says why.
// - ".png" or ".apng": an animated PNG (APNG), assembled here from each frame's PNG encoding:
//   every browser plays it; a viewer without APNG shows its first frame.
//
// The file follows the output rule (core/output_target.hpp): a file plumekit did not write is
// never replaced, the file appears whole (written beside it, then renamed) and carries plumekit's
// mark (a PNG text chunk; a trailing MP4 "free" box), and a video is read back and its frames
// counted before it is moved into place.
#include <filesystem>
#include <memory>
#include <string>

#include <opencv2/core.hpp>

namespace plumekit {

// InputError naming `flag` unless `target` is a path an animation may be written to (its extension
// and the output rule): what a command checks before the work that makes the frames.
void check_animation_target(const std::filesystem::path& target, const std::string& flag);

class AnimationWriter {
 public:
  // Checks `target` against the output rule; InputError naming `flag` when its extension is none
  // of the above. `fps`: frames per second of playback.
  AnimationWriter(std::filesystem::path target, double fps, const std::string& flag);
  ~AnimationWriter();
  AnimationWriter(const AnimationWriter&) = delete;
  AnimationWriter& operator=(const AnimationWriter&) = delete;

  // Appends a frame: 8-bit BGR, every frame the first one's size (even sides for H.264).
  void add(const cv::Mat& frame);

  struct Written {
    std::filesystem::path file;  // the target, or the animated PNG written in its place
    std::string format;          // "mp4" or "apng"
    int frames = 0;
    cv::Size size;
    std::string note;  // why an MP4 became an animated PNG; empty otherwise
  };
  // Writes the file; the writer takes no more frames.
  Written finish();

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Where the video module was found, or why it was not (for `plumekit --version`-style reports and
// the tests): empty `error` when it loads.
struct VideoModule {
  std::filesystem::path path;
  std::string error;
};
VideoModule find_video_module();

}  // namespace plumekit
