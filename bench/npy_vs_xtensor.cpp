// Issue 43 ("Own less"): core/npy against xtensor's xnpy (libxtensor-dev), the library that could
// replace it: are the bytes written the same, and does xt::load_npy refuse what plumekit refuses?
// Prints one line per check; docs/own-code.md says why core/npy stays.
//
//   build/bench/npy_vs_xtensor
#include <xtensor/xarray.hpp>
#include <xtensor/xnpy.hpp>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "core/npy.hpp"

namespace {

xt::xarray<double> array(const std::vector<double>& v, const std::vector<std::size_t>& shape) {
  xt::xarray<double> a = xt::xarray<double>::from_shape(shape);
  std::copy(v.begin(), v.end(), a.begin());
  return a;
}

std::string dict(const std::string& npy) {
  return npy.substr(10, npy.find('}') - 9);
}

void compare_writers() {
  const std::vector<double> v = {1, 2, 3, 4, 5, 6};
  const std::string xt1 = xt::dump_npy(array(v, {6})), ours1 = plumekit::npy_float64(v, {6});
  const std::string xt2 = xt::dump_npy(array(v, {2, 3})), ours2 = plumekit::npy_float64(v, {2, 3});
  std::printf("write 2-D: same bytes: %s\n", xt2 == ours2 ? "yes" : "no");
  std::printf("write 1-D: same bytes: %s\n  xtensor: %s\n  plumekit: %s\n",
              xt1 == ours1 ? "yes" : "no", dict(xt1).c_str(), dict(ours1).c_str());
}

void load(const char* what, const std::string& bytes) {
  std::istringstream in(bytes);
  std::printf("%s\n  xtensor: ", what);
  try {
    const xt::xarray<double> a = xt::load_npy<double>(in);
    std::printf("loaded %zu values, no error\n", a.size());
  } catch (const std::exception& e) {
    std::printf("%s\n", e.what());
  }
  std::printf("  plumekit: ");
  try {
    const plumekit::NpyArray a = plumekit::parse_npy(bytes, "field.npy");
    std::printf("loaded %zu values\n", a.values.size());
  } catch (const std::exception& e) {
    std::printf("%s\n", e.what());
  }
}

}  // namespace

int main() {
  compare_writers();
  const std::vector<double> v = {1, 2, 3, 4, 5, 6};
  const std::string good = plumekit::npy_float64(v, {2, 3});
  load("a file cut 20 bytes short", good.substr(0, good.size() - 20));
  load("a float32 file read as numbers", plumekit::npy_float32(v, {2, 3}));
  load("not an .npy file", "not an npy file at all");
  std::string fortran = good;
  fortran.replace(fortran.find("False"), 5, "True ");
  load("Fortran order", fortran);
}
