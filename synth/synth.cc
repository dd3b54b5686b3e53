#include "synth/synth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <thread>

#include "backends/common/naming.h"
#include "backends/common/temp_dir.h"
#include "harness/mujoco_errors.h"
#include "harness/playback.h"
#include "harness/render.h"
#include "synth/camera_path.h"
#include "synth/effect_visuals.h"
#include "synth/frame_writer.h"
#include "synth/hand.h"
#include "synth/image/preview.h"
#include "synth/scene.h"
#include "synth/timeline.h"
#include "synth/truth.h"

namespace fs = std::filesystem;

namespace efc::synth {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

constexpr const char* kHandMask = "hand";

// Focal length of a 525-pixel Kinect-like camera at 640 wide, scaled.
seq::Intrinsics intrinsics_for(int width, int height) {
  seq::Intrinsics K;
  K.fx = K.fy = 525.0 * width / 640.0;
  K.cx = 0.5 * (width - 1);
  K.cy = 0.5 * (height - 1);
  return K;
}

std::string role_of(const Object& obj, int part) {
  bool receptor = false, effector = false;
  for (const Function& f : obj.functions) {
    receptor |= f.receptor_index == part;
    effector |= f.effector_index == part;
  }
  if (receptor && effector) return "receptor+effector";
  if (receptor) return "receptor";
  if (effector) return "effector";
  return "object";
}

uint64_t folder_bytes(const fs::path& dir) {
  uint64_t total = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_regular_file(ec)) total += it->file_size(ec);
  return total;
}

}  // namespace

