#include "pipeline/egofun3d/video_import.h"

#include <filesystem>
#include <set>

#include "compiler/core/load.h"
#include "pipeline/egofun3d/annotations.h"
#include "pipeline/egofun3d/camera_poses.h"
#include "pipeline/egofun3d/intrinsics.h"
#include "pipeline/egofun3d/masks_h5.h"
#include "pipeline/egofun3d/names.h"
#include "pipeline/egofun3d/npy.h"
#include "pipeline/egofun3d/ply.h"
#include "pipeline/egofun3d/staged_folder.h"
#include "pipeline/egofun3d/truth_spec.h"
#include "pipeline/egofun3d/video.h"
#include "sequence/sequence.h"

namespace efc::egofun3d {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* role_of(int mask_idx) {
  switch (mask_idx) {
    case 3: return "receptor";
    case 4: return "effector";
    case 5: return "object";
    default: return nullptr;
  }
}

// A mask group that becomes masks/<name>/ and a meta.json part.
struct MaskPart {
  size_t group = 0;
  std::string name, role;
  bool crop = false;  // the masks are full frames: cut the stored frames' box out
};

class VideoImport {
 public:
  VideoImport(const VideoEntry& e, const JsonDoc& index, const std::string& out, Diagnostics& diags)
      : e_(e), index_(index), diags_(diags), stage_(out, e.folder) {}

  VideoResult run() {
    VideoResult r;
    if (!read_inputs()) return r;
    build_names();
    truth_ = build_truth();
    std::string error;
    if (!open_video()) return r;
    if (!stage_.create(&error)) return io_error(stage_.target(), error);
    if (!write_rgb(&r)) return r;
    if (!check_counts()) return r;
    if (!write_masks(&r)) return r;
    if (!write_poses_and_meta(&r)) return r;
    if (!write_truth(&r)) return r;
    if (!check_truth_spec()) return r;
    if (!self_check()) return r;
    if (!stage_.commit(&error)) return io_error(stage_.target(), error);
    r.ok = true;
    r.summary = std::to_string(frames_) + " frames " + std::to_string(video_.width()) + "x" +
                std::to_string(video_.height()) + (cam_.cropped ? " (cropped)" : "") + ", " +
                std::to_string(mask_parts_.size()) + " mask parts -> " + stage_.target();
    for (const std::string& n : truth_.notes) r.summary += "\n  note: " + n;
    return r;
  }

 private:
  VideoResult io_error(const std::string& file, const std::string& message) {
    diags_.error("E1048", file, 0, 0, "", message);
    VideoResult r;
    r.io_failure = true;
    return r;
  }

  // Every input file read and checked before any decoding: reports the
  // problems of all of them at once.
  bool read_inputs() {
    const size_t before = diags_.error_count();
    read_intrinsics(e_.intrinsics, e_.cropped_video, diags_, &intrinsics_doc_, &cam_);
    read_npy_matrices(e_.extrinsics, diags_, &extrinsics_);
    if (masks_.open(e_.masks, diags_)) {
      for (size_t g = 0; g < masks_.groups().size(); ++g) {
        const MaskGroup& mg = masks_.groups()[g];
        if (!role_of(mg.mask_idx)) {
          diags_.note(e_.masks + ": group '" + mg.label + "' has mask_idx " + std::to_string(mg.mask_idx) +
                      ", not 3 (receptor), 4 (effector) or 5 (object); left out");
        }
      }
    }
    const bool ply_ok = read_ply(e_.geometry, diags_, &ply_);
    if (ply_ok && e_.geometry_type == "mesh" && ply_.faces.empty())
      diags_.note(e_.geometry + ": geometry_type is \"mesh\" but the PLY has no faces; parts become boxes around "
                  "their points");
    const bool instance_ok =
        read_function_instance(e_.part_annotation, e_.function_instance_id,
                               ply_ok ? static_cast<long long>(ply_.vertices.size()) : -1, diags_, &instance_);
    if (instance_ok) {
      if (id_text(instance_.receptor.pid) == id_text(instance_.effector.pid))
        diags_.error("E1046", e_.part_annotation, 0, 0, instance_.effector.pointer,
                     "the receptor and the effector have the same pid " + id_text(instance_.effector.pid) +
                         "; a function needs two parts");
      read_articulations(e_.articulation, instance_.receptor.pid, instance_.effector.pid, diags_, &receptor_joint_,
                         &effector_joint_);
    }
    read_function_annotation(e_.function_annotation, e_.function_instance_id, diags_, &function_);
    return diags_.error_count() == before;
  }

