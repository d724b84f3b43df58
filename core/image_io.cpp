#include "core/image_io.hpp"

#include <png.h>
#include <zlib.h>

#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <vector>

namespace plumekit {

namespace {

void append_bytes(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), size);
}

void no_flush(png_structp) {}

// libpng reports errors by longjmp; these handlers keep it quiet.
void on_error(png_structp png, png_const_charp) {
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}

}  // namespace

std::string encode_png(const cv::Mat& image) {
  if (image.depth() != CV_8U || image.empty() ||
      (image.channels() != 1 && image.channels() != 3 && image.channels() != 4))
    throw std::runtime_error(
        "encode_png: expected a non-empty 8-bit image with 1, 3 or 4 channels");
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("encode_png: out of memory");
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.rows));
  for (int r = 0; r < image.rows; ++r)
    rows[r] = const_cast<png_bytep>(image.ptr<png_byte>(r));
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("encode_png: libpng failed");
  }
  png_set_write_fn(png, &out, append_bytes, no_flush);
  // OpenCV's defaults when no compression level is given: tuned for speed.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_level(png, 1);     // Z_BEST_SPEED
  png_set_compression_strategy(png, 3);  // Z_RLE
  const int channels = image.channels();
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.cols),
               static_cast<png_uint_32>(image.rows), 8,
               channels == 1   ? PNG_COLOR_TYPE_GRAY
               : channels == 3 ? PNG_COLOR_TYPE_RGB
                               : PNG_COLOR_TYPE_RGBA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_set_bgr(png);
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return out;
}

namespace {

cv::Mat read_png(std::FILE* file) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return {};
  }
  cv::Mat image;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return {};
  }
  png_init_io(png, file);
  png_read_info(png, info);
  const int color = png_get_color_type(png, info), depth = png_get_bit_depth(png, info);
  // The transformations of OpenCV's PNG decoder for IMREAD_GRAYSCALE.
  if (depth > 8) png_set_strip_16(png);
  png_set_strip_alpha(png);
  if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if ((color & PNG_COLOR_MASK_COLOR) == 0 && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  png_set_rgb_to_gray(png, 1, 0.299, 0.587);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  image.create(static_cast<int>(png_get_image_height(png, info)),
               static_cast<int>(png_get_image_width(png, info)), CV_8UC1);
  rows.resize(static_cast<std::size_t>(image.rows));
  for (int r = 0; r < image.rows; ++r)
    rows[r] = image.ptr<png_byte>(r);
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

// PGM, binary (P5) or ASCII (P2): header fields separated by white space,
// '#' comments in the header.
cv::Mat read_pgm(const std::string& bytes) {
  std::size_t pos = 2;
  auto field = [&]() -> long {
    for (;;) {
      while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos])))
        ++pos;
      if (pos < bytes.size() && bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n')
          ++pos;
        continue;
      }
      break;
    }
    long v = 0;
    bool any = false;
    while (pos < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[pos]))) {
      v = v * 10 + (bytes[pos++] - '0');
      any = true;
      if (v > 1'000'000'000) return -1;
    }
    return any ? v : -1;
  };
  const bool binary = bytes[1] == '5';
  const long width = field(), height = field(), maxval = field();
  if (width <= 0 || height <= 0 || maxval <= 0 || maxval > 65535 || width * height > (1L << 30))
    return {};
  ++pos;  // the single white-space character after maxval
  cv::Mat image(static_cast<int>(height), static_cast<int>(width), CV_8UC1);
  const bool wide = maxval > 255;
  auto to_byte = [&](long v) -> uchar {
    if (v > maxval) v = maxval;
    if (wide) return static_cast<uchar>(v >> 8);
    return static_cast<uchar>(maxval == 255 ? v : (v * 255 + maxval / 2) / maxval);
  };
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  uchar* out = image.ptr<uchar>(0);
  if (binary) {
    const std::size_t sample = wide ? 2 : 1;
    if (bytes.size() < pos + count * sample) return {};
    for (std::size_t k = 0; k < count; ++k) {
      const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + pos + k * sample);
      out[k] = to_byte(wide ? (p[0] << 8 | p[1]) : p[0]);
    }
  } else {
    --pos;
    for (std::size_t k = 0; k < count; ++k) {
      const long v = field();
      if (v < 0) return {};
      out[k] = to_byte(v);
    }
  }
  return image;
}

}  // namespace

cv::Mat read_gray_image(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  char magic[8] = {};
  in.read(magic, sizeof magic);
  if (in.gcount() >= 2 && magic[0] == 'P' && (magic[1] == '5' || magic[1] == '2')) {
    in.clear();
    in.seekg(0);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return read_pgm(bytes);
  }
  if (in.gcount() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(magic), 0, 8) != 0)
    return {};
  in.close();
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) return {};
  return read_png(file.get());
}

void put_be32(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<char>((value >> shift) & 0xff));
}

std::uint32_t get_be32(std::string_view bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k)
    v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
  return v;
}

std::string png_chunk(std::string_view type, std::string_view data) {
  std::string out;
  put_be32(out, static_cast<std::uint32_t>(data.size()));
  std::string typed(type);
  typed += data;
  out += typed;
  put_be32(out, static_cast<std::uint32_t>(crc32(0L, reinterpret_cast<const Bytef*>(typed.data()),
                                                 static_cast<uInt>(typed.size()))));
  return out;
}

}  // namespace plumekit