int synthesize(const Object& obj, const SynthOptions& opts, const std::string& out_dir, Diagnostics& diags,
               SynthStats* stats) {
  const auto wall_start = std::chrono::steady_clock::now();
  for (const Part& p : obj.parts)
    if (p.name == kHandMask) {
      diags.error("E1010", obj.file, p.loc.line, p.loc.col, p.loc.pointer,
                  "a part named 'hand' would share its mask folder with the hand's (masks/hand/)",
                  "rename the part");
      return 1;
    }
  const double duration = opts.frames / opts.fps;
  const Layout layout = plan_layout(obj, opts.knobs);
  const Timeline timeline = plan_timeline(obj, opts.profile, duration, opts.dt);
  const seq::Intrinsics K = intrinsics_for(opts.width, opts.height);

  SceneExtras extras;
  extras.width = opts.width;
  extras.height = opts.height;
  extras.fovy_deg = 2 * std::atan(0.5 * opts.height / K.fy) * 180 / M_PI;
  for (const Function& f : obj.functions) {
    if (f.effect.type == EffectType::Airflow) extras.air.push_back({f.name, kAirMotes});
    if (f.effect.type == EffectType::Illumination) extras.glow_functions.push_back(f.name);
  }
  extras.hand_xml = hand_body_xml(opts.knobs, layout.center_object + Vector3d(0, 0, layout.radius + 2.0));

  Playback run;
  const int open_rc = run.open(obj, timeline.profile, duration, opts.dt, diags,
                               [&](std::string* mjcf, std::string* error) {
                                 return build_scene_mjcf(obj, layout, opts.knobs, extras, mjcf, error);
                               });
  if (open_rc) return open_rc;
  mjModel* m = run.model();
  mjData* d = run.data();
  const efc_mj::Controller& controller = run.controller();
  // Near and far planes in metres (they are stored relative to the extent).
  m->vis.map.znear = static_cast<float>(0.02 / m->stat.extent);
  m->vis.map.zfar = static_cast<float>(40.0 / m->stat.extent);
  const int camera = mj_name2id(m, mjOBJ_CAMERA, kCamera);
  const int head = mj_name2id(m, mjOBJ_BODY, kHeadBody);
  const int hand = mj_name2id(m, mjOBJ_BODY, kHandBody);
  OffscreenRenderer renderer(m, opts.width, opts.height);
  if (!renderer.ok()) {
    diags.error("E0902", obj.file, 0, 0, "", "offscreen rendering unavailable: " + renderer.error());
    return 2;
  }
  if (renderer.width() != opts.width || renderer.height() != opts.height) {
    diags.error("E0902", obj.file, 0, 0, "",
                "the renderer offers " + std::to_string(renderer.width()) + "x" + std::to_string(renderer.height()) +
                    ", not " + std::to_string(opts.width) + "x" + std::to_string(opts.height));
    return 2;
  }

  // Grasps, the gaze and the camera path, planned from the state at t = 0.
  const Vector3d eye = standing_eye(layout, opts.knobs);
  std::vector<Grasp> grasps;
  for (const Visit& v : timeline.visits) grasps.push_back(plan_grasp(obj, v.part, m, d, eye));
  std::vector<Vector3d> focus(opts.frames);
  for (int f = 0; f < opts.frames; ++f) {
    const double t = f / opts.fps;
    Vector3d target = layout.center_object;
    for (size_t i = 0; i < grasps.size(); ++i) {
      const Visit& v = timeline.visits[i];
      const double w = smoothstep((t - v.reach + 0.3) / 0.4) * (1 - smoothstep((t - v.leave + 0.1) / 0.4));
      if (w > 0) target += w * (grasps[i].point(d) - target);
    }
    focus[f] = target;
  }
  const std::vector<CameraPose> path =
      plan_camera_path(layout, opts.knobs, focus, opts.fps, timeline.approach, opts.seed);

  // Masks: every part's geoms, and the hand's.
  std::vector<std::string> mask_names;
  std::map<int, int> body_mask;
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    mask_names.push_back(obj.parts[i].name);
    const int b = mj_name2id(m, mjOBJ_BODY, obj.parts[i].name.c_str());
    if (b >= 0) body_mask[b] = static_cast<int>(i);
  }
  mask_names.push_back(kHandMask);
  body_mask[hand] = static_cast<int>(mask_names.size()) - 1;
  std::vector<int> geom_mask(m->ngeom, -1);
  for (int g = 0; g < m->ngeom; ++g) {
    auto it = body_mask.find(m->geom_bodyid[g]);
    if (it != body_mask.end()) geom_mask[g] = it->second;
  }
  std::vector<std::pair<int, int>> swap_pairs;
  for (const Function& f : obj.functions)
    if (f.receptor_index != f.effector_index) swap_pairs.push_back({f.receptor_index, f.effector_index});

  const Vector3d parked = layout.center_object + Vector3d(0, 0, layout.radius + 50.0);
  EffectVisuals visuals(obj, m, controller, parked, opts.seed);

  // The folder is built beside its final place and renamed at the end.
  const fs::path final_dir = fs::absolute(out_dir);
  std::error_code ec;
  fs::create_directories(final_dir.parent_path(), ec);
  TempDir staging(final_dir.parent_path(), "." + final_dir.filename().string() + ".partial");
  if (staging.path().empty()) {
    diags.error("E0900", out_dir, 0, 0, "", "cannot create a folder beside '" + out_dir + "'");
    return 2;
  }
  const std::string dir = staging.path().string();
  std::vector<std::string> folders = {"rgb", "depth", "truth"};
  for (const std::string& name : mask_names) folders.push_back("masks/" + name);
  for (const std::string& sub : folders)
    if (!ec) fs::create_directories(dir + "/" + sub, ec);
  if (ec) {
    diags.error("E0900", out_dir, 0, 0, "", "cannot create folders: " + ec.message());
    return 2;
  }

  FrameWriterConfig wc;
  wc.dir = dir;
  wc.intrinsics = K;
  wc.noise = noise_params(opts.knobs.noise);
  wc.seed = opts.seed;
  wc.mask_names = mask_names;
  wc.geom_mask = geom_mask;
  wc.swap_pairs = swap_pairs;
  wc.png_compression = opts.png_compression;
  wc.threads = opts.threads > 0 ? opts.threads : std::max(1u, std::thread::hardware_concurrency());
  // The preview shows the middle of the first operation (the hand on the part).
  wc.preview_frame = opts.preview ? std::clamp(static_cast<int>(std::lround(
                                                   (timeline.visits.empty() ? 0.5 * duration
                                                                            : 0.5 * (timeline.visits[0].grasp +
                                                                                     timeline.visits[0].release)) *
                                                   opts.fps)),
                                               0, opts.frames - 1)
                                  : -1;
  FrameWriter writer(wc);

  Truth truth;
  truth.begin(obj, m, controller);
  std::vector<seq::Pose> poses_sim(opts.frames);
  const long last_step = std::lround((opts.frames - 1) / opts.fps / opts.dt);
  int frame = 0;
  double render_seconds = 0;
  auto last_progress = std::chrono::steady_clock::now();
  try {
    for (long k = 0; k <= last_step && frame < opts.frames; ++k) {
      const double t = k * opts.dt;
      run.control(t);
      if (k == std::lround(frame / opts.fps / opts.dt)) {
        const double tf = frame / opts.fps;
        const CameraPose& cam = path[frame];
        set_mocap(m, d, head, cam.position, mujoco_camera_quat(cam.rotation));
        const HandState hand_now = hand_at(tf, cam, grasps, timeline.visits, d);
        set_mocap(m, d, hand, hand_now.pose.translation(), Quaterniond(hand_now.pose.linear()));
        visuals.update(m, d, controller, 1 / opts.fps);
        mj_kinematics(m, d);
        mj_camlight(m, d);
        const auto r0 = std::chrono::steady_clock::now();
        OffscreenRenderer::Views views;
        if (!renderer.render_views(m, d, camera, true, true, &views)) {
          diags.error("E0902", obj.file, 0, 0, "", renderer.error());
          return 2;
        }
        render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
        // hands.txt: the contact point while holding, else the fingertips
        // when they are in the picture.
        const Vector3d hand_point = hand_now.holding ? hand_now.holding->point(d) : hand_now.pose.translation();
        const Vector3d in_cam = cam.rotation.transpose() * (hand_point - cam.position);
        const double u = K.fx * in_cam.x() / in_cam.z() + K.cx, v = K.fy * in_cam.y() / in_cam.z() + K.cy;
        const bool seen = hand_now.holding || (in_cam.z() > 0.05 && u >= 0 && u <= opts.width - 1 && v >= 0 &&
                                      v <= opts.height - 1);
        truth.record(tf, d, controller, hand_point, seen);
        seq::Pose& pose = poses_sim[frame];
        pose.t = tf;
        for (int c = 0; c < 3; ++c) pose.p[c] = cam.position[c];
        const Quaterniond qc(cam.rotation);
        pose.q = {qc.x(), qc.y(), qc.z(), qc.w()};
        writer.push(frame, std::move(views));
        ++frame;
        const auto now = std::chrono::steady_clock::now();
        if (opts.progress && (now - last_progress > std::chrono::milliseconds(500) || frame == opts.frames)) {
          last_progress = now;
          const double elapsed = std::chrono::duration<double>(now - wall_start).count();
          const double rate = frame / std::max(elapsed, 1e-9);
          char line[128];
          std::snprintf(line, sizeof line, "synth: frame %d/%d, %.1f frames/s, %.0f s left", frame, opts.frames,
                        rate, (opts.frames - frame) / std::max(rate, 1e-9));
          opts.progress(line);
        }
      }
      if (k < last_step) run.advance();
    }
  } catch (const MujocoError& e) {
    diags.error("E0901", obj.file, 0, 0, "", e.what());
    return 1;
  }
  std::string error;
  if (!writer.finish(&error)) {
    diags.error("E0900", out_dir, 0, 0, "", error);
    return 2;
  }
  for (const std::string& w : take_mujoco_warnings())
    diags.warning("W0901", obj.file, 0, 0, "", "MuJoCo warned during synthesis: " + w);

  TruthFiles files;
  files.dir = dir;
  files.layout = &layout;
  files.timeline = &timeline;
  files.poses_sim = &poses_sim;
  files.intrinsics = K;
  files.opts = &opts;
  files.mask_names = &mask_names;
  files.mask_noise = &writer.mask_noise();
  for (size_t i = 0; i < obj.parts.size(); ++i) files.roles.push_back({obj.parts[i].name, role_of(obj, static_cast<int>(i))});
  if (!truth.write(obj, files, &error)) {
    diags.error("E0900", out_dir, 0, 0, "", error);
    return 2;
  }
  if (opts.preview) {
    std::vector<std::pair<std::string, const seq::Image8*>> masks;
    for (size_t i = 0; i < mask_names.size() && i < writer.preview_masks().size(); ++i)
      masks.push_back({mask_names[i], &writer.preview_masks()[i]});
    if (!write_contact_sheet(dir + "/preview.png", writer.preview_rgb(), writer.preview_depth(), 0.001, masks,
                             &error)) {
      diags.error("E0900", out_dir, 0, 0, "", error);
      return 2;
    }
  }

  // Into place: an existing sequence there is replaced, anything else kept.
  if (fs::exists(final_dir)) {
    if (!fs::is_directory(final_dir) || (!fs::is_empty(final_dir) && !fs::exists(final_dir / "meta.json"))) {
      diags.error("E0910", out_dir, 0, 0, "", "'" + out_dir + "' exists and is not a sequence folder; not replacing it",
                  "choose another -o or remove it");
      return 2;
    }
    TempDir old(final_dir.parent_path(), "." + final_dir.filename().string() + ".old");
    fs::rename(final_dir, old.path() / "seq", ec);
  }
  if (!ec) fs::rename(staging.path(), final_dir, ec);
  if (ec) {
    diags.error("E0900", out_dir, 0, 0, "", "cannot move the sequence into place: " + ec.message());
    return 2;
  }
  staging.release();
  if (stats) {
    stats->frames = frame;
    stats->render_seconds = render_seconds;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    stats->bytes = folder_bytes(final_dir);
  }
  return 0;
}

}  // namespace efc::synth
