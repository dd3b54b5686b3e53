// efc infer, stage 1: what the recording shows of each part, frame by frame.
// Each part's mask pixels (sequence masks, or the motion fallback's) are
// back-projected through the depth and the camera pose given in poses.txt,
// so every later stage works on 3D points in the (still drifting) world
// frame. The hand's mask is not a part: its pixels are never points.
#pragma once

#include <Eigen/Geometry>

#include <functional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "pipeline/cloud/cloud.h"
#include "sequence/sequence.h"

namespace efc::pipeline {

using ProgressFn = std::function<void(const std::string&)>;

struct PartFrames {
  std::string name, role;       // role from meta.json (receptor, effector, object, ...)
  std::string mask;             // the mask folder its pixels come from
  std::vector<Cloud> clouds;    // per frame, world frame of poses.txt; empty when unseen
  std::vector<int> pixels;      // mask pixels per frame (before the depth test)
  // Per frame, the points just outside the mask (within kOutlinePixels of
  // it), thinned as `clouds` were: what a mask drawn a pixel or two too
  // wide takes in (the face behind a knob's rim, the wall beside a body).
  // Reconstruction keeps only the voxels more frames put inside the mask
  // than just outside it. Empty with the motion fallback.
  std::vector<Cloud> outlines;
};

// How far outside a mask its outline reaches: a segmenter's outline error
// is a band a pixel or two wide (the synthetic realistic noise: up to 2).
constexpr int kOutlinePixels = 3;

struct Observations {
  std::vector<double> times;                       // per frame (poses.txt)
  std::vector<Eigen::Isometry3d> camera_to_world;  // per frame, as poses.txt gives them
  std::vector<seq::HandPoint> hands;               // per frame; empty without hands.txt
  std::vector<PartFrames> parts;
  // The room around the object: per frame, the near pixels no mask claims
  // (no part, not the hand), world frame of poses.txt. Static like the body,
  // and it closes the body's blind directions: a camera close to a fridge
  // sees one plane, which cannot fix a slide along itself or a turn about
  // its normal; the floor and the wall beside it can. Empty with the motion
  // fallback (no masks, so no telling the room from the object).
  std::vector<Cloud> background;
  // The hand's own points per frame (world frame of poses.txt): its mask's
  // pixels within kHandCloudRadius of its hands.txt point, for the grip's
  // track (grip_track.h). Empty without a hand mask or hands.txt; an empty
  // cloud where the hand is not seen.
  std::vector<Cloud> hand_clouds;
  bool motion_masks = false;  // the masks came from the motion fallback
};

// The hand's points kept around its hands.txt point: the grip's radius
// (kGripRadius, grip_track.h) and the hand detector's error on top.
constexpr double kHandCloudRadius = 0.15;

struct ObserveOptions {
  int stride = 2;                 // back-project every stride-th pixel in x and y
  int max_points_static = 6000;   // per frame, for parts of role "object"
  int max_points_moving = 3000;   // per frame, for the others
  int threads = 2;
  // The background: every background_stride-th pixel, nearer than
  // background_max_depth (farther, a consumer depth camera's noise is
  // centimetres: it would blur the model more than it constrains it), at
  // most max_points_background per frame. background false: none.
  bool background = true;
  int background_stride = 4;
  double background_max_depth = 2.0;
  int max_points_background = 4000;
};

// Camera-to-world of a poses.txt line.
Eigen::Isometry3d pose_to_isometry(const seq::Pose& pose);

// Reads every frame's depth and masks (in parallel) and fills *out. Needs
// depth and poses (E1050 / E1051 name what is missing and how to supply it);
// a frame that cannot be read is a located error. False after any error.
// `masks` names, per part, the mask folder to read ("" = the part's own name);
// parts without a folder are left out with a warning (E1052).
bool observe(const seq::Sequence& sequence, const ObserveOptions& options, Diagnostics& diags,
             const ProgressFn& progress, Observations* out);

}  // namespace efc::pipeline
