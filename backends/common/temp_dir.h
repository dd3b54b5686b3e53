// A temporary folder, made unique with mkdtemp and removed (with everything
// in it) when it goes out of scope: the harness's compiled model, the CLI's
// staging, parity's work folder.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <string>

namespace efc {

class TempDir {
 public:
  // A new folder `<parent>/<stem>-XXXXXX`; path() is empty when it could not be made.
  explicit TempDir(const std::filesystem::path& parent, const std::string& stem) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    std::string tmpl = (parent / (stem + "-XXXXXX")).string();
    if (mkdtemp(tmpl.data())) path_ = tmpl;
  }
  // Under the system's temporary folder.
  explicit TempDir(const std::string& stem) : TempDir(std::filesystem::temp_directory_path(), stem) {}
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Keeps the folder (it was moved into place): nothing is removed.
  void release() { path_.clear(); }

 private:
  std::filesystem::path path_;
};

}  // namespace efc
