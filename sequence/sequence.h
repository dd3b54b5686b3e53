// The efc sequence format, version 1 (shared/spec/sequence.md): reading and
// writing a recording folder. Used by `efc synth` (writes), `efc infer` and
// `efc eval` (read) and `efc check-sequence` (validates).
//
//   SEQ/meta.json            required (grammar/sequence-meta.schema.json)
//   SEQ/rgb/000000.png       8-bit RGB, one per frame, numbered from 0
//   SEQ/depth/000000.png     16-bit grey, metres = value x depth_scale, 0 = none
//   SEQ/masks/<name>/...     8-bit grey, non-zero = inside
//   SEQ/poses.txt            camera-to-world per frame, TUM lines
//   SEQ/hands.txt            hand contact point per frame (t x y z | t nan nan nan)
//   SEQ/truth/               ground truth (spec.json, object_pose.json, joints.csv, effects.csv)
//
// Every problem is a located diagnostic (compiler/diagnostics.h): the file the
// user can open, and line:col for the text and JSON files. Nothing here
// aborts on bad input.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"

namespace efc::seq {

// ---- meta.json
struct Intrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels; OpenCV convention
};

struct FunctionRef {
  std::string name, receptor, effector;
};

// Roles a mask name or a part may have (meta.json "parts" values).
//   receptor, effector, receptor+effector (a chain's middle part), object
//   (a part that is neither), hand
struct Meta {
  int version = 1;  // "efc_sequence"
  double fps = 30;
  int width = 0, height = 0;
  Intrinsics intrinsics;
  double depth_scale = 0.001;  // metres per depth unit
  int frames = 0;
  std::array<double, 3> gravity{0, 0, -1};
  std::vector<std::pair<std::string, std::string>> parts;  // name -> role, file order
  std::vector<FunctionRef> functions;
  std::string source;
  // Keys this version does not know ("x-..." extensions, a writer's own
  // notes): kept so a sequence read and written back is unchanged.
  nlohmann::json extra = nlohmann::json::object();
};

// ---- poses.txt / hands.txt
struct Pose {
  double t = 0;
  std::array<double, 3> p{0, 0, 0};     // camera position in the world
  std::array<double, 4> q{0, 0, 0, 1};  // camera-to-world rotation, x y z w (TUM order)
};

struct HandPoint {
  double t = 0;
  bool seen = false;                  // false: "t nan nan nan"
  std::array<double, 3> p{0, 0, 0};   // world frame
};

// ---- images (top row first, rows packed)
struct Image8 {
  int width = 0, height = 0, channels = 0;  // 3: RGB, 1: grey
  std::vector<uint8_t> pixels;
};
struct Image16 {
  int width = 0, height = 0;
  std::vector<uint16_t> pixels;
};

// Writes `text` to `path` (removing a half-written file on failure): the one
// text writer of the sequence files (meta.json, tracks, truth/).
bool write_text_file(const std::string& path, const std::string& text, std::string* error);

// "000123.png" (six digits; more when the index needs them).
std::string frame_file(int index);

// PNG I/O. Reading converts nothing: a file of another kind (RGBA, 16-bit
// where 8 is expected, palette) is an error naming what was found. False with
// *error on failure, worded to follow "the file": "is not a PNG file", "is
// 8-bit grey, expected 8-bit RGB", "does not exist", "is corrupt (...)".
bool read_png_rgb(const std::string& path, Image8* out, std::string* error);
bool read_png_gray8(const std::string& path, Image8* out, std::string* error);
bool read_png_gray16(const std::string& path, Image16* out, std::string* error);
// compression: zlib level 0-9 (synth uses a fast level; PNG stays lossless).
// Levels 1-5 use the SUB filter only (fast), 0 none, 6-9 libpng's adaptive
// choice. A failed write removes the partial file.
bool write_png_rgb(const std::string& path, const Image8& img, std::string* error, int compression = 3);
bool write_png_gray8(const std::string& path, const Image8& img, std::string* error, int compression = 3);
bool write_png_gray16(const std::string& path, const Image16& img, std::string* error, int compression = 3);

// meta.json. read_meta checks the document against the schema's rules (types,
// required keys, positive sizes, fps > 0, intrinsics > 0, roles known,
// functions naming listed parts when "parts" is given) and reports each
// problem at its line:col with its JSON pointer. False after any error.
// Unknown top-level keys are errors unless they start with "x-" (kept in
// Meta::extra). JSON syntax errors are E0002-E0007 (as for specs), every
// other problem E1002; a missing or unreadable file E1001.
bool read_meta(const std::string& meta_path, Diagnostics& diags, Meta* out);
// The same from text already read; `file` names it in diagnostics.
bool read_meta_text(const std::string& text, const std::string& file, Diagnostics& diags, Meta* out);
// Keys in the order of shared/spec/sequence.md, then Meta::extra; integral
// numbers as integers ("fps": 30); "parts", "functions" and "source" left out
// when empty.
std::string meta_to_json_text(const Meta& meta);  // 2-space indented, trailing newline
// Refuses (false, *error) a Meta that read_meta would reject, and extra keys
// not starting with "x-".
bool write_meta(const std::string& meta_path, const Meta& meta, std::string* error);

