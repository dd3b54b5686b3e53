#include "pipeline/egofun3d/npy.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

namespace efc::egofun3d {
namespace {

constexpr const char* kCode = "E1042";

// The value text of `key` in the header dict ("'descr': '<f8', ..."), and
// its column (1-based, counted from the start of the file as the header is
// the file's first line). Empty when absent.
std::string header_value(const std::string& header, const std::string& key, size_t header_offset, int* col) {
  const std::regex re("['\"]" + key + "['\"]\\s*:\\s*(\\([^)]*\\)|'[^']*'|\"[^\"]*\"|\\w+)");
  std::smatch m;
  if (!std::regex_search(header, m, re)) return "";
  *col = static_cast<int>(header_offset + m.position(1)) + 1;
  return m[1].str();
}

}  // namespace

bool read_npy_matrices(const std::string& path, Diagnostics& diags, std::vector<Matrix4>* out) {
  out->clear();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    diags.error(kCode, path, 0, 0, "", "the camera extrinsics file does not exist");
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto fail = [&](int col, const std::string& message, const std::string& hint = "") {
    diags.error(kCode, path, col > 0 ? 1 : 0, col, "", message,
                hint.empty() ? "save it with numpy.save(path, extrinsics.astype('<f8')), shape (N, 4, 4)" : hint);
    return false;
  };
  if (data.size() < 10 || std::memcmp(data.data(), "\x93NUMPY", 6) != 0)
    return fail(0, "is not a NumPy .npy file (no \\x93NUMPY magic)");
  const int major = static_cast<unsigned char>(data[6]);
  size_t header_len = 0, header_start = 0;
  if (major == 1) {
    header_len = static_cast<unsigned char>(data[8]) | (static_cast<unsigned char>(data[9]) << 8);
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (data.size() < 12) return fail(0, "is truncated inside the .npy header");
    header_len = 0;
    for (int i = 3; i >= 0; --i) header_len = (header_len << 8) | static_cast<unsigned char>(data[8 + i]);
    header_start = 12;
  } else {
    return fail(0, ".npy format version " + std::to_string(major) + "." +
                       std::to_string(static_cast<unsigned char>(data[7])) + " is not supported (1.0, 2.0, 3.0)");
  }
  if (header_start + header_len > data.size()) return fail(0, "is truncated inside the .npy header");
  const std::string header = data.substr(header_start, header_len);

  int col = 0;
  const std::string descr = header_value(header, "descr", header_start, &col);
  bool f8 = false;
  if (descr == "'<f8'" || descr == "'<d'" || descr == "\"<f8\"")
    f8 = true;
  else if (descr == "'<f4'" || descr == "'<f'" || descr == "\"<f4\"")
    f8 = false;
  else
    return fail(col ? col : 1, "dtype " + (descr.empty() ? std::string("(none)") : descr) +
                                   " is not supported: expected little-endian float64 '<f8' or float32 '<f4'");
  const std::string fortran = header_value(header, "fortran_order", header_start, &col);
  if (fortran != "False")
    return fail(col ? col : 1, "fortran_order " + (fortran.empty() ? std::string("(none)") : fortran) +
                                   " is not supported: expected False (C order)");
  const std::string shape = header_value(header, "shape", header_start, &col);
  std::smatch m;
  static const std::regex shape_re("^\\(\\s*(\\d+)\\s*,\\s*4\\s*,\\s*4\\s*,?\\s*\\)$");
  if (!std::regex_match(shape, m, shape_re))
    return fail(col ? col : 1, "shape " + (shape.empty() ? std::string("(none)") : shape) +
                                   " is not (N, 4, 4): expected one 4x4 camera-to-world matrix per frame");
  const unsigned long long n = std::stoull(m[1].str().substr(0, 12));
  if (n == 0) return fail(col, "shape " + shape + " holds no matrices");
  const size_t elem = f8 ? 8 : 4;
  const size_t body = header_start + header_len;
  if (n > (data.size() - body) / (16 * elem) || data.size() - body != n * 16 * elem)
    return fail(0, "holds " + std::to_string(data.size() - body) + " bytes of data, shape " + shape + " needs " +
                       std::to_string(n * 16 * elem));
  out->resize(n);
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < 16; ++k) {
      const char* p = data.data() + body + (i * 16 + k) * elem;
      double v;
      if (f8) {
        std::memcpy(&v, p, 8);  // x86-64 and arm64 are little-endian, as '<' says
      } else {
        float f;
        std::memcpy(&f, p, 4);
        v = f;
      }
      if (!std::isfinite(v)) {
        out->clear();
        return fail(0, "matrix " + std::to_string(i) + " holds a value that is not finite");
      }
      (*out)[i][k] = v;
    }
  }
  return true;
}

}  // namespace efc::egofun3d
