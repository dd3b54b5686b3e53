#include "pipeline/egofun3d/staged_folder.h"

#include <unistd.h>

#include <filesystem>

namespace efc::egofun3d {

namespace fs = std::filesystem;

StagedFolder::StagedFolder(const std::string& parent, const std::string& name) {
  const std::string pid = std::to_string(getpid());
  staging_ = (fs::path(parent) / ("." + name + ".importing-" + pid)).string();
  target_ = (fs::path(parent) / name).string();
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

bool StagedFolder::create(std::string* error) {
  std::error_code ec;
  fs::remove_all(staging_, ec);
  if (!fs::create_directories(staging_, ec)) {
    *error = "cannot create " + staging_ + " (" + ec.message() + ")";
    return false;
  }
  return true;
}

bool StagedFolder::commit(std::string* error) {
  std::error_code ec;
  // An earlier import of the same video steps aside first, and goes only
  // once the new one is in place.
  const std::string old = staging_ + ".old";
  const bool had_old = fs::exists(target_, ec);
  if (had_old) {
    fs::remove_all(old, ec);
    fs::rename(target_, old, ec);
    if (ec) {
      *error = "cannot replace " + target_ + " (" + ec.message() + ")";
      return false;
    }
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    *error = "cannot rename " + staging_ + " to " + target_ + " (" + ec.message() + ")";
    std::error_code ignore;
    if (had_old) fs::rename(old, target_, ignore);
    return false;
  }
  committed_ = true;
  if (had_old) fs::remove_all(old, ec);
  return true;
}

}  // namespace efc::egofun3d