  // meta.json parts from the mask groups (their labels made valid names);
  // the spec's receptor and effector take the receptor and effector masks'
  // names, so masks/<part>/ and the truth spec's parts line up.
  void build_names() {
    std::set<std::string> taken;
    for (size_t g = 0; g < masks_.groups().size(); ++g) {
      const MaskGroup& mg = masks_.groups()[g];
      const char* role = role_of(mg.mask_idx);
      if (!role) continue;
      MaskPart mp;
      mp.group = g;
      mp.name = unique_name(sanitize_name(mg.label), &taken);
      mp.role = role;
      mask_parts_.push_back(mp);
      if (mp.role == "receptor" && receptor_name_.empty()) receptor_name_ = mp.name;
      if (mp.role == "effector" && effector_name_.empty()) effector_name_ = mp.name;
    }
    std::set<std::string> spec_taken;
    if (receptor_name_.empty()) receptor_name_ = sanitize_name(instance_.receptor.label, "receptor");
    receptor_name_ = unique_name(receptor_name_, &spec_taken);
    if (effector_name_.empty()) effector_name_ = sanitize_name(instance_.effector.label, "effector");
    effector_name_ = unique_name(effector_name_, &spec_taken);
    base_name_ = unique_name("base", &spec_taken);
    function_name_ = sanitize_name("f" + id_text(e_.function_instance_id), "f");
  }

  TruthSpec build_truth() {
    TruthInput in;
    in.object_name = sanitize_name(e_.video_name, "egofun3d_object");
    in.receptor_name = receptor_name_;
    in.effector_name = effector_name_;
    in.base_name = base_name_;
    in.function_name = function_name_;
    in.ply = &ply_;
    in.instance = &instance_;
    in.receptor_joint = receptor_joint_;
    in.effector_joint = effector_joint_;
    in.function = function_;
    in.provenance = {{"video_name", e_.video_name},
                     {"function_instance_id", e_.function_instance_id},
                     {"receptor_label", instance_.receptor.label},
                     {"effector_label", instance_.effector.label},
                     {"receptor_pid", instance_.receptor.pid},
                     {"effector_pid", instance_.effector.pid}};
    TruthSpec t = build_truth_spec(in);
    if (!t.notes.empty()) t.spec["x-egofun3d"]["notes"] = t.notes;
    return t;
  }

  bool open_video() {
    std::string error;
    if (!video_.open(e_.video, &error)) {
      const std::string key = e_.cropped_video ? "cropped_video_path" : "original_video_path";
      diags_.error("E1041", e_.video, 0, 0, "", "the video " + error,
                   "dataset_metadata.json names it at " + index_.file() + " " + e_.pointer + "/" + key);
      return false;
    }
    // The frames must be the box the intrinsics describe.
    if (video_.width() != cam_.width() || video_.height() != cam_.height()) {
      intrinsics_doc_.error(diags_, "E1043", cam_.cropped ? "/cropped_bottom_right" : "/original_frame_size",
                            "the video's frames are " + std::to_string(video_.width()) + "x" +
                                std::to_string(video_.height()) + ", but these intrinsics describe " +
                                std::to_string(cam_.width()) + "x" + std::to_string(cam_.height()) +
                                (cam_.cropped ? " (the crop box)" : " (original_frame_size)"),
                            "the intrinsics file and the video must belong together");
      return false;
    }
    // Masks: full original frames (cropped here, as the reference loader
    // does) or already the stored frames' size.
    bool ok = true;
    for (MaskPart& mp : mask_parts_) {
      const MaskGroup& mg = masks_.groups()[mp.group];
      if (static_cast<int>(mg.width) == cam_.original_width && static_cast<int>(mg.height) == cam_.original_height) {
        mp.crop = cam_.cropped;
      } else if (static_cast<int>(mg.width) == cam_.width() && static_cast<int>(mg.height) == cam_.height()) {
        mp.crop = false;
      } else {
        diags_.error("E1044", e_.masks, 0, 0, "/" + mg.label + "/masks",
                     "group '" + mg.label + "': masks are " + std::to_string(mg.width) + "x" +
                         std::to_string(mg.height) + " (W x H), neither the original frame (" +
                         std::to_string(cam_.original_width) + "x" + std::to_string(cam_.original_height) +
                         ") nor the video's (" + std::to_string(video_.width()) + "x" +
                         std::to_string(video_.height()) + ")");
        ok = false;
      }
    }
    return ok;
  }

