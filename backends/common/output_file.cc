#include "backends/common/output_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

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

bool write_output_files(const std::string& dir, const std::vector<OutputFile>& files,
                        Diagnostics& diags) {
  std::set<std::string> made;  // subfolders created so far
  std::string error;
  for (const OutputFile& f : files) {
    const std::string path = dir + "/" + f.path;
    const size_t slash = f.path.rfind('/');
    if (slash != std::string::npos && made.insert(f.path.substr(0, slash)).second) {
      std::error_code ec;
      const std::string sub = dir + "/" + f.path.substr(0, slash);
      std::filesystem::create_directories(sub, ec);
      if (ec) {
        diags.error("E0900", sub, 0, 0, "", "cannot create '" + sub + "': " + ec.message());
        return false;
      }
    }
    if (!write_text_file(path, f.bytes, &error)) {
      diags.error("E0900", path, 0, 0, "", "cannot write '" + path + "': " + error);
      return false;
    }
  }
  return true;
}

}  // namespace efc
