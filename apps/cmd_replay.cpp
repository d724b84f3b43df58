// plumekit replay RUN_DIR --out FILE: a run's replay (run/replay.hpp, recorded by
// `localize --out DIR --animate FILE`) drawn again, without running the mission again.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/animation.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "map/map_render.hpp"
#include "run/replay.hpp"
#include "run/replay_render.hpp"

namespace plumekit::cli {

namespace {

namespace fs = std::filesystem;

// "WIDTHxHEIGHT": even sides of at least 640 x 360 pixels.
cv::Size parse_frame_size(const std::string& text) {
  const std::size_t x = text.find('x');
  int w = 0, h = 0;
  try {
    std::size_t used_w = 0, used_h = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    w = std::stoi(text.substr(0, x), &used_w);
    h = std::stoi(text.substr(x + 1), &used_h);
    if (used_w != x || used_h != text.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw InputError("--size: expected WIDTHxHEIGHT in pixels, e.g. 1280x720, got '" + text + "'");
  }
  if (w < 640 || h < 360 || w > 3840 || h > 2160 || w % 2 != 0 || h % 2 != 0)
    throw InputError("--size " + text +
                     ": each side even, from 640x360 to 3840x2160 (a video encoder's limits)");
  return {w, h};
}

// `replay RUN --at SECONDS --out FILE.png`: the one frame at that second, as a still picture.
void still(const std::string& run_dir, const std::string& out, double at, cv::Size size) {
  if (fs::path(out).extension() != ".png")
    throw InputError("--out " + out + ": a frame (--at) is written as a .png picture");
  check_output_file(out);
  const run::Replay replay = run::read_replay(run_dir);
  const double last = replay.time_of(replay.frames() - 1);
  if (!(at >= 0.0 && at <= last + 1e-9))
    throw InputError("--at " + compact(at) + ": the replay runs from 0 to " + compact(last) + " s");
  run::ReplayPainter painter(replay, size);
  const int frame =
      std::min(static_cast<int>(std::lround(at / replay.every_s)), replay.frames() - 1);
  write_png(painter.frame(frame), out);
  report({{"ok", true},
          {"run", run_dir},
          {"out", out},
          {"frame", frame},
          {"time_s", replay.time_of(frame)}},
         replay.title + "\nwrote " + out + " (the frame at " +
             std::to_string(std::lround(replay.time_of(frame))) + " s)");
}

}  // namespace

void add_replay_commands(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "replay",
      "Draw a recorded run again as a video or animated PNG (`localize --out DIR --animate FILE` "
      "records it; docs/replay.md)");
  struct Args {
    std::string run, out, size = "1280x720";
    double fps = 10.0;
    std::optional<double> at;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("RUN_DIR", a->run, "A run's folder holding replay.json")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out,-o", a->out, "The animation: FILE.mp4 (a video) or FILE.png (animated)")
      ->required()
      ->type_name("FILE");
  cmd->add_option("--fps", a->fps, "Frames per second of playback; a frame is a second of the run")
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Frame size in pixels, WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--at", a->at,
                  "Write only the frame at this second of the mission, as a still FILE.png")
      ->type_name("SECONDS");
  add_common_flags(cmd);
  cmd->callback([a] {
    const auto t0 = std::chrono::steady_clock::now();
    const cv::Size size = parse_frame_size(a->size);
    if (!(a->fps > 0.0 && a->fps <= 240.0))
      throw InputError("--fps: frames per second must lie in (0, 240]");
    if (a->at) return still(a->run, a->out, *a->at, size);
    check_animation_target(a->out, "--out");
    const run::Replay replay = run::read_replay(a->run);
    run::AnimateOptions o;
    o.fps = a->fps;
    o.size = size;
    o.progress = !output().json;
    const AnimationWriter::Written w = run::animate_replay(replay, a->out, "--out", o);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::ordered_json j{{"ok", true},
                             {"run", a->run},
                             {"title", replay.title},
                             {"out", w.file.string()},
                             {"format", w.format},
                             {"frames", w.frames},
                             {"width", w.size.width},
                             {"height", w.size.height},
                             {"seconds", seconds}};
    std::string text = replay.title + "\nwrote " + w.file.string() + " (" +
                       std::to_string(w.frames) + " frames, " + std::to_string(w.size.width) + "x" +
                       std::to_string(w.size.height) + ")";
    if (!w.note.empty()) {
      j["note"] = w.note;
      text += "; " + w.note;
    }
    report(j, text);
  });
}

}  // namespace plumekit::cli
