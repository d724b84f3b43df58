#pragma once
// PNG encoding and PGM/PNG reading straight through libpng, so that the
// plumekit binary does not link OpenCV's imgcodecs: that library pulls in
// about 150 shared libraries (GDAL, GDCM, poppler, HDF5, ...), whose loading
// and relocation cost ~50 ms at every process start, longer than a 5 cm
// flow solve's coarse grids.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <opencv2/core.hpp>

namespace plumekit {

// PNG bytes of an 8-bit image with 1 (grey), 3 (BGR) or 4 (BGRA) channels.
// The settings are OpenCV's defaults for imencode(".png") (SUB filter, zlib
// level 1, RLE strategy), so the bytes are the same as OpenCV's. Throws
// std::runtime_error on other image types.
std::string encode_png(const cv::Mat& image);

// An 8-bit grey image from a binary or ASCII PGM (P5/P2) or a PNG file,
// converted as cv::imread(path, IMREAD_GRAYSCALE) would (colour to grey with
// weights 0.299/0.587/0.114, alpha dropped, 16-bit samples to their high
// byte, PGM with a maxval below 255 rescaled to 0..255). An empty image when
// the file is missing or is neither format.
cv::Mat read_gray_image(const std::filesystem::path& path);

// Big-endian 32-bit words and PNG chunks (length, type, data, the CRC-32 of type and data): what
// plumekit's own edits of PNG bytes (its mark, animated PNGs) are read and written with.
void put_be32(std::string& out, std::uint32_t value);
std::uint32_t get_be32(std::string_view bytes, std::size_t at);
std::string png_chunk(std::string_view type, std::string_view data);

}  // namespace plumekit
