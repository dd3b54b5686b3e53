#include "synth/truth.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace efc::synth {
namespace {

using Eigen::Isometry3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using nlohmann::json;

constexpr const char* kVersion = "efc 0.1.0";

std::string csv(const std::vector<std::string>& columns, const std::vector<double>& times,
                const std::vector<std::vector<double>>& rows) {
  std::string out = "t";
  for (const std::string& c : columns) out += "," + c;
  out += "\n";
  char buf[32];
  for (size_t i = 0; i < rows.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.9g", times[i]);  // as efc play writes its log
    out += buf;
    for (double v : rows[i]) {
      std::snprintf(buf, sizeof buf, ",%.9g", v);
      out += buf;
    }
    out += "\n";
  }
  return out;
}

// Relative mesh paths of the spec (meshes inside compounds included).
void mesh_paths(const Geometry& g, std::vector<std::pair<std::string, std::string>>* out) {
  if (g.kind == GeomKind::Mesh && !g.mesh_path.empty()) out->push_back({g.mesh_path, g.mesh_resolved});
  for (const Geometry& c : g.children) mesh_paths(c, out);
}

std::vector<seq::Pose> to_world(const std::vector<seq::Pose>& sim, const Isometry3d& T) {
  std::vector<seq::Pose> out = sim;
  const Quaterniond qT(T.linear());
  for (seq::Pose& p : out) {
    const Vector3d w = T * Vector3d(p.p[0], p.p[1], p.p[2]);
    const Quaterniond q = (qT * Quaterniond(p.q[3], p.q[0], p.q[1], p.q[2])).normalized();
    p.p = {w.x(), w.y(), w.z()};
    p.q = {q.x(), q.y(), q.z(), q.w()};
  }
  return out;
}

}  // namespace

void Truth::begin(const Object& obj, const mjModel* m, const efc_mj::Controller& controller) {
  for (const Part& p : obj.parts)
    if (p.joint && p.joint->movable()) {
      joint_parts_.push_back(p.name);
      const int j = mj_name2id(m, mjOBJ_JOINT, p.name.c_str());
      joint_qpos_.push_back(j >= 0 ? m->jnt_qposadr[j] : -1);
    }
  for (int i = 0; i < controller.count(); ++i) functions_.push_back(controller.binding(i).name);
}

void Truth::record(double t, const mjData* d, const efc_mj::Controller& controller, const Vector3d& hand_point,
                   bool hand_seen) {
  times_.push_back(t);
  std::vector<double> joints;
  for (int adr : joint_qpos_) joints.push_back(adr >= 0 ? d->qpos[adr] : std::nan(""));
  joints_.push_back(std::move(joints));
  std::vector<double> effects;
  for (int i = 0; i < controller.count(); ++i) effects.push_back(controller.readout(i).s_E);
  effects_.push_back(std::move(effects));
  seq::HandPoint h;
  h.t = t;
  h.seen = hand_seen;
  h.p = {hand_point.x(), hand_point.y(), hand_point.z()};
  hands_sim_.push_back(h);
}

