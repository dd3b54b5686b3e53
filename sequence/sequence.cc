// A sequence folder: opening (meta.json and what the folder holds), frames on
// demand with their size checked against meta.json, and check_all.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "compiler/frontend/json_reader.h"
#include "compiler/frontend/suggest.h"
#include "sequence/sequence.h"

namespace efc::seq {
namespace {

namespace fs = std::filesystem;

// Mask folders may be named after a role instead of a part.
const std::vector<std::string> kMaskRoles = {"receptor", "effector", "object", "hand"};

// More problems than this in one folder are counted, not listed: 300 frames
// of the wrong size are one mistake, not 300.
constexpr int kListedPerFolder = 20;

std::string join(const std::string& dir, const std::string& rel) { return (fs::path(dir) / rel).string(); }

bool is_dir(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

bool is_file(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// The frame index a file name stands for ("000123.png" -> 123), or -1.
int frame_index(const std::string& name) {
  if (name.size() < 5 || name.size() > 13) return -1;  // at most 9 digits: fits an int
  const size_t digits = name.size() - 4;
  if (name.compare(digits, 4, ".png") != 0) return -1;
  if (!std::all_of(name.begin(), name.begin() + digits, [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  const int index = std::stoi(name.substr(0, digits));
  return frame_file(index) == name ? index : -1;  // "0001.png" is not frame 1's name
}

// The frame numbers of the files a folder holds, sorted.
std::vector<int> numbered_frames(const std::string& dir) {
  std::vector<int> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const int index = frame_index(it->path().filename().string());
    if (index >= 0) out.push_back(index);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Lists a folder's first problems and counts the rest.
class FolderReport {
 public:
  FolderReport(const std::string& folder, Diagnostics& diags) : folder_(folder), diags_(diags) {}
  ~FolderReport() {
    if (hidden_ == 0) return;
    diags_.add({Severity::Note, "", folder_, 0, 0, "",
                std::to_string(hidden_) + " more problems in this folder are not listed", "", ""});
  }
  void add(const Diagnostics& local) {
    for (const Diagnostic& d : local.items()) {
      if (full()) {
        ++hidden_;
      } else {
        diags_.add(d);
        ++shown_;
      }
    }
  }
  void hide(long long problems) { hidden_ += problems; }
  bool full() const { return shown_ >= kListedPerFolder; }

 private:
  std::string folder_;
  Diagnostics& diags_;
  int shown_ = 0;
  long long hidden_ = 0;
};

// The three checks of a frame read, each adding its located error: the file
// is there, it decodes as the kind expected, it has meta.json's size.
bool frame_present(const std::string& path, const char* what, int frame, int frames, Diagnostics& diags) {
  if (frame < 0 || frame >= frames) {
    diags.error("E1003", path, 0, 0, "",
                std::string(what) + " frame " + std::to_string(frame) + " is outside the sequence (0 to " +
                    std::to_string(frames - 1) + ")");
    return false;
  }
  if (is_file(path)) return true;
  diags.error("E1003", path, 0, 0, "", std::string(what) + " frame " + std::to_string(frame) + " is missing",
              "meta.json says " + std::to_string(frames) + " frames: every one needs its file, numbered from " +
                  frame_file(0));
  return false;
}

bool frame_read(bool read_ok, const std::string& error, const std::string& path, const char* what,
                Diagnostics& diags) {
  if (!read_ok) diags.error("E1005", path, 0, 0, "", std::string(what) + " frame " + error);
  return read_ok;
}

bool frame_size(int w, int h, const Meta& meta, const std::string& path, const char* what,
                Diagnostics& diags) {
  if (w == meta.width && h == meta.height) return true;
  diags.error("E1004", path, 0, 0, "",
              std::string(what) + " frame is " + size_text(w, h) + ", meta.json says " +
                  size_text(meta.width, meta.height),
              "every frame has meta.json's width and height (the intrinsics are for that size)");
  return false;
}

// A part of meta.json's "parts" or a role (any name when "parts" is not given).
bool mask_name_known(const Meta& meta, const std::string& name) {
  if (!is_valid_name(name)) return false;
  if (meta.parts.empty()) return true;
  if (std::find(kMaskRoles.begin(), kMaskRoles.end(), name) != kMaskRoles.end()) return true;
  return std::any_of(meta.parts.begin(), meta.parts.end(), [&](const auto& p) { return p.first == name; });
}

}  // namespace

std::string frame_file(int index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06d.png", index);
  return buf;
}

bool Sequence::open(const std::string& dir, Diagnostics& diags) {
  *this = Sequence();
  dir_ = dir;
  const char* hint = "a sequence is a folder with meta.json and rgb/ (shared/spec/sequence.md)";
  std::error_code ec;
  const auto st = fs::status(dir, ec);
  if (!fs::exists(st)) {
    diags.error("E1001", dir, 0, 0, "", "no such folder", hint);
    return false;
  }
  if (!fs::is_directory(st)) {
    diags.error("E1001", dir, 0, 0, "", "is a file, not a sequence folder", hint);
    return false;
  }
  fs::directory_iterator first(dir, ec);
  if (ec) {
    diags.error("E1001", dir, 0, 0, "", "cannot list the folder (" + ec.message() + ")", hint);
    return false;
  }
  if (first == fs::directory_iterator()) {
    diags.error("E1001", dir, 0, 0, "", "the folder is empty: not a sequence", hint);
    return false;
  }
  const std::string meta_path = join(dir, "meta.json");
  if (!fs::exists(meta_path, ec)) {
    diags.error("E1001", meta_path, 0, 0, "", "no meta.json: the folder is not a sequence", hint);
    return false;
  }
  if (!read_meta(meta_path, diags, &meta_)) return false;
  has_depth_ = is_dir(join(dir, "depth"));
  has_poses_ = fs::exists(join(dir, "poses.txt"), ec);
  has_hands_ = fs::exists(join(dir, "hands.txt"), ec);
  has_truth_ = is_dir(join(dir, "truth"));
  for (fs::directory_iterator it(join(dir, "masks"), ec), end; !ec && it != end; it.increment(ec))
    if (is_dir(it->path().string())) mask_names_.push_back(it->path().filename().string());
  std::sort(mask_names_.begin(), mask_names_.end());
  return true;
}

std::string Sequence::rgb_path(int frame) const { return join(dir_, "rgb/" + frame_file(frame)); }
std::string Sequence::depth_path(int frame) const { return join(dir_, "depth/" + frame_file(frame)); }
std::string Sequence::mask_path(const std::string& name, int frame) const {
  return join(dir_, "masks/" + name + "/" + frame_file(frame));
}

bool Sequence::read_rgb(int frame, Diagnostics& diags, Image8* out) const {
  const std::string path = rgb_path(frame);
  std::string error;
  return frame_present(path, "rgb", frame, meta_.frames, diags) &&
         frame_read(read_png_rgb(path, out, &error), error, path, "rgb", diags) &&
         frame_size(out->width, out->height, meta_, path, "rgb", diags);
}

bool Sequence::read_depth(int frame, Diagnostics& diags, Image16* out) const {
  const std::string path = depth_path(frame);
  std::string error;
  return frame_present(path, "depth", frame, meta_.frames, diags) &&
         frame_read(read_png_gray16(path, out, &error), error, path, "depth", diags) &&
         frame_size(out->width, out->height, meta_, path, "depth", diags);
}

bool Sequence::read_mask(const std::string& name, int frame, Diagnostics& diags, Image8* out) const {
  const std::string path = mask_path(name, frame);
  std::string error;
  return frame_present(path, "mask", frame, meta_.frames, diags) &&
         frame_read(read_png_gray8(path, out, &error), error, path, "mask", diags) &&
         frame_size(out->width, out->height, meta_, path, "mask", diags);
}

bool Sequence::read_poses(Diagnostics& diags, std::vector<Pose>* out) const {
  return seq::read_poses(join(dir_, "poses.txt"), meta_.frames, diags, out);
}

bool Sequence::read_hands(Diagnostics& diags, std::vector<HandPoint>* out) const {
  return seq::read_hands(join(dir_, "hands.txt"), meta_.frames, diags, out);
}

bool Sequence::check_all(Diagnostics& diags) const {
  const size_t before = diags.error_count();
  // Every frame of one folder, read with `read`, then the extra files. Once
  // the report is full only the files there are read and the missing ones
  // counted: a huge "frames" over an empty folder takes no step per frame.
  auto check_folder = [&](const std::string& folder, auto read) {
    const std::string path = join(dir_, folder);
    FolderReport report(path, diags);
    const std::vector<int> present = numbered_frames(path);
    const auto beyond = std::lower_bound(present.begin(), present.end(), meta_.frames);
    int f = 0;
    for (; f < meta_.frames && !report.full(); ++f) {
      Diagnostics local;
      read(f, local);
      report.add(local);
    }
    auto rest = std::lower_bound(present.begin(), beyond, f);
    report.hide(static_cast<long long>(meta_.frames - f) - (beyond - rest));
    for (; rest != beyond; ++rest) {
      Diagnostics local;
      read(*rest, local);
      report.add(local);
    }
    for (auto extra = beyond; extra != present.end(); ++extra) {
      Diagnostics local;
      local.error("E1007", join(path, frame_file(*extra)), 0, 0, "",
                  "frame " + std::to_string(*extra) + " is beyond meta.json's \"frames\" (" +
                      std::to_string(meta_.frames) + ")",
                  "frames are numbered 0 to " + std::to_string(meta_.frames - 1) +
                      ": remove the extra files or raise \"frames\"");
      report.add(local);
    }
  };
  Image8 image;
  Image16 depth;
  if (is_dir(join(dir_, "rgb")))
    check_folder("rgb", [&](int f, Diagnostics& d) { read_rgb(f, d, &image); });
  else
    diags.error("E1003", join(dir_, "rgb"), 0, 0, "", "no rgb/ folder: rgb frames are required",
                "rgb/000000.png, rgb/000001.png, ...: 8-bit RGB, one per frame");
  if (has_depth_) check_folder("depth", [&](int f, Diagnostics& d) { read_depth(f, d, &depth); });
  for (const std::string& name : mask_names_) {
    if (!mask_name_known(meta_, name)) {
      std::vector<std::string> known = kMaskRoles;
      for (const auto& part : meta_.parts) known.push_back(part.first);
      std::string hint = frontend::did_you_mean(name, known);
      if (hint.empty()) hint = "name it after a part in \"parts\", or a role: receptor, effector, object, hand";
      diags.error("E1009", join(dir_, "masks/" + name), 0, 0, "",
                  is_valid_name(name)
                      ? "mask folder '" + name + "' is neither a part listed in meta.json's \"parts\" nor a role"
                      : "mask folder '" + name + "' is not a name (letters, digits, '_'; not starting with a digit)",
                  hint);
      continue;
    }
    check_folder("masks/" + name, [&](int f, Diagnostics& d) { read_mask(name, f, d, &image); });
  }
  std::vector<Pose> poses;
  if (has_poses_) read_poses(diags, &poses);
  std::vector<HandPoint> hands;
  if (has_hands_) read_hands(diags, &hands);
  if (has_truth_) check_truth(join(dir_, "truth"), meta_.frames, diags);
  return diags.error_count() == before;
}

}  // namespace efc::seq