  bool write_rgb(VideoResult* r) {
    std::error_code ec;
    fs::create_directories(stage_.path() + "/rgb", ec);
    seq::Image8 img;
    std::string error;
    while (video_.next(&img, &error)) {
      if (!seq::write_png_rgb(stage_.path() + "/rgb/" + seq::frame_file(frames_), img, &error)) {
        *r = io_error(stage_.target() + "/rgb/" + seq::frame_file(frames_), "cannot be written: " + error);
        return false;
      }
      ++frames_;
    }
    if (!error.empty()) {
      diags_.error("E1041", e_.video, 0, 0, "", "the video " + error + " at frame " + std::to_string(frames_));
      return false;
    }
    if (frames_ == 0) {
      diags_.error("E1041", e_.video, 0, 0, "", "the video has no frames");
      return false;
    }
    return true;
  }

  // One camera pose and one mask per decoded frame.
  bool check_counts() {
    bool ok = true;
    if (extrinsics_.size() != static_cast<size_t>(frames_)) {
      diags_.error("E1042", e_.extrinsics, 0, 0, "",
                   "holds " + std::to_string(extrinsics_.size()) + " camera matrices, the video has " +
                       std::to_string(frames_) + " frames",
                   "one camera-to-world matrix per frame of the video");
      ok = false;
    }
    for (const MaskPart& mp : mask_parts_) {
      const MaskGroup& mg = masks_.groups()[mp.group];
      if (mg.frames != static_cast<unsigned long long>(frames_)) {
        diags_.error("E1044", e_.masks, 0, 0, "/" + mg.label + "/masks",
                     "group '" + mg.label + "': masks has " + std::to_string(mg.frames) + " frames (T), the video has " +
                         std::to_string(frames_),
                     "one mask per frame of the video");
        ok = false;
      }
    }
    return ok;
  }

  bool write_masks(VideoResult* r) {
    std::vector<uint8_t> full;
    std::string error;
    for (const MaskPart& mp : mask_parts_) {
      const MaskGroup& mg = masks_.groups()[mp.group];
      const std::string dir = stage_.path() + "/masks/" + mp.name;
      std::error_code ec;
      fs::create_directories(dir, ec);
      seq::Image8 img;
      img.width = cam_.width();
      img.height = cam_.height();
      img.channels = 1;
      img.pixels.resize(static_cast<size_t>(img.width) * img.height);
      for (int t = 0; t < frames_; ++t) {
        if (!masks_.read_frame(mp.group, t, &full, &error)) {
          diags_.error("E1044", e_.masks, 0, 0, "/" + mg.label + "/masks", error);
          return false;
        }
        const int x0 = mp.crop ? cam_.x0 : 0, y0 = mp.crop ? cam_.y0 : 0;
        for (int y = 0; y < img.height; ++y)
          std::copy_n(full.data() + static_cast<size_t>(y + y0) * mg.width + x0, img.width,
                      img.pixels.data() + static_cast<size_t>(y) * img.width);
        if (!seq::write_png_gray8(dir + "/" + seq::frame_file(t), img, &error)) {
          *r = io_error(stage_.target() + "/masks/" + mp.name + "/" + seq::frame_file(t), "cannot be written: " + error);
          return false;
        }
      }
    }
    return true;
  }

