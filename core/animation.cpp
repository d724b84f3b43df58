#include "core/animation.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <optional>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/output_target.hpp"
#include "core/temporary_files.hpp"

namespace plumekit {

namespace fs = std::filesystem;

namespace {

constexpr const char* kModuleName = "libplumekit_video.so";

// The module's entry points (core/video_plugin.cpp).
struct VideoApi {
  void* (*open)(const char*, double, int, int, char*, int) = nullptr;
  int (*write)(void*, const unsigned char*, std::size_t) = nullptr;
  int (*close)(void*) = nullptr;
  int (*probe)(const char*, int*, int*, int*) = nullptr;
  VideoModule module;
};

// Where the module may be: $PLUMEKIT_VIDEO_MODULE, else beside the program (or the Python
// module) this code is linked into, one folder up (the Python module's build folder), or in
// ../lib/plumekit (an installed prefix).
std::vector<fs::path> module_candidates() {
  if (const char* env = std::getenv("PLUMEKIT_VIDEO_MODULE"); env != nullptr && *env != '\0')
    return {fs::path(env)};
  Dl_info info{};
  fs::path here;
  if (dladdr(reinterpret_cast<void*>(&module_candidates), &info) != 0 && info.dli_fname != nullptr)
    here = fs::absolute(info.dli_fname).parent_path();
  if (here.empty()) here = fs::read_symlink("/proc/self/exe").parent_path();
  return {here / kModuleName, here.parent_path() / kModuleName,
          here.parent_path() / "lib" / "plumekit" / kModuleName};
}

const VideoApi& video_api() {
  static VideoApi api;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const fs::path& p : module_candidates()) {
      std::error_code ec;
      if (!fs::exists(p, ec)) {
        tried += (tried.empty() ? "" : ", ") + p.string();
        continue;
      }
      void* h = dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (h == nullptr) {
        api.module = {p, std::string("cannot load it: ") + dlerror()};
        return;
      }
      api.open = reinterpret_cast<decltype(api.open)>(dlsym(h, "plumekit_video_open"));
      api.write = reinterpret_cast<decltype(api.write)>(dlsym(h, "plumekit_video_write"));
      api.close = reinterpret_cast<decltype(api.close)>(dlsym(h, "plumekit_video_close"));
      api.probe = reinterpret_cast<decltype(api.probe)>(dlsym(h, "plumekit_video_probe"));
      api.module = {p, api.open && api.write && api.close && api.probe
                           ? ""
                           : "it lacks plumekit_video_* entry points"};
      return;  // the module stays loaded: the encoder may run again
    }
    api.module = {{}, "no " + std::string(kModuleName) + " (looked for " + tried + ")"};
  });
  return api;
}

void put_be16(std::string& s, std::uint16_t v) {
  s.push_back(static_cast<char>(v >> 8));
  s.push_back(static_cast<char>(v & 0xff));
}

// An animated PNG built frame by frame (the APNG extension: acTL, then per frame an fcTL and its
// image data, IDAT for the first frame, fdAT with a sequence number for the others).
class ApngBuilder {
 public:
  explicit ApngBuilder(double fps) : fps_(fps) {}
  void add(const cv::Mat& frame) {
    const std::string png = encode_png(frame);
    std::string data;  // the frame's IDAT payloads, in order
    for (std::size_t at = 8; at + 12 <= png.size();) {
      const std::uint32_t length = get_be32(png, at);
      const std::string type = png.substr(at + 4, 4);
      if (type == "IHDR" && ihdr_.empty()) ihdr_ = png.substr(at + 8, length);
      if (type == "IDAT") data += png.substr(at + 8, length);
      at += 12 + length;
    }
    std::string control;
    put_be32(control, sequence_++);
    put_be32(control, static_cast<std::uint32_t>(frame.cols));
    put_be32(control, static_cast<std::uint32_t>(frame.rows));
    put_be32(control, 0);    // x offset
    put_be32(control, 0);    // y offset
    put_be16(control, 100);  // delay: 100 / (100 fps) s
    put_be16(control, static_cast<std::uint16_t>(std::lround(std::min(655.0, fps_) * 100.0)));
    control.push_back(0);  // dispose: none
    control.push_back(0);  // blend: source (each frame is whole)
    body_ += png_chunk("fcTL", control);
    if (frames_ == 0) {
      body_ += png_chunk("IDAT", data);
    } else {
      std::string fdat;
      put_be32(fdat, sequence_++);
      body_ += png_chunk("fdAT", fdat + data);
    }
    ++frames_;
  }
  std::string bytes() const {
    std::string out("\x89PNG\r\n\x1a\n", 8);
    out += png_chunk("IHDR", ihdr_);
    std::string control;
    put_be32(control, static_cast<std::uint32_t>(frames_));
    put_be32(control, 0);  // plays: forever
    out += png_chunk("acTL", control);
    out += body_;
    out += png_chunk("IEND", "");
    return mark_png(std::move(out));
  }

