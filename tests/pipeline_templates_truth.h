// A TemplateInput built from a synthetic sequence's ground truth (truth/spec.json,
// joints.csv, poses.txt, object_pose.json), so the function-template stage is
// tested alone, without the geometric stages before it.
#pragma once

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "compiler/core/load.h"
#include "pipeline/templates/template_input.h"
#include "sequence/sequence.h"
#include "tests/truth_csv.h"

namespace efc::test {

struct TruthInput {
  seq::Sequence sequence;
  pipeline::TemplateInput input;
  std::optional<Object> spec;
};

inline Eigen::Isometry3d joint_motion(const Joint& j, double q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d a(j.axis[0], j.axis[1], j.axis[2]), o(j.origin[0], j.origin[1], j.origin[2]);
  if (j.type == JointType::Prismatic) T.translate(a * q);
  else if (j.type != JointType::Fixed) {
    T.translate(o);
    T.rotate(Eigen::AngleAxisd(q, a.normalized()));
    T.translate(-o);
  }
  return T;
}

// False with *why when the sequence or its truth does not load.
inline bool load_truth_input(const std::string& seq_dir, TruthInput* t, std::string* why) {
  Diagnostics diags;
  if (!t->sequence.open(seq_dir, diags)) {
    *why = "sequence does not open";
    return false;
  }
  const seq::Meta& meta = t->sequence.meta();
  t->spec = load_spec(seq_dir + "/truth/spec.json", LoadOptions{}, diags);
  if (!t->spec) {
    *why = "truth spec does not load";
    return false;
  }
  std::vector<seq::Pose> poses;
  if (!seq::read_poses(seq_dir + "/truth/poses.txt", diags, &poses) || static_cast<int>(poses.size()) != meta.frames) {
    *why = "truth poses do not load";
    return false;
  }
  pipeline::TemplateInput& in = t->input;
  in.sequence = &t->sequence;
  for (const seq::Pose& p : poses) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translate(Eigen::Vector3d(p.p[0], p.p[1], p.p[2]));
    T.rotate(Eigen::Quaterniond(p.q[3], p.q[0], p.q[1], p.q[2]).normalized());
    in.camera_to_world.push_back(T);
  }
  std::ifstream pose_in(seq_dir + "/truth/object_pose.json");
  const nlohmann::json op = nlohmann::json::parse(pose_in, nullptr, false);
  if (op.is_discarded() || !op.contains("object_to_world")) {
    *why = "object_pose.json does not load";
    return false;
  }
  Eigen::Matrix4d M;
  for (int i = 0; i < 16; ++i) M(i / 4, i % 4) = op["object_to_world"][i].get<double>();
  in.object_to_world.matrix() = M;
  const auto joints = read_joints_csv(seq_dir + "/truth/joints.csv");
  std::map<std::string, std::string> roles(meta.parts.begin(), meta.parts.end());
  const Object& obj = *t->spec;
  // Parts' motions, parents first (a child moves with its parent).
  std::map<std::string, std::vector<Eigen::Isometry3d>> motions;
  std::function<const std::vector<Eigen::Isometry3d>&(const Part&)> motion_of = [&](const Part& p) -> const std::vector<Eigen::Isometry3d>& {
    auto it = motions.find(p.name);
    if (it != motions.end()) return it->second;
    std::vector<Eigen::Isometry3d> m(meta.frames, Eigen::Isometry3d::Identity());
    if (p.joint) {
      for (const Part& parent : obj.parts)
        if (parent.name == p.joint->parent) {
          const auto& pm = motion_of(parent);
          for (int f = 0; f < meta.frames; ++f) m[f] = pm[f];
        }
      auto q = joints.find(p.name);
      if (q != joints.end())
        for (int f = 0; f < meta.frames && f < static_cast<int>(q->second.size()); ++f)
          m[f] = m[f] * joint_motion(*p.joint, q->second[f]);
    }
    return motions[p.name] = m;
  };
  for (const Part& p : obj.parts) {
    pipeline::PartObservation o;
    o.name = p.name;
    o.role = roles.count(p.name) ? roles[p.name] : "object";
    const JointType jt = p.joint ? p.joint->type : JointType::Fixed;
    o.joint_type = jt == JointType::Fixed ? "fixed" : jt == JointType::Revolute ? "revolute"
                                                   : jt == JointType::Continuous ? "continuous" : "prismatic";
    if (p.joint && jt != JointType::Fixed) {
      o.axis = Eigen::Vector3d(p.joint->axis[0], p.joint->axis[1], p.joint->axis[2]);
      o.origin = Eigen::Vector3d(p.joint->origin[0], p.joint->origin[1], p.joint->origin[2]);
      if (p.joint->has_range) o.range_lo = p.joint->lo, o.range_hi = p.joint->hi;
      auto q = joints.find(p.name);
      if (q != joints.end()) o.q = q->second;
    }
    o.motion = motion_of(p);
    o.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(p.bbox_min[0], p.bbox_min[1], p.bbox_min[2]),
                                   Eigen::Vector3d(p.bbox_max[0], p.bbox_max[1], p.bbox_max[2]));
    in.parts.push_back(std::move(o));
  }
  in.functions = meta.functions;
  return true;
}

}  // namespace efc::test
