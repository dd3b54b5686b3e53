// Sensor noise for `efc synth`: the renderer gives exact depth, poses, hand
// points and masks; these models make them look like what a head-mounted
// RGB-D camera, a visual-odometry tracker, a hand detector and an instance
// segmenter deliver. Everything is reproducible from a seed: every random
// decision comes from synth/image/rng.h, seeded per frame and per stream, so
// frames may be processed in any order and in parallel.
//
// NoiseLevel::None changes nothing at all (bit-exact identity), Mild is a
// good sensor in good conditions, Realistic a consumer structured-light
// camera (Kinect v1 / PrimeSense class) with a monocular-ish tracker.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sequence/sequence.h"
#include "synth/image/rng.h"
#include "synth/suite/knobs.h"

namespace efc::synth {

struct NoiseParams {
  NoiseLevel level = NoiseLevel::None;

  // ---- depth (metres)
  // Axial noise sigma(z) = sigma0 + k (z - z0)^2: triangulation error grows
  // with the square of range (dz = z^2 / (f b) dd).
  double depth_sigma0_m = 0;
  double depth_sigma_k = 0;  // 1/m
  double depth_sigma_z0_m = 0;
  // Readings outside [min, max] are dropped (0 = no limit for min, max <= 0 = no limit).
  double depth_min_m = 0;
  double depth_max_m = 0;
  // Incidence angle (between the viewing ray and the surface normal) where
  // grazing dropouts start, and where the probability reaches 1. Both >= 90:
  // no grazing dropouts.
  double depth_grazing_start_deg = 90;
  double depth_grazing_full_deg = 90;
  // Dark surfaces: below this luminance (0..1) the dropout probability rises
  // linearly to depth_dark_max_prob at black.
  double depth_dark_luma = 0;
  double depth_dark_max_prob = 0;
  // Isolated random dropouts (speckle interference, saturation).
  double depth_speckle_prob = 0;
  // Lateral edge noise: at a depth jump larger than depth_edge_jump_rel x z, a
  // pixel takes its neighbour's reading with this probability.
  double depth_edge_shift_prob = 0;
  double depth_edge_jump_rel = 0.05;
  // Structured-light disparity quantisation: baseline (0 = none) and the
  // sub-pixel step of the disparity (pixels).
  double depth_baseline_m = 0;
  double depth_disparity_step_px = 0;

  // ---- camera poses
  // Random-walk drift, per axis: metres and degrees per sqrt(second).
  double pose_walk_m = 0;
  double pose_walk_deg = 0;
  // White per-frame jitter, per axis.
  double pose_jitter_m = 0;
  double pose_jitter_deg = 0;

  // ---- hand contact points
  double hand_sigma_m = 0;   // per axis
  double hand_miss_prob = 0; // a seen hand reported as not seen

  // ---- masks
  int mask_radius_px = 0;       // erosion or dilation by 0..radius
  double mask_miss_prob = 0;    // a mask emptied for one frame
  double mask_swap_prob = 0;    // two instances' masks exchanged for one frame
};

NoiseParams noise_params(NoiseLevel level);

// Stream ids for stream_seed(seed, frame, stream): one per model, so adding a
// model never changes another's numbers.
enum NoiseStream : uint64_t {
  kDepthStream = 1,
  kPoseStream = 2,
  kHandStream = 3,
  kMaskStream = 4,
  kMaskSwapStream = 5,
};

// ---- depth
// depth_m: width x height metres, row-major, top row first, 0 = no reading;
// the camera follows the OpenCV convention (x right, y down, z forward).
// rgb: the matching RGB frame (3 bytes per pixel) for the dark-surface
// dropouts, or null. Seed `rng` with stream_seed(seed, frame, kDepthStream).
// A depth_m of another size than width x height is left unchanged.
void add_depth_noise(const NoiseParams& params, const seq::Intrinsics& intrinsics, int width,
                     int height, const uint8_t* rgb, std::vector<float>* depth_m, Rng& rng);

// The depth PNG's units: round(z / depth_scale); 0, negative, NaN and values
// beyond 65535 units become 0 (no reading). Missing values (depth_m shorter
// than w x h) are 0.
seq::Image16 quantize_depth(const std::vector<float>& depth_m, int width, int height,
                            double depth_scale);

// ---- poses: truth plus a random walk (drift) and white jitter; same times,
// unit quaternions on the truth's side of the double cover. The walk starts
// at zero on the first frame (a tracker defines its world by its first frame).
std::vector<seq::Pose> drift_poses(const NoiseParams& params, const std::vector<seq::Pose>& truth,
                                   uint64_t seed);

// ---- hands: per-axis gaussian jitter and missed detections (seen = false,
// p = 0); a hand not seen stays not seen. Frame i uses
// stream_seed(seed, i, kHandStream).
std::vector<seq::HandPoint> jitter_hands(const NoiseParams& params,
                                         const std::vector<seq::HandPoint>& truth, uint64_t seed);

// ---- masks
// Binary masks (0 / 255 grey, non-zero = inside), one per name, same size.
struct MaskSet {
  std::vector<std::string> names;
  std::vector<seq::Image8> masks;
};

// What add_mask_noise did to one frame (for tests and truth/noise.json).
// eroded_px[i] / dilated_px[i] is the radius used for eroded[i] / dilated[i].
struct MaskNoiseLog {
  int frame = 0;
  std::vector<std::string> eroded, dilated, missed;
  std::vector<int> eroded_px, dilated_px;
  std::vector<std::pair<std::string, std::string>> swapped;
  bool empty() const {
    return eroded.empty() && dilated.empty() && missed.empty() && swapped.empty();
  }
};

// One frame's masks: first maybe a swapped-instance frame (the two masks of
// one of swap_pairs, indices into set->names, exchanged), then per mask either a missed frame
// (emptied) or an erosion or dilation by 0..mask_radius_px pixels with a disc.
// Every decision comes from stream_seed(seed, frame, ...) and the mask's name,
// so a frame gives the same result alone or in a batch, in any order. Masks
// that are not 1-channel images of their stated size are left unchanged.
MaskNoiseLog add_mask_noise(const NoiseParams& params, int frame, MaskSet* set,
                            const std::vector<std::pair<int, int>>& swap_pairs, uint64_t seed);

// Binary morphology with a disc of `radius` pixels (offsets dx^2 + dy^2 <=
// radius^2); output 0 / 255. Outside the image counts as background for
// dilation and as foreground for erosion (the frame border cuts a mask; it is
// not the object's outline). radius <= 0 only binarises.
void dilate_mask(seq::Image8* mask, int radius);
void erode_mask(seq::Image8* mask, int radius);

}  // namespace efc::synth
