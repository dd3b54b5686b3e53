// All-or-nothing output: a sequence is written into a hidden folder beside
// its target (same file system, so the final rename is atomic) and renamed
// into place when complete; dropped otherwise, so a failed video leaves
// nothing behind.
#pragma once

#include <string>

namespace efc::egofun3d {

class StagedFolder {
 public:
  // DIR/.<name>.importing-<pid>; removed first if a crashed run left it.
  StagedFolder(const std::string& parent, const std::string& name);
  ~StagedFolder();  // removes the staging folder unless committed
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  bool create(std::string* error);
  const std::string& path() const { return staging_; }
  const std::string& target() const { return target_; }
  // Replaces DIR/<name> (an earlier import of the same video) with the
  // staging folder. False with *error; the staging folder is then dropped.
  bool commit(std::string* error);

 private:
  std::string staging_, target_;
  bool committed_ = false;
};

}  // namespace efc::egofun3d
