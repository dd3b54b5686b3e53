// efc infer, stage 4: each part's joint, from its own motion and the hand's.
// Three tracks feed the articulation estimator (pipeline/articulation, BIC
// model selection): the part's registered poses (stage 3), the grip's (the
// hand's own points registered while it holds the part, grip_track.h) and
// the hand's contact points in the frames the hand holds the part. The
// part's own track decides when it can: when its points show the motion (or
// show that there is none). Where they cannot (a round knob whose turn the
// depth does not resolve, a button hidden under the finger), the grip
// decides (with the hand's points' evidence added where they show the part
// moving too), and where it shows nothing either, the hand's points. A
// round part nobody operates whose registration slips round its own axis
// is typed again with that twist left out, so that a swing the slip hid
// shows; a slide along a direction the part's shape barely shows (a flat
// button's face wandering in its own plane) is taken for a slip, and the
// slide along the direction it shows best for the joint. A part none
// shows moving is fixed. The tracks' scores, and the
// part's and the hand's points' sum, are in the report.
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "pipeline/articulation/articulation.h"
#include "pipeline/infer/part_tracking.h"

namespace efc::pipeline {

struct JointEstimate {
  std::string type = "fixed";  // fixed, revolute, continuous, prismatic
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // object frame, unit
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // a point on the axis (revolute)
  double range_lo = 0, range_hi = 0;
  // Per frame: the joint position (q = 0 in the first frame the part was
  // seen), NaN before it was; empty for fixed.
  std::vector<double> q;
  // q where a track measured it, NaN in the frames fill_gaps bridged (the
  // part unseen, or its pose a spike). An effector's geometry signal: a
  // lid that opens while out of view is not shut there.
  std::vector<double> q_seen;
  // Where q came from the part's own track or the grip's and the hand held
  // the part: the same from the hand's contacts alone (the chosen axis; q =
  // 0 at the first contact, held between grasps), NaN before. Empty
  // otherwise. The templates' second candidate for the receptor's state.
  std::vector<double> q_hand;
  // Maps the track's reference configuration to q = 0.
  Eigen::Isometry3d reference_to_zero = Eigen::Isometry3d::Identity();
  std::string source = "none";  // which track gave the geometry: part, grip, hand, none
  bool has_part_track = false, has_hand_track = false, has_grip_track = false, has_swing_track = false;
  // from_swing: the part's track less its twist about its symmetry axis
  // (swing_past_slip below), where it was tried.
  Articulation from_part, from_hand, from_grip, from_swing;
  double bic_fixed = 0, bic_prismatic = 0, bic_revolute = 0;  // fused
  double confidence = 0;  // posterior of the chosen type under the fused BIC
  // A receptor the hand held whose motion neither track shows: moving by
  // assumption (the likelier moving model), not by evidence.
  bool assumed_moving = false;
  // Typed by the part's name (joint_names.h): moving by assumption, where
  // the fused BIC of two fits to noise would decide; pressed past a slip
  // whose press does not show (press_past_slip); or a track's near-tie
  // between a turn and a slide settled by the name's prior
  // (kNamePriorOdds).
  bool type_from_name = false;
  // An operated part whose motion only a track that cannot type a press of
  // a few millimetres shows: its grip's, which the grip's shape barely
  // shows, where the part's own track shows it staying put; or the hand's
  // contacts', within two detector errors of where they began, or about a
  // joint the part's shape would show plainly (hand_motion_visibility)
  // where its track shows it still. The name,
  // where it names a joint, types it (type_from_name where it changed it).
  bool motion_untyped = false;
  // Where the hand's contacts decide over a part whose own track shows it
  // still: how plainly the part's shape would show the contacts' joint
  // (visibility()); 0 elsewhere.
  double hand_motion_visibility = 0;
  // A part that turns about an axis through itself, typed prismatic: its
  // hinge fit explained its poses better with a slide along the same axis
  // (Articulation::slide_bic), so the turn is taken for the registration
  // slipping round a near-symmetry and the slide for the motion.
  bool slide_over_turn = false;
  // A part no hand held whose track turns, a turn its shape barely shows,
  // and that shows no slide either: typed fixed, the turn taken for its
  // registration slipping round a near-symmetry.
  bool turn_taken_for_slip = false;
  // The same for a slide: a part no hand held whose track slides along a
  // direction its shape barely shows, and along the one it shows best
  // stays put; typed fixed, the slide taken for its registration slipping
  // across a flat face.
  bool slide_taken_for_slip = false;
  // Fixed, but the part's registration slipped round or along a shape
  // that hides it: the registration still places the part in each frame
  // (its fusion, the templates' pixels) better than the object's alone.
  bool registration_slipped() const { return turn_taken_for_slip || slide_taken_for_slip; }
  // A near-symmetric part whose track, less its twist about its symmetry
  // axis, swings about a hinge beside it that its shape plainly shows: the
  // swing decides (a door's plate slipping round its normal, a round
  // shade's spin), whatever the slip made of the whole track.
  bool swing_past_slip = false;
  // The swing's hinge as its shape shows it (visibility()), and whether
  // that hinge runs through the part (turns_about_itself()), where a swing
  // was tried: what swing_past_slip was decided on.
  double swing_visibility = 0;
  bool swing_about_itself = false;
  // A receptor whose track turns about an axis through itself that its
  // shape does not show plainly, that faces along its symmetry axis, and
  // whose centre, its poses less their twist about that axis, is held one
  // way along it for a while and never as far the other way: the press (a
  // round button's) decides, along the turn's axis, the turn taken for the
  // registration's slip. A round receptor named to slide (a button) is read
  // so whatever hinge its track fits (through it or beside it, shown plainly
  // or not), pressed along its symmetry axis, unless the hand's contacts
  // turn it from a lever arm or its grip slides further than a press.
  bool press_past_slip = false;
  // A part nobody operates whose track turns about an axis through itself,
  // and whose poses less that twist slide along the axis: the slide (a
  // pump's ram rising) decides, the turn taken for its registration's spin.
  bool slide_past_spin = false;
  // A slide the part's track found along a direction its shape barely
  // shows, taken for a slip and replaced by the slide along the direction
  // its shape shows best (a button's press under its face's in-plane
  // drift).
  bool plain_slide = false;
  // A slide along a direction the part's shape barely shows that the
  // hand's own track follows further than a press goes: kept as the motion,
  // not taken for a slip (a slider's knob).
  bool hand_slides_along = false;
  // The hand's contacts alone showed the part moving (its own track no
  // motion, no grip): they gave its position frame by frame, and the part's
  // own track, fitted with that joint, its axis.
  bool axis_from_part = false;
  // The grip decided, and the hand's contacts showed the part moving too:
  // revolute or prismatic by the two tracks' BICs together.
  bool grip_with_hand = false;
  // The part's registration slipped about an axis through itself, and the
  // grip turned plainly about an axis of its own and not about that one:
  // the grip's own hinge gave the geometry (a rocker's, a pedal's).
  bool grip_swings_past_slip = false;
  // The part's own track decided a turn its shape shows, and the grip
  // holding it turned plainly too: the grip's hinge (axis, origin) is the
  // joint's, the part's twist about it its position (a lever's).
  bool hinge_from_grip = false;
  // The part's own track gave the hinge of a turn the hand made, and the
  // grip's twist searched about that hinge gave its position frame by
  // frame (a knob's or a lever's own poses slip or lag behind the hand's).
  bool state_from_grip = false;
  // The frames of the grip's one typing sample its type was read without
  // (a trimmed fit: its registration spun for those frames), left out of
  // its frame-by-frame fits too; empty where none was.
  std::vector<int> grip_frames_left_out;
  // The part's frames its hinge's fit left out: turned about another axis
  // than the rest of its large turns (a misregistration a few frames long).
  std::vector<int> frames_off_axis;
  int hand_samples = 0;
  // How much of the part track's motion its shape can show (visibility()).
  double part_visibility = 0;
  // The same for the grip's track (grip_track.h) and its motion.
  double grip_visibility = 0;
};

// The model with each normal its kSurfaceNormalNeighbours nearest points'
// plane. A fused model's normals come from each pixel's neighbours in its
// depth image, averaged per voxel, and carry the depth's noise: on them a
// plain cylinder's spin reads half as visible as a generic turn, on the
// surface's (about 1.5 cm of a pot's points) a tenth.
constexpr int kSurfaceNormalNeighbours = 30;
Cloud with_surface_normals(const Cloud& model);
// Whether a shape shows a motion at all, not how its registration saw it:
// the lower of visibility() on the fused normals and on the surface's.
// Noise only adds to the first; the second, on a part of a few hundred
// points, fits planes across a fifth of it and rounds it (seed 1's s0020
// LED: 0.35 on the fused normals, 0.56 on the surface's).
double shape_visibility(const Cloud& model, const std::string& type, const Eigen::Vector3d& axis,
                        const Eigen::Vector3d& origin);

// The slide a part's shape shows best: along the principal direction of
// its normals (the largest eigenvector of sum n n^T: a button's face
// normal; object frame, the model's reference configuration). False where
// even that slide shows less than kSlipVisibility (a round rod along its
// length).
bool best_shown_slide(const Cloud& model, Eigen::Vector3d* axis);

// A receptor's slide across a shape that shows it less than a generic
// motion (kPlainTurnVisibility) is taken for a press under a drift only
// up to this far: a press (kMaxPress) and a registration's wander with it
// (the suites' buttons: 12 to 35 mm); a slider's knob goes further. The
// body's axes read a slide no longer than this as a press too
// (axis_prior.h).
constexpr double kMaxDriftedPress = 0.04;

// How visible a joint's motion is on a part's surface: the share of the
// motion's displacement that lies along the surface normals, relative to
// that of generic motions (turns about two axes across it through the same
// centre). About 1 for a door or a lever; near 0 for a surface of revolution
// turning on its own axis (a ring, a plain knob) or a cylinder sliding along
// it: registration noise there is not motion. A pointer ridge on a knob
// makes its turn visible.
double visibility(const Cloud& surface, const std::string& type, const Eigen::Vector3d& axis,
                  const Eigen::Vector3d& origin);
constexpr double kMinVisibility = 0.1;
// A turn less visible than this (half a generic turn) is one a
// registration can slip into: a part whose track turns so about an axis
// through itself, and also slides along it, is taken to slide.
constexpr double kSlipVisibility = 0.5;
// A turn at least this visible (as visible as a generic turn) is shown
// plainly by the part's shape: no registration slips into it.
constexpr double kPlainTurnVisibility = 1.0;

// The prior odds for the moving joint a part's name names against the
// other one (joint_names.h): a name is a hint, not a measurement. Most
// buttons slide and most knobs turn, but a key may turn and a wheel may
// roll: four to one, so likelihoods of a few to one (a hand's handful of
// noisy samples) yield to it and plain evidence never does.
constexpr double kNamePriorOdds = 4;

// Whether a joint axis passes through the part (a knob's, a button's) rather
// than beside it (a lever's, a door's hinge): the part's centroid is nearer
// the axis line than the median distance of its points from a line along
// the axis through its centroid (medians: a fused model keeps strays).
bool turns_about_itself(const Cloud& model, const Eigen::Vector3d& axis, const Eigen::Vector3d& origin);

// The joint's rigid motion at position q (object frame).
Eigen::Isometry3d joint_motion(const JointEstimate& joint, double q);

// The part track as the articulation estimator sees it: the pose of
// `centroid` (a point of the model) in each tracked frame, frames whose pose
// jumps away from their neighbours' dropped as ICP failures (not those of a
// door swung open for a few frames: pose_spikes in the .cc), then averaged
// over runs of up to `bin_frames` consecutive frames (1: none).
// frames_of_sample[k] lists the frames averaged into sample k. Each sample
// carries its information (Track::information) from the registrations' Hessians;
// `drop_unconstrained` gives none to the directions the tracker left alone.
//
// `twist_axis` (a unit direction of the model through `centroid`, or null):
// each frame's turn about that axis of the part's own (its twist, by the
// swing-twist decomposition) is taken out of its rotation, and the
// information about it marginalised away. The turn a near-symmetric
// shape's registration slips into random-walks there over the frames (a
// lamp head's spin about its round shade, whole radians, while the head
// tilts a tenth of one), and it would otherwise be the likeliest motion.
Track part_samples(const PartTrack& track, const Eigen::Vector3d& centroid, int bin_frames,
                   std::vector<std::vector<int>>* frames_of_sample, bool drop_unconstrained = false,
                   const Eigen::Vector3d* twist_axis = nullptr);

// The axis through the model's centroid about which a turn shows least on
// its surface (visibility()), when it shows less than kSlipVisibility: the
// symmetry axis of a round shade, a knob, a button. False for a shape every
// turn of which shows (a door, a lever, a box).
bool near_symmetry_axis(const Cloud& model, Eigen::Vector3d* axis);

// The samples of a pose track turned about another axis than most of its
// large turns are, ascending: a wide, flat door misregistered near the peak
// of its swing for a few frames on end (s0056's, turned 1.4 rad about an
// axis 80 degrees off its hinge for four frames) passes the spike test,
// which looks for lone frames, and bends the hinge fitted through it by 50
// degrees; estimate_joint leaves them out of a hinge's frame-by-frame fit
// where they bend it. A turn of at least 0.3 rad names its own axis; the
// axis shared (within 15 degrees) by the most of them is the consensus, and
// a sample turned at least 0.3 rad about an axis more than 30 degrees off
// it is off. None where fewer than 4 large turns share an axis, or where
// more than 5 samples (a sixth of a second) or more than a third of the
// large turns are off: then it is no brief misregistration but a part
// whose turns share no one axis (a round knob slipping about its own).
std::vector<size_t> turned_about_another_axis(const Track& track);

// hand_points[f]: the hand's contact point in the object frame in the frames
// it holds this part (NaN elsewhere). `operated`: someone may move the part
// (a receptor's role); an effector or another part only its function or
// nothing moves, so a turn its registration can slip into is not taken for
// a motion there (JointEstimate::turn_taken_for_slip). `grip`: the track of
// the hand's own points while it holds the part (grip_track.h), or null.
// It speaks for an operated part whose own track cannot: one whose motion
// its shape does not show, or whose turn is one its registration can slip
// into (a round knob's, a round button's), since a hand holding a part
// moves with it and its fingers show a twist or a press the part hides.
// `named`: the joint the part's name speaks of (joint_named(): "prismatic",
// "revolute" or ""); it types a part moving by assumption, a receptor
// whose slipping registration hides its press, and it is the prior
// (kNamePriorOdds) between a turn and a slide wherever likelihoods choose
// (JointEstimate::type_from_name); a motion a track plainly shows outweighs it.
// `hand_recorded`: false for a recording without the hand (no hands.txt),
// where an operated part's motion has only its own track to show it.
// `grip_points`: the grip's points per frame (object frame), or null; where
// the grip gives a turn's position, its twist is searched about the hinge
// there too (twist_search.h: a turn faster than the registration's reach).
JointEstimate estimate_joint(const PartTrack& track, const std::vector<Eigen::Vector3d>& hand_points,
                             bool operated = true, const PartTrack* grip = nullptr, const std::string& named = "",
                             bool hand_recorded = true, const std::vector<Cloud>* grip_points = nullptr);

}  // namespace efc::pipeline