 private:
  double fps_;
  std::string ihdr_, body_;
  std::uint32_t sequence_ = 0;
  int frames_ = 0;
};

std::string lower_extension(const fs::path& p) {
  std::string e = p.extension().string();
  for (char& c : e)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

}  // namespace

VideoModule find_video_module() {
  return video_api().module;
}

class AnimationWriter::Impl {
 public:
  fs::path target;
  double fps = 10.0;
  bool mp4 = false;
  std::string note;
  cv::Size size;
  int frames = 0;
  bool finished = false;
  std::optional<Temporary> video_file;  // the MP4 being written, outside the target's folder
  void* video = nullptr;
  std::optional<ApngBuilder> apng;

  ~Impl() {
    if (video != nullptr) video_api().close(video);
  }

  // The MP4 writer, or, when none opens, the animated PNG that takes its place.
  void open_video() {
    const VideoApi& api = video_api();
    std::string why = api.module.error;
    if (why.empty()) {
      video_file.emplace(fs::temp_directory_path() /
                         ("plumekit-video-" + std::to_string(::getpid()) + ".mp4"));
      char error[512] = "";
      video = api.open(video_file->path().c_str(), fps, size.width, size.height, error,
                       static_cast<int>(sizeof error));
      if (video != nullptr) return;
      why = error;
      video_file.reset();
    }
    const fs::path png = fs::path(target).replace_extension(".png");
    check_output_file(png);
    note = "no MP4 encoder (" + why + "): wrote an animated PNG, " + png.string() + ", instead";
    target = png;
    mp4 = false;
    apng.emplace(fps);
  }
};

void check_animation_target(const fs::path& target, const std::string& flag) {
  const std::string ext = lower_extension(target);
  if (ext != ".mp4" && ext != ".png" && ext != ".apng")
    throw InputError(flag + " " + target.string() +
                     ": an animation is written as .mp4 (a video) or .png (an animated PNG)");
  check_output_file(target);
}

AnimationWriter::AnimationWriter(fs::path target, double fps, const std::string& flag)
    : impl_(std::make_unique<Impl>()) {
  check_animation_target(target, flag);
  if (!(fps > 0.0 && fps <= 240.0))
    throw InputError(flag + ": frames per second must lie in (0, 240]");
  impl_->mp4 = lower_extension(target) == ".mp4";
  impl_->target = std::move(target);
  impl_->fps = fps;
  if (!impl_->mp4) impl_->apng.emplace(fps);
}

AnimationWriter::~AnimationWriter() = default;

void AnimationWriter::add(const cv::Mat& frame) {
  Impl& m = *impl_;
  if (m.finished) throw std::logic_error("AnimationWriter: a frame after finish()");
  if (frame.type() != CV_8UC3 || frame.empty())
    throw std::logic_error("AnimationWriter: frames are 8-bit BGR images");
  if (m.frames == 0) {
    m.size = frame.size();
    if (m.mp4) m.open_video();
  } else if (frame.size() != m.size) {
    throw std::logic_error("AnimationWriter: every frame has the first frame's size");
  }
  if (m.video != nullptr) {
    const cv::Mat whole = frame.isContinuous() ? frame : frame.clone();
    if (video_api().write(m.video, whole.data, whole.step) != 0)
      throw std::runtime_error("writing the video " + m.target.string() + " failed");
  } else {
    m.apng->add(frame);
  }
  ++m.frames;
}

AnimationWriter::Written AnimationWriter::finish() {
  Impl& m = *impl_;
  if (m.frames == 0) throw std::logic_error("AnimationWriter: no frames");
  m.finished = true;
  Written w{m.target, m.video != nullptr ? "mp4" : "apng", m.frames, m.size, m.note};
  std::string bytes;
  if (m.video != nullptr) {
    const int closed = video_api().close(m.video);
    m.video = nullptr;
    if (closed != 0)
      throw std::runtime_error("finishing the video " + m.target.string() +
                               " failed; nothing was written");
    int frames = 0, width = 0, height = 0;
    if (video_api().probe(m.video_file->path().c_str(), &frames, &width, &height) != 0 ||
        frames != m.frames || width != m.size.width || height != m.size.height)
      throw std::runtime_error("the video " + m.target.string() + " read back " +
                               std::to_string(frames) + " frames of " + std::to_string(width) +
                               " x " + std::to_string(height) + ", not the " +
                               std::to_string(m.frames) + " written; nothing was written");
    bytes = read_file(m.video_file->path());
    // plumekit's mark: a top-level "free" box, which players skip (output_target.hpp).
    const std::string mark = plumekit_mark();
    put_be32(bytes, static_cast<std::uint32_t>(8 + mark.size()));
    bytes += "free" + mark;
    m.video_file.reset();
  } else {
    bytes = m.apng->bytes();
  }
  write_output_file(m.target, bytes);
  return w;
}

}  // namespace plumekit
