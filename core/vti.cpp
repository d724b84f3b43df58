#include "core/vti.hpp"

#include <cstdint>
#include <cstring>
#include <sstream>

namespace plumekit {

namespace {

std::string base64(const std::string& bytes) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k)
      v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k)
      out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

}  // namespace

std::string vti_cell_data(const GridShape& shape, const std::vector<VtiArray>& arrays,
                          const std::string& vectors, const std::string& scalars, Vec2 origin) {
  std::ostringstream s;
  s.precision(10);
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt32\">\n"
    << "  <ImageData WholeExtent=\"0 " << shape.nx << " 0 " << shape.ny << " 0 0\" Origin=\""
    << origin.x << ' ' << origin.y << " 0\" Spacing=\"" << shape.dx() << ' ' << shape.dy()
    << " 1\">\n"
    << "    <Piece Extent=\"0 " << shape.nx << " 0 " << shape.ny << " 0 0\">\n"
    << "      <CellData" << (vectors.empty() ? std::string() : " Vectors=\"" + vectors + "\"")
    << (scalars.empty() ? std::string() : " Scalars=\"" + scalars + "\"") << ">\n";
  for (const VtiArray& a : arrays) {
    const auto size = static_cast<std::uint32_t>(a.values.size() * sizeof(float));
    std::string block(sizeof size + size, '\0');
    std::memcpy(block.data(), &size, sizeof size);  // x86: already little-endian
    std::memcpy(block.data() + sizeof size, a.values.data(), size);
    s << "        <DataArray type=\"Float32\" Name=\"" << a.name << "\" NumberOfComponents=\""
      << a.components << "\" format=\"binary\">\n          " << base64(block)
      << "\n        </DataArray>\n";
  }
  s << "      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
  return s.str();
}

}  // namespace plumekit
