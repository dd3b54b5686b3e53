#include "backends/output_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>

namespace efc {

bool write_text_file(const std::string& path, const std::string& text, std::string* error) {
  std::ofstream out(path, std::ios::binary);
  if (!out) {
    *error = std::strerror(errno);
    return false;
  }
  out << text;
  out.close();
  if (!out) {
    *error = "write failed";
    return false;
  }
  return true;
}

}  // namespace efc
