#include "core/npy.hpp"

#include <cctype>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace plumekit {

namespace {

std::string header(const char* descr, const std::vector<std::size_t>& shape) {
  std::string dims;
  for (std::size_t d : shape)
    dims += std::to_string(d) + ", ";
  if (shape.size() > 1) dims.erase(dims.size() - 2);  // (n,) keeps its comma
  std::string dict =
      "{'descr': '" + std::string(descr) + "', 'fortran_order': False, 'shape': (" + dims + "), }";
  // Magic (6) + version (2) + length (2) + dict + padding + '\n', a multiple of 64.
  const std::size_t total = 10 + dict.size() + 1;
  dict.append((64 - total % 64) % 64, ' ');
  dict += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  out += static_cast<char>(dict.size() & 0xff);
  out += static_cast<char>(dict.size() >> 8);
  return out + dict;
}

template <class T>
std::string npy_bytes(const char* descr, const std::vector<T>& values,
                      const std::vector<std::size_t>& shape) {
  std::string out = header(descr, shape);
  const std::size_t offset = out.size();
  out.resize(offset + values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(out.data() + offset, values.data(), values.size() * sizeof(T));
  return out;
}

}  // namespace

std::string npy_float64(const std::vector<double>& values, const std::vector<std::size_t>& shape) {
  return npy_bytes("<f8", values, shape);
}

std::string npy_int32(const std::vector<std::int32_t>& values,
                      const std::vector<std::size_t>& shape) {
  return npy_bytes("<i4", values, shape);
}

std::string npy_float32(const std::vector<float>& values, const std::vector<std::size_t>& shape) {
  std::string out = header("<f4", shape);
  const std::size_t offset = out.size();
  out.resize(offset + values.size() * sizeof(float));
  std::memcpy(out.data() + offset, values.data(),
              values.size() * sizeof(float));  // x86: little-endian
  return out;
}

std::string npy_float32(const std::vector<double>& values, const std::vector<std::size_t>& shape) {
  return npy_float32(std::vector<float>(values.begin(), values.end()), shape);
}

NpyArray read_npy(const std::filesystem::path& path) {
  return parse_npy(read_file(path), path);
}

namespace {

// The header of an .npy file: the element type (none of the three: another type) and width, the
// shape, and where the data starts.
struct NpyHeader {
  bool f4 = false, f8 = false, i4 = false;
  std::vector<std::size_t> shape;
  std::size_t data_offset = 0;
  std::size_t width() const { return f8 ? 8 : 4; }
  std::size_t count() const {
    return std::accumulate(shape.begin(), shape.end(), std::size_t{1}, std::multiplies<>());
  }
};

// `bytes` holds at least the header; `path` only names the file in messages.
NpyHeader parse_header(std::string_view bytes, const std::filesystem::path& path) {
  auto bad = [&](const std::string& what) { throw InputError(path.string() + ": " + what); };
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) bad("not an .npy file");
  const std::size_t len =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  if (bytes[6] != 1 || bytes.size() < 10 + len) bad("unsupported .npy version or truncated header");
  const std::string dict(bytes.substr(10, len));
  NpyHeader h;
  h.f4 = dict.find("'descr': '<f4'") != std::string::npos;
  h.f8 = dict.find("'descr': '<f8'") != std::string::npos;
  h.i4 = dict.find("'descr': '<i4'") != std::string::npos;
  if (dict.find("'fortran_order': False") == std::string::npos)
    bad("Fortran order is not supported");
  const std::size_t open = dict.find("'shape': (");
  if (open == std::string::npos) bad("header has no shape");
  std::size_t p = open + 10;
  while (p < dict.size() && dict[p] != ')') {
    if (std::isdigit(static_cast<unsigned char>(dict[p]))) {
      std::size_t used = 0;
      try {
        h.shape.push_back(std::stoull(dict.substr(p), &used));
      } catch (const std::out_of_range&) {
        bad("a dimension of the shape is too large");
      }
      p += used;
    } else {
      ++p;
    }
  }
  h.data_offset = 10 + len;
  // The byte count in bounds: a huge shape must not wrap round to the size of the data that
  // follows.
  std::size_t count = 1;
  for (const std::size_t d : h.shape) {
    if (d != 0 && count > std::numeric_limits<std::size_t>::max() / d)
      bad("the shape holds more values than memory can");
    count *= d;
  }
  // No file holds that many bytes (and data_offset + count * width must not wrap).
  if (count > (std::numeric_limits<std::size_t>::max() - h.data_offset) / 8)
    bad("data size does not match the shape (truncated?)");
  return h;
}

}  // namespace

std::vector<std::size_t> read_npy_shape(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot be read");
  std::string head(10, '\0');
  in.read(head.data(), 10);
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.size() == 10) {
    const std::size_t len =
        static_cast<unsigned char>(head[8]) | (static_cast<unsigned char>(head[9]) << 8);
    std::string dict(len, '\0');
    in.read(dict.data(), static_cast<std::streamsize>(len));
    head.append(dict, 0, static_cast<std::size_t>(in.gcount()));
  }
  const NpyHeader h = parse_header(head, path);
  if (!h.f4 && !h.f8 && !h.i4)
    throw InputError(path.string() + ": only little-endian float32/float64/int32 arrays are read");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size != h.data_offset + h.count() * h.width())
    throw InputError(path.string() + ": data size does not match the shape (truncated?)");
  return h.shape;
}

NpyArray parse_npy(std::string_view bytes, const std::filesystem::path& path) {
  const NpyHeader h = parse_header(bytes, path);
  if (!h.f4 && !h.f8)
    throw InputError(path.string() + ": only little-endian float32/float64 arrays are read");
  const bool f4 = h.f4;
  NpyArray a;
  a.shape = h.shape;
  const std::size_t count = h.count();
  if (bytes.size() != h.data_offset + count * h.width())
    throw InputError(path.string() + ": data size does not match the shape (truncated?)");
  a.values.resize(count);
  const char* data = bytes.data() + h.data_offset;
  for (std::size_t k = 0; k < count; ++k) {
    if (f4) {
      float v;
      std::memcpy(&v, data + 4 * k, 4);
      a.values[k] = v;
    } else {
      std::memcpy(&a.values[k], data + 8 * k, 8);
    }
  }
  return a;
}

}  // namespace plumekit
