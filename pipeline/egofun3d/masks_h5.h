// video_mask_path: the 2D part masks, an HDF5 file with one group per part
// label; each group has an integer attribute mask_idx (3 receptor, 4
// effector, 5 object) and a dataset "masks" of shape (T, H, W), non-zero =
// inside (h5py writes bool, uint8 or other integers; any non-zero element is
// inside). Frames are read one at a time (a hyperslab), so a long video's
// masks never sit in memory whole.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"

namespace efc::egofun3d {

struct MaskGroup {
  std::string label;  // the group's name, as in the file
  int mask_idx = 0;
  unsigned long long frames = 0, height = 0, width = 0;
};

class MaskFile {
 public:
  MaskFile() = default;
  ~MaskFile();
  MaskFile(const MaskFile&) = delete;
  MaskFile& operator=(const MaskFile&) = delete;

  // Lists the groups (name order, as h5py does). Groups without mask_idx, or
  // whose "masks" is missing or not 3-D, are E1044 errors at the file; other
  // objects at the top level are ignored. False after any error.
  bool open(const std::string& path, Diagnostics& diags);
  const std::vector<MaskGroup>& groups() const { return groups_; }

  // Frame t of group g as H*W bytes, 0 or 255, top row first.
  bool read_frame(size_t g, unsigned long long t, std::vector<uint8_t>* out, std::string* error) const;

 private:
  long long file_ = -1;  // hid_t
  std::vector<long long> datasets_;
  std::vector<MaskGroup> groups_;
};

}  // namespace efc::egofun3d