// poses.txt and hands.txt: '#' lines and blank lines skipped; every other
// line must have 8 (poses) or 4 (hands) numbers. NaN or inf in a pose, a
// quaternion far from unit length (|1 - |q|| > 1e-3), or times not strictly
// increasing are errors at file:line:col. In hands.txt a line may be
// "t nan nan nan" (no hand); a partial nan is an error.
// Codes: E1006 for a bad line (and a file that cannot be read), E1007 for a
// count that differs from `frames`. Bad lines are left out of *out.
bool read_poses(const std::string& path, Diagnostics& diags, std::vector<Pose>* out);
bool read_hands(const std::string& path, Diagnostics& diags, std::vector<HandPoint>* out);
// The same, with the line count checked against `frames` (E1007 at the
// first line too many, or at the last line of a file too short).
bool read_poses(const std::string& path, int frames, Diagnostics& diags, std::vector<Pose>* out);
bool read_hands(const std::string& path, int frames, Diagnostics& diags, std::vector<HandPoint>* out);
// Each number as the shortest text that reads back to the same double (so a
// write then a read gives identical values); a comment header line. Refuses
// non-finite values (but "t nan nan nan" for a hand not seen).
bool write_poses(const std::string& path, const std::vector<Pose>& poses, std::string* error);
bool write_hands(const std::string& path, const std::vector<HandPoint>& hands, std::string* error);

// truth/ (every file there is optional; those present are checked):
// spec.json is a JSON object; object_pose.json holds "object_to_world", 16
// numbers with the last row 0 0 0 1; joints.csv and effects.csv have a header
// "t,<name>,..." (names unique) and one row of finite numbers per frame, times
// increasing. E1008 at file:line:col (E1007 for the row count; JSON syntax
// errors E0002-E0007). False after any error.
bool check_truth(const std::string& truth_dir, int frames, Diagnostics& diags);

// ---- a whole folder
// Opening reads meta.json and lists what the folder holds; frames are read on
// demand. Errors name the file: "SEQ/depth/000123.png: error[E1003]: ...".
class Sequence {
 public:
  // False (with diagnostics) when SEQ is not a folder, has no meta.json, or
  // meta.json is wrong; an empty folder is an error.
  bool open(const std::string& dir, Diagnostics& diags);

  const std::string& dir() const { return dir_; }
  const Meta& meta() const { return meta_; }
  bool has_depth() const { return has_depth_; }
  bool has_poses() const { return has_poses_; }
  bool has_hands() const { return has_hands_; }
  bool has_truth() const { return has_truth_; }
  const std::vector<std::string>& mask_names() const { return mask_names_; }  // sorted

  std::string rgb_path(int frame) const;
  std::string depth_path(int frame) const;
  std::string mask_path(const std::string& name, int frame) const;

  // Read one frame, checking its size against meta.json. False after adding
  // a located error (missing, unreadable, wrong size or kind).
  bool read_rgb(int frame, Diagnostics& diags, Image8* out) const;
  bool read_depth(int frame, Diagnostics& diags, Image16* out) const;
  bool read_mask(const std::string& name, int frame, Diagnostics& diags, Image8* out) const;
  // poses.txt / hands.txt, with their line count checked against "frames".
  bool read_poses(Diagnostics& diags, std::vector<Pose>* out) const;
  bool read_hands(Diagnostics& diags, std::vector<HandPoint>* out) const;

  // Validates everything: every rgb frame (and every depth and mask frame
  // when their folders exist) present, readable and of the right size, no
  // extra numbered frames beyond "frames", mask folders named after a part of
  // "parts" or a role (E1009), poses and hands parsed with one line per
  // frame, truth/ files checked when present (check_truth). Reports every
  // problem (not just the first), but lists at most 20 per frame folder and
  // counts the rest in a note; false after any error.
  bool check_all(Diagnostics& diags) const;

 private:
  std::string dir_;
  Meta meta_;
  bool has_depth_ = false, has_poses_ = false, has_hands_ = false, has_truth_ = false;
  std::vector<std::string> mask_names_;
};

}  // namespace efc::seq
