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

bool is_contained_path(const std::string& path) {
  if (path.empty() || path.front() == '/') return false;
  size_t start = 0;
  while (true) {
    const size_t slash = path.find('/', start);
    const std::string part = path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (part.empty() || part == "." || part == "..") return false;
    for (char c : part)
      if (c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
    if (slash == std::string::npos) return true;
    start = slash + 1;
  }
}

bool write_output_files(const std::string& dir, const std::vector<OutputFile>& files,
                        Diagnostics& diags) {
  std::set<std::string> made;  // subfolders created so far
  std::string error;
  for (const OutputFile& f : files) {
    if (!is_contained_path(f.path)) {
      diags.error("E0900", dir, 0, 0, "", "refusing to write '" + f.path + "': not a path inside the output folder",
                  "this is a compiler defect: please report it with the spec");
      return false;
    }
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
