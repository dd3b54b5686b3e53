// efc infer, stage 2's last step: where the refined camera path sits in the
// world. Registering every frame onto one model of the static scene makes
// the poses consistent with each other, up to one rigid transform A (model
// frame -> world) that the registration cannot see. poses.txt says where the
// world is, through a tracker whose error D_f is a random walk from zero
// (drift) plus white noise (jitter): A = D_f^-1 C_f^-1 in every frame f
// (C_f: frame f's correction, tracker world -> model), so each frame
// measures A with an error whose spread grows with time.
//
// The estimate is the weighted mean of the C_f^-1 with the generalised
// least-squares weights of that error model, Cov(f, g) = w^2 min(t_f, t_g) +
// j^2 [f = g] (t from the recording's first frame): the first frames count
// most, how much more than later ones set by w against j. Both are read
// off the corrections themselves: the object's centre, carried by C_f^-1,
// moves between two frames dt apart by 2 j^2 + w^2 dt in mean square per
// axis (the constant A cancels), fitted over every pair up to a second
// apart. A tracker that does not drift (w = 0) gives every frame the same
// weight; one that does not shake, the first frame all of it. The mean of
// the first second's corrections, which this replaces, left the object
// 2 to 3 cm from where it is (bench/ego_motion_eval: the camera's walk in
// turns about its own centre, metres from the object).
#pragma once

#include <Eigen/Geometry>

#include <vector>

namespace efc::pipeline {

struct EgoAnchor {
  Eigen::Isometry3d model_to_world = Eigen::Isometry3d::Identity();  // A
  double jitter_m = 0;          // j: the white noise per axis, at the centre (m)
  double walk_m_per_sqrt_s = 0;  // w: the drift per axis per sqrt(second), at the centre
  int frames = 0;               // registered frames that carried weight
  double weight_first_second = 0;  // the share of the weight within a second of the start
};

// `times` (s), `correction` (C_f) and `registered` per frame; `centre`: a
// point of the static scene in the model frame (its centroid), where the
// errors are measured. Unregistered frames carry no weight. With no
// registered frame, the identity.
EgoAnchor anchor_refined_world(const std::vector<double>& times, const std::vector<Eigen::Isometry3d>& correction,
                               const std::vector<bool>& registered, const Eigen::Vector3d& centre);

}  // namespace efc::pipeline
