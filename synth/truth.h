// The ground truth of a synthetic sequence and the files that carry it:
// meta.json, poses.txt and hands.txt (what a sensor would report: with the
// noise model's drift and misses) and truth/ (exact): spec.json and its
// meshes, object_pose.json, joints.csv, effects.csv, poses.txt, hands.txt,
// profile.csv, timeline.json and noise.json (shared/spec/sequence.md).
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

#include <string>
#include <utility>
#include <vector>

#include "compiler/ir.h"
#include "runtime/mujoco/efc_mujoco.h"
#include "sequence/sequence.h"
#include "synth/image/noise.h"
#include "synth/scene.h"
#include "synth/synth.h"
#include "synth/timeline.h"

namespace efc::synth {

// What Truth::write needs besides what it recorded.
struct TruthFiles {
  std::string dir;  // the sequence folder
  const Layout* layout = nullptr;
  const Timeline* timeline = nullptr;
  const std::vector<seq::Pose>* poses_sim = nullptr;  // camera poses, simulation frame
  seq::Intrinsics intrinsics;
  const SynthOptions* opts = nullptr;
  const std::vector<std::string>* mask_names = nullptr;
  const std::vector<MaskNoiseLog>* mask_noise = nullptr;
  std::vector<std::pair<std::string, std::string>> roles;  // part -> role
};

class Truth {
 public:
  // Columns: every movable joint (by part) and every function's s_E.
  void begin(const Object& obj, const mjModel* m, const efc_mj::Controller& controller);
  // One frame: joints and effects as the playback has them now; the hand's
  // point (simulation frame) and whether the camera sees it.
  void record(double t, const mjData* d, const efc_mj::Controller& controller, const Eigen::Vector3d& hand_point,
              bool hand_seen);
  bool write(const Object& obj, const TruthFiles& files, std::string* error) const;

 private:
  std::vector<std::string> joint_parts_;
  std::vector<int> joint_qpos_;  // qpos address of each, -1 if the model lacks it
  std::vector<std::string> functions_;
  std::vector<std::vector<double>> joints_, effects_;  // per frame
  std::vector<double> times_;
  std::vector<seq::HandPoint> hands_sim_;
};

}  // namespace efc::synth
