// What changes at an effector, frame by frame, read from the recording's
// pixels: one signal per image-borne effect hypothesis (geometry needs no
// pixels: it is the effector's own joint position).
//   glow      mean luminance of the effector's pixels (a lamp's emission)
//   heat      how much red-hot the effector's mean colour holds
//             (hot_component(): the runtime blends a heated part towards
//             red-hot; shading and a lamp's emission scale the channels
//             alike and leave it at 0 while the part is cool)
//   droplets  area (m^2 at the effector's distance) of small water-blue
//             blobs whose ray passes through the space below, around or
//             above the effector
//   motes     the same for small near-white streaks brighter than what is
//             behind them (air motes)
// The renderers' materials decide the colours: droplets (0.35, 0.55, 0.95),
// motes (0.92, 0.95, 1); shading scales channels alike, so the tests are on
// the channels' order and spread (frame_signals.cc, blob_kind).
// Effector pixels: its mask's core (eroded up to 2 px while pixels remain: a
// segmenter's grown outline takes in the neighbours' colour) where the depth
// agrees with the part's box, the hand's pixels left out.
// A blob pixel: in no part's mask nor the (grown) hand's, unlike both of its
// neighbours 1-3 px away across a row or a column while those two are alike
// (a droplet or a mote's streak, not the edge between two surfaces). A
// mote's streak is thin as well: a candidate most of whose neighbourhood
// (8 px around) shares its colour is a lit patch of a surface (a shadow's
// ragged edge on a white floor), not a mote. A blob whose ray passes
// through several effectors' spaces counts once, for the effector whose
// box the ray passes nearest (a vent's motes rising past a lamp beside it
// are the vent's). Blobs are found in colour, not depth: droplets and motes are translucent, and
// translucent bodies leave no depth. Their ray must enter the space in
// question before the surface the depth sees. Frames where that space is out
// of view, or the effector has no pixels, are NaN (not observed).
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "pipeline/templates/template_input.h"

namespace efc::pipeline {

struct EffectorSignals {
  std::vector<double> glow, heat, droplets, motes;  // per frame; NaN = not observed
  std::vector<Eigen::Vector3d> colour;               // mean colour of its pixels (heat: hot_component())
  // Luminance of the static surfaces around the effector (the blobs' search
  // space; the hand and the movable parts left out), each 2 cm object-frame
  // cell against its own mean over the frames that see it: a lamp lights
  // what is around it, which shows when the bulb itself is hidden (under a
  // hood, inside a fridge), while a door moving or revealing its inside
  // changes which surfaces are seen, not how lit each is. Read where the
  // depth places a pixel (NaN in frames without depth).
  std::vector<double> surround;
  int frames_seen = 0;                               // frames with effector pixels
  // Object-frame blob points (summed) and counts, for the emitter and outlet.
  Eigen::Vector3d droplet_sum = Eigen::Vector3d::Zero(), mote_sum = Eigen::Vector3d::Zero();
  double droplet_top_z = -1e9;  // highest droplet point (object frame)
  long droplet_points = 0, mote_points = 0;
  int frames_read = 0;
};

// One entry per effector index (into input.parts); frames are read once for
// all of them, split over `threads`. Unreadable frames are skipped (their
// diagnostics are not repeated here: the caller warns once).
std::vector<EffectorSignals> measure_effectors(const TemplateInput& input, const std::vector<int>& effectors,
                                               int threads, int* frames_failed);

// One surround cell's luminance in one frame: its pixels' sum and count.
struct CellLum {
  int64_t cell;
  double sum;
  int count;
};

// The surround signal from its cells ([frame] -> the cells it sees): per
// frame, the mean over the cells it sees of each cell's luminance less that
// cell's mean over all frames that see it (plus the overall mean, to keep
// the units). A door swinging open reveals a darker inside and hides a lit
// front: the plain mean follows the door; each surface point against itself
// follows only its lighting. Cells seen in one frame say nothing and are
// left out. NaN where a frame has none.
std::vector<double> surround_from_cells(const std::vector<std::vector<CellLum>>& frames);

// The heat signal: how much red-hot the effector's mean colour holds, per
// frame. The runtime blends a heated part's colour from its own (B)
// towards red-hot (H = (1, 0.22, 0.04)) by a fraction f of the way from
// e_lo to glowing, and the pixel is that colour times the shading s (a
// lamp's emission scales it alike): P = s ((1 - f) B + f H). Written as
// P = alpha b + beta h in the chromaticities b and h of B and H (unit
// sums), beta = s f sum(H): linear in f, and 0 while the part is cool
// whatever the light (never below 0). (The chromaticity R / (R + G + B)
// alone is not: a near-black burner's reaches most of red-hot's at
// f = 0.05, and a dark red one's falls as it heats.) b is the mean
// chromaticity of the fifth of the frames farthest from h's; a part
// coloured within 0.15 of h (an amber lamp: a blend towards red-hot barely
// shows, and its noise would be amplified) gets its red chromaticity
// instead. colour[f]: the mean R, G, B in [0, 1]; NaN where unobserved.
std::vector<double> hot_component(const std::vector<Eigen::Vector3d>& colour);

// A moving effector's pixels change with its pose: a lid turning towards
// the light brightens, its colour shifts with the shading. What its own
// pixels say of light or heat is what its pose does not explain: y less
// its least-squares fit in (1, q, q^2) of the effector's joint position q
// (the constant kept; frames without y or q left as they are).
std::vector<double> pose_shading_removed(const std::vector<double>& y, const std::vector<double>& q);

}  // namespace efc::pipeline
