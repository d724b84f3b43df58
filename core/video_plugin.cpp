// libplumekit_video: an H.264 MP4 writer (and a reader that counts a file's frames, to verify what
// was written) on FFmpeg's libraries, behind a small C interface that core/animation.cpp loads at
// run time. A module of its own so that no other command loads FFmpeg and the ~100 libraries it
// pulls in at every start.
//
// FFmpeg directly rather than OpenCV's VideoWriter (the same libraries underneath): OpenCV 4.6's
// writer cannot choose x264's preset, and its default, "medium", took 60 % of a replay's time.
// "veryfast" at CRF 23 encodes about four times faster at a size that stays far below a megabyte a
// minute for these pictures; "+faststart" puts the index first, so a browser starts playing at
// once.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace {

void say(char* error, int length, const std::string& text) {
  if (error == nullptr || length <= 0) return;
  const std::size_t n = std::min<std::size_t>(text.size(), static_cast<std::size_t>(length - 1));
  text.copy(error, n);
  error[n] = '\0';
}

std::string av_error(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = "";
  av_strerror(code, text, sizeof text);
  return text;
}

struct Writer {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  SwsContext* convert = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  int width = 0, height = 0;
  std::int64_t next_pts = 0;
  bool header = false;

  ~Writer() {
    sws_freeContext(convert);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    if (format != nullptr) {
      if (format->pb != nullptr) avio_closep(&format->pb);
      avformat_free_context(format);
    }
  }

  // Sends `f` (null: the end) to the encoder and writes every packet it gives back.
  int encode(AVFrame* f) {
    int err = avcodec_send_frame(codec, f);
    while (err >= 0) {
      err = avcodec_receive_packet(codec, packet);
      if (err == AVERROR(EAGAIN) || err == AVERROR_EOF) return 0;
      if (err < 0) break;
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      err = av_interleaved_write_frame(format, packet);
    }
    return err;
  }
};

// Opens the writer's file, encoder and converter; "" or what failed.
std::string open_writer(Writer& w, const char* path, double fps) {
  if (avformat_alloc_output_context2(&w.format, nullptr, "mp4", path) < 0 || w.format == nullptr)
    return "FFmpeg has no MP4 muxer";
  const AVCodec* h264 = avcodec_find_encoder_by_name("libx264");
  if (h264 == nullptr) h264 = avcodec_find_encoder(AV_CODEC_ID_H264);
  if (h264 == nullptr) return "FFmpeg has no H.264 encoder here";
  w.stream = avformat_new_stream(w.format, nullptr);
  w.codec = avcodec_alloc_context3(h264);
  w.frame = av_frame_alloc();
  w.packet = av_packet_alloc();
  if (w.stream == nullptr || w.codec == nullptr || w.frame == nullptr || w.packet == nullptr)
    return "out of memory";
  w.codec->width = w.width;
  w.codec->height = w.height;
  w.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  w.codec->framerate = av_d2q(fps, 100000);
  w.codec->time_base = av_inv_q(w.codec->framerate);
  w.codec->gop_size = std::max(1, static_cast<int>(fps * 2));
  if ((w.format->oformat->flags & AVFMT_GLOBALHEADER) != 0)
    w.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* options = nullptr;
  av_dict_set(&options, "preset", "veryfast", 0);
  av_dict_set(&options, "crf", "23", 0);
  const int opened = avcodec_open2(w.codec, h264, &options);
  av_dict_free(&options);
  if (opened < 0) return "the H.264 encoder did not open: " + av_error(opened);
  if (avcodec_parameters_from_context(w.stream->codecpar, w.codec) < 0) return "FFmpeg failed";
  w.stream->time_base = w.codec->time_base;
  w.stream->avg_frame_rate = w.codec->framerate;
  if (const int err = avio_open(&w.format->pb, path, AVIO_FLAG_WRITE); err < 0)
    return std::string(path) + ": " + av_error(err);
  AVDictionary* mux = nullptr;
  av_dict_set(&mux, "movflags", "+faststart", 0);
  const int header = avformat_write_header(w.format, &mux);
  av_dict_free(&mux);
  if (header < 0) return "the MP4 header: " + av_error(header);
  w.header = true;
  w.frame->format = AV_PIX_FMT_YUV420P;
  w.frame->width = w.width;
  w.frame->height = w.height;
  if (av_frame_get_buffer(w.frame, 0) < 0) return "out of memory";
  w.convert = sws_getContext(w.width, w.height, AV_PIX_FMT_BGR24, w.width, w.height,
                             AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr, nullptr, nullptr);
  return w.convert == nullptr ? "no BGR to YUV converter" : "";
}

}  // namespace

extern "C" {

// A writer of H.264 in MP4 at `path` (frames of even sides), or null with the reason in `error`.
__attribute__((visibility("default"))) void* plumekit_video_open(const char* path, double fps,
                                                                 int width, int height, char* error,
                                                                 int length) {
  av_log_set_level(AV_LOG_ERROR);  // x264's statistics are not the user's business
  auto w = std::make_unique<Writer>();
  w->width = width;
  w->height = height;
  if (width <= 0 || height <= 0 || width % 2 != 0 || height % 2 != 0) {
    say(error, length, "an H.264 video's sides are even");
    return nullptr;
  }
  const std::string failed = open_writer(*w, path, fps);
  if (!failed.empty()) {
    say(error, length, failed);
    return nullptr;
  }
  return w.release();
}

// Appends one 8-bit BGR frame of the writer's size (rows `step` bytes apart); 0 on success.
__attribute__((visibility("default"))) int plumekit_video_write(void* writer,
                                                                const unsigned char* bgr,
                                                                std::size_t step) {
  auto* w = static_cast<Writer*>(writer);
  if (av_frame_make_writable(w->frame) < 0) return 1;
  const std::uint8_t* planes[1] = {bgr};
  const int strides[1] = {static_cast<int>(step)};
  sws_scale(w->convert, planes, strides, 0, w->height, w->frame->data, w->frame->linesize);
  w->frame->pts = w->next_pts++;
  return w->encode(w->frame) < 0 ? 1 : 0;
}

// Flushes the encoder, finishes the file (0 on success) and frees the writer.
__attribute__((visibility("default"))) int plumekit_video_close(void* writer) {
  auto* w = static_cast<Writer*>(writer);
  int err = 0;
  if (w->header) {
    err = w->encode(nullptr);
    if (av_write_trailer(w->format) < 0) err = -1;
  }
  delete w;
  return err < 0 ? 1 : 0;
}

// Reads the video at `path` back: its video stream's frame count (its packets, one per frame) and
// size; 0 when it could be read to the end.
__attribute__((visibility("default"))) int plumekit_video_probe(const char* path, int* frames,
                                                                int* width, int* height) {
  AVFormatContext* in = nullptr;
  if (avformat_open_input(&in, path, nullptr, nullptr) < 0) return 1;
  int result = 1;
  const int video = avformat_find_stream_info(in, nullptr) < 0
                        ? -1
                        : av_find_best_stream(in, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (video >= 0) {
    *width = in->streams[video]->codecpar->width;
    *height = in->streams[video]->codecpar->height;
    AVPacket* p = av_packet_alloc();
    int n = 0, err = 0;
    while ((err = av_read_frame(in, p)) >= 0) {
      n += p->stream_index == video;
      av_packet_unref(p);
    }
    av_packet_free(&p);
    *frames = n;
    result = err == AVERROR_EOF ? 0 : 1;
  }
  avformat_close_input(&in);
  return result;
}

}  // extern "C"
