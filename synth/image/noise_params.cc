// The figures of each noise level, with where they come from.
#include "synth/image/noise.h"

namespace efc::synth {

NoiseParams noise_params(NoiseLevel level) {
  NoiseParams p;
  p.level = level;
  switch (level) {
    case NoiseLevel::None:
      break;  // every number zero / off: identity

    case NoiseLevel::Mild:
      // A good active-stereo or ToF camera at arm's length: ~2 mm at 1 m,
      // ~1 cm at 3 m, no visible quantisation.
      p.depth_sigma0_m = 0.0008;
      p.depth_sigma_k = 0.0010;
      p.depth_sigma_z0_m = 0.0;
      p.depth_min_m = 0.15;
      p.depth_max_m = 10.0;
      p.depth_grazing_start_deg = 75;
      p.depth_grazing_full_deg = 88;
      p.depth_dark_luma = 0.08;
      p.depth_dark_max_prob = 0.3;
      p.depth_speckle_prob = 0.001;
      // Head-mounted VIO over a minute: millimetres of drift.
      p.pose_walk_m = 0.002;
      p.pose_walk_deg = 0.1;
      p.pose_jitter_m = 0.0005;
      p.pose_jitter_deg = 0.02;
      // A hand-pose network on clean frames.
      p.hand_sigma_m = 0.003;
      p.hand_miss_prob = 0.02;
      // A segmenter that is right but for its outline.
      p.mask_radius_px = 1;
      p.mask_miss_prob = 0.01;
      p.mask_swap_prob = 0.0;
      break;

    case NoiseLevel::Realistic:
      // Kinect v1 / PrimeSense: sigma = 1.2 mm + 1.9 mm (z - 0.4 m)^2
      // (Nguyen, Izadi, Lovell 2012), working range 0.3..6 m, disparity
      // quantised to 1/8 pixel over a 7.5 cm baseline.
      p.depth_sigma0_m = 0.0012;
      p.depth_sigma_k = 0.0019;
      p.depth_sigma_z0_m = 0.4;
      p.depth_min_m = 0.3;
      p.depth_max_m = 6.0;
      // Beyond ~70 deg the projected pattern is too stretched to match; at
      // ~85 deg nothing comes back (same paper, Fig. 5).
      p.depth_grazing_start_deg = 70;
      p.depth_grazing_full_deg = 85;
      p.depth_dark_luma = 0.15;
      p.depth_dark_max_prob = 0.6;
      p.depth_speckle_prob = 0.005;
      // Lateral sigma ~0.8 px (same paper): shows only where depth jumps.
      p.depth_edge_shift_prob = 0.3;
      p.depth_edge_jump_rel = 0.05;
      p.depth_baseline_m = 0.075;
      p.depth_disparity_step_px = 1.0 / 8.0;
      // Monocular-ish VO: ~1 cm and ~0.5 deg per sqrt(s), visible shake.
      p.pose_walk_m = 0.01;
      p.pose_walk_deg = 0.5;
      p.pose_jitter_m = 0.002;
      p.pose_jitter_deg = 0.1;
      // Egocentric hand detectors: ~1 cm error, lost under occlusion.
      p.hand_sigma_m = 0.008;
      p.hand_miss_prob = 0.06;
      // A video segmenter: ragged outlines, lost frames, identity switches.
      p.mask_radius_px = 2;
      p.mask_miss_prob = 0.03;
      p.mask_swap_prob = 0.015;
      break;
  }
  return p;
}

}  // namespace efc::synth