  bool write_poses_and_meta(VideoResult* r) {
    std::vector<seq::Pose> poses;
    std::string error;
    if (!matrices_to_poses(extrinsics_, video_.fps(), &poses, &error)) {
      diags_.error("E1042", e_.extrinsics, 0, 0, "", error);
      return false;
    }
    if (!seq::write_poses(stage_.path() + "/poses.txt", poses, &error)) {
      *r = io_error(stage_.target() + "/poses.txt", error);
      return false;
    }
    seq::Meta meta;
    meta.fps = video_.fps();
    meta.width = video_.width();
    meta.height = video_.height();
    meta.intrinsics = cam_.k;
    meta.frames = frames_;
    meta.source = "egofun3d";
    for (const MaskPart& mp : mask_parts_) meta.parts.push_back({mp.name, mp.role});
    // The function the video shows, when both of its masks are there.
    const bool has_r = std::any_of(mask_parts_.begin(), mask_parts_.end(), [&](auto& m) { return m.name == receptor_name_; });
    const bool has_e = std::any_of(mask_parts_.begin(), mask_parts_.end(), [&](auto& m) { return m.name == effector_name_; });
    if (has_r && has_e) meta.functions.push_back({function_name_, receptor_name_, effector_name_});
    json x = {{"video_name", e_.video_name},
              {"function_instance_id", e_.function_instance_id},
              {"cropped", cam_.cropped},
              {"original_frame_size", {cam_.original_width, cam_.original_height}}};
    if (!e_.source.empty()) x["source"] = e_.source;
    if (cam_.cropped) x["crop_box"] = {cam_.x0, cam_.y0, cam_.x1, cam_.y1};
    meta.extra["x-egofun3d"] = x;
    if (!seq::write_meta(stage_.path() + "/meta.json", meta, &error)) {
      *r = io_error(stage_.target() + "/meta.json", error);
      return false;
    }
    return true;
  }

  bool write_truth(VideoResult* r) {
    std::string error;
    const std::string dir = stage_.path() + "/truth";
    std::error_code ec;
    fs::create_directories(dir + "/meshes", ec);
    for (const auto& [rel, text] : truth_.meshes)
      if (!seq::write_text_file(dir + "/" + rel, text, &error)) {
        *r = io_error(stage_.target() + "/truth/" + rel, error);
        return false;
      }
    if (truth_.meshes.empty()) fs::remove(dir + "/meshes", ec);
    const json identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    if (!seq::write_text_file(dir + "/spec.json", truth_.spec.dump(2) + "\n", &error) ||
        !seq::write_text_file(dir + "/object_pose.json", json{{"object_to_world", identity}}.dump(2) + "\n", &error)) {
      *r = io_error(stage_.target() + "/truth", error);
      return false;
    }
    return true;
  }

  // The compiler's own checks on what was written: an annotation that makes
  // no valid object (a receptor without a movable joint, a geometry effect on
  // a fixed effector) fails the video. Warnings (meshes cut out of a scan are
  // rarely closed) are not shown.
  bool check_truth_spec() {
    Diagnostics local;
    LoadOptions opts;
    const std::string path = stage_.path() + "/truth/spec.json";
    if (load_spec(path, opts, local)) return true;
    for (const Diagnostic& d : local.items()) {
      if (d.severity != Severity::Error) continue;
      const auto [line, col] = index_.at(e_.pointer);
      diags_.error("E1047", index_.file(), line, col, e_.pointer,
                   "video '" + e_.video_name + "': the truth spec built from its annotations fails the compiler's " +
                       d.code + " at " + (d.pointer.empty() ? "/" : d.pointer) + ": " + d.message,
                   "check the articulation (" + e_.articulation + ") and function (" + e_.function_annotation +
                       ") annotations of function instance " + id_text(e_.function_instance_id));
    }
    return false;
  }

  // The written folder must pass the checks every consumer runs.
  bool self_check() {
    Diagnostics local;
    seq::Sequence s;
    if (s.open(stage_.path(), local) && s.check_all(local)) return true;
    for (Diagnostic d : local.items()) {
      if (d.file.rfind(stage_.path(), 0) == 0) d.file = stage_.target() + d.file.substr(stage_.path().size());
      if (d.severity == Severity::Error) {
        d.message = "the imported sequence fails its own check (" + d.code + "): " + d.message;
        d.code = "E1048";
      }
      diags_.add(d);
    }
    return false;
  }

  const VideoEntry& e_;
  const JsonDoc& index_;
  Diagnostics& diags_;
  StagedFolder stage_;
  JsonDoc intrinsics_doc_;
  CameraIntrinsics cam_;
  std::vector<Matrix4> extrinsics_;
  MaskFile masks_;
  Ply ply_;
  FunctionInstance instance_;
  JointAnnotation receptor_joint_, effector_joint_;
  FunctionAnnotation function_;
  std::vector<MaskPart> mask_parts_;
  std::string receptor_name_, effector_name_, base_name_, function_name_;
  TruthSpec truth_;
  VideoReader video_;
  int frames_ = 0;
};

}  // namespace

VideoResult import_video(const VideoEntry& entry, const JsonDoc& index, const std::string& output_dir,
                         Diagnostics& diags) {
  VideoImport job(entry, index, output_dir, diags);
  return job.run();
}

}  // namespace efc::egofun3d