bool Truth::write(const Object& obj, const TruthFiles& f, std::string* error) const {
  const SynthOptions& o = *f.opts;
  const Isometry3d& T = f.layout->object_to_world;
  const NoiseParams noise = noise_params(o.knobs.noise);

  // The sensor's view (drifting poses, jittered and missed hands) and the truth.
  const std::vector<seq::Pose> poses = to_world(*f.poses_sim, T);
  std::vector<seq::HandPoint> hands = hands_sim_;
  for (seq::HandPoint& h : hands) {
    const Vector3d w = T * Vector3d(h.p[0], h.p[1], h.p[2]);
    h.p = {w.x(), w.y(), w.z()};
  }
  if (!seq::write_poses(f.dir + "/poses.txt", drift_poses(noise, poses, o.seed), error) ||
      !seq::write_poses(f.dir + "/truth/poses.txt", poses, error) ||
      !seq::write_hands(f.dir + "/hands.txt", jitter_hands(noise, hands, o.seed), error) ||
      !seq::write_hands(f.dir + "/truth/hands.txt", hands, error))
    return false;

  seq::Meta meta;
  meta.fps = o.fps;
  meta.width = o.width;
  meta.height = o.height;
  meta.intrinsics = f.intrinsics;
  meta.depth_scale = 0.001;
  meta.frames = static_cast<int>(times_.size());
  meta.parts = f.roles;
  meta.parts.push_back({"hand", "hand"});
  for (const Function& fn : obj.functions) meta.functions.push_back({fn.name, fn.receptor, fn.effector});
  meta.source = "synthetic";
  meta.extra["x-efc-synth"] = {{"generator", kVersion},
                               {"object", obj.name},
                               {"seed", o.seed},
                               {"profile", o.profile.text},
                               {"noise", to_string(o.knobs.noise)},
                               {"knobs", to_json(o.knobs)}};
  if (!seq::write_meta(f.dir + "/meta.json", meta, error)) return false;

  // truth/spec.json with its meshes beside it, so it loads where it lies.
  if (!seq::write_text_file(f.dir + "/truth/spec.json", o.spec_json, error)) return false;
  std::vector<std::pair<std::string, std::string>> meshes;
  for (const Part& p : obj.parts) mesh_paths(p.geometry, &meshes);
  for (const auto& [rel, abs] : meshes) {
    const fs::path to = fs::path(f.dir) / "truth" / fs::path(rel).lexically_normal();
    if (fs::path(rel).is_absolute() || fs::path(rel).lexically_normal().string().rfind("..", 0) == 0) {
      *error = "mesh '" + rel + "' is outside the spec's folder; truth/spec.json cannot carry it";
      return false;
    }
    std::error_code ec;
    fs::create_directories(to.parent_path(), ec);
    fs::copy_file(abs, to, fs::copy_options::overwrite_existing, ec);
    if (ec) {
      *error = "cannot copy mesh '" + abs + "': " + ec.message();
      return false;
    }
  }

  json pose = json::array();
  const Eigen::Matrix4d M = T.matrix();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) pose.push_back(M(r, c));
  if (!seq::write_text_file(f.dir + "/truth/object_pose.json", json{{"object_to_world", pose}}.dump(2) + "\n", error))
    return false;
  std::vector<std::string> effect_columns;
  for (const std::string& fn : functions_) effect_columns.push_back(fn + ".s_E");
  if (!seq::write_text_file(f.dir + "/truth/joints.csv", csv(joint_parts_, times_, joints_), error) ||
      !seq::write_text_file(f.dir + "/truth/effects.csv", csv(effect_columns, times_, effects_), error) ||
      !seq::write_text_file(f.dir + "/truth/profile.csv", profile_csv(*f.timeline), error))
    return false;

  json visits = json::array();
  for (const Visit& v : f.timeline->visits)
    visits.push_back({{"part", obj.parts[v.part].name},
                      {"reach", v.reach},
                      {"grasp", v.grasp},
                      {"release", v.release},
                      {"leave", v.leave}});
  const json timeline = {{"duration", f.timeline->duration},
                         {"approach", f.timeline->approach},
                         {"dt", o.dt},
                         {"visits", visits},
                         {"replay", "efc play truth/spec.json --profile csv:truth/profile.csv --duration " +
                                        std::to_string(f.timeline->duration) + " --dt " + std::to_string(o.dt)}};
  if (!seq::write_text_file(f.dir + "/truth/timeline.json", timeline.dump(2) + "\n", error)) return false;

  json masks = json::array();
  for (const MaskNoiseLog& log : *f.mask_noise) {
    json swapped = json::array();
    for (const auto& [a, b] : log.swapped) swapped.push_back({a, b});
    masks.push_back({{"frame", log.frame},
                     {"eroded", log.eroded},
                     {"dilated", log.dilated},
                     {"missed", log.missed},
                     {"swapped", swapped}});
  }
  const json noise_doc = {{"level", to_string(o.knobs.noise)}, {"seed", o.seed}, {"masks", masks}};
  return seq::write_text_file(f.dir + "/truth/noise.json", noise_doc.dump(2) + "\n", error);
}

}  // namespace efc::synth
