#include "pipeline/infer/infer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>

#include "pipeline/infer/axis_prior.h"
#include "pipeline/infer/ego_motion.h"
#include "pipeline/infer/grip_track.h"
#include "pipeline/infer/hand_contacts.h"
#include "pipeline/infer/joint_estimate.h"
#include "pipeline/infer/joint_names.h"
#include "pipeline/infer/part_tracking.h"
#include "pipeline/infer/reconstruction.h"
#include "pipeline/infer/spec_assembly.h"

namespace efc::pipeline {

namespace {

using ojson = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

ojson vec(const Eigen::Vector3d& v) { return ojson::array({v.x(), v.y(), v.z()}); }

// The object frame: z against gravity, x along the world's x as far as
// gravity allows, its origin under the centre of the static parts' bounding
// box, on their lowest point.
Eigen::Isometry3d object_frame(const Cloud& static_model, const std::array<double, 3>& gravity) {
  Eigen::Vector3d up = -Eigen::Vector3d(gravity[0], gravity[1], gravity[2]);
  if (!(up.norm() > 0)) up = Eigen::Vector3d::UnitZ();
  up.normalize();
  Eigen::Vector3d x = Eigen::Vector3d::UnitX() - up.x() * up;
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitY() - up.y() * up;
  x.normalize();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = up.cross(x);
  R.col(2) = up;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : static_model.points) box.extend(R.transpose() * p);
  Eigen::Vector3d origin_local = Eigen::Vector3d::Zero();
  if (!box.isEmpty()) origin_local = Eigen::Vector3d(box.center().x(), box.center().y(), box.min().z());
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = R * origin_local;
  return T;
}

ojson stage(const std::string& name, double seconds) {
  ojson s;
  s["name"] = name;
  s["seconds"] = seconds;
  return s;
}

ojson joint_report(const JointEstimate& j) {
  ojson r;
  r["type"] = j.type;
  r["source"] = j.source;
  r["confidence"] = j.confidence;
  if (j.assumed_moving) r["assumed_moving"] = true;
  if (j.type_from_name) r["type_from_name"] = true;
  if (j.motion_untyped) r["motion_untyped"] = true;
  if (j.hand_motion_visibility > 0) r["hand_motion_visibility"] = j.hand_motion_visibility;
  if (j.slide_over_turn) r["slide_over_turn"] = true;
  if (j.turn_taken_for_slip) r["turn_taken_for_slip"] = true;
  if (j.slide_taken_for_slip) r["slide_taken_for_slip"] = true;
  if (j.swing_past_slip) r["swing_past_slip"] = true;
  if (j.press_past_slip) r["press_past_slip"] = true;
  if (j.slide_past_spin) r["slide_past_spin"] = true;
  if (j.grip_with_hand) r["grip_with_hand"] = true;
  if (j.grip_swings_past_slip) r["grip_swings_past_slip"] = true;
  if (j.hinge_from_grip) r["hinge_from_grip"] = true;
  if (j.state_from_grip) r["state_from_grip"] = true;
  if (j.plain_slide) r["plain_slide"] = true;
  if (j.hand_slides_along) r["hand_slides_along"] = true;
  if (j.axis_from_part) r["axis_from_part"] = true;
  if (j.type != "fixed") {
    r["axis"] = vec(j.axis);
    r["origin"] = vec(j.origin);
    r["range"] = ojson::array({j.range_lo, j.range_hi});
    // The joint position per frame (the receptor's s_R for the templates);
    // null before the part was first seen.
    auto series = [](const std::vector<double>& v) {
      ojson a = ojson::array();
      for (double x : v) a.push_back(std::isfinite(x) ? ojson(x) : ojson(nullptr));
      return a;
    };
    r["q"] = series(j.q);
    // The same from the hand's contacts, where the part's track gave q.
    if (!j.q_hand.empty()) r["q_hand"] = series(j.q_hand);
  }
  auto fits = [](const Articulation& a) {
    ojson f;
    f["type"] = a.type;
    f["samples"] = a.samples;
    f["residual_m"] = a.residual;
    // The track's own geometry (object frame), where it moved: what the
    // joint's axis would be had this track decided.
    if (a.type != "fixed") {
      f["axis"] = vec(a.axis);
      if (a.type == "revolute") f["origin"] = vec(a.origin), f["radius_m"] = a.radius;
      f["range"] = {a.range_lo, a.range_hi};
    }
    f["p"] = {{"fixed", a.p_fixed}, {"prismatic", a.p_prismatic}, {"revolute", a.p_revolute}};
    // The hinge that also slides along its axis (Articulation::slide_bic),
    // beside the plain hinge's score: where it wins by much on a part
    // turning about itself, the part is taken to slide (slide_over_turn).
    if (std::isfinite(a.slide_bic) && a.revolute.valid)
      f["bic"] = {{"revolute", a.revolute.bic}, {"revolute_and_slide", a.slide_bic}};
    return f;
  };
  r["bic"] = {{"fixed", j.bic_fixed}, {"prismatic", j.bic_prismatic}, {"revolute", j.bic_revolute}};
  if (j.has_part_track) r["from_part"] = fits(j.from_part);
  if (j.has_hand_track) r["from_hand"] = fits(j.from_hand);
  if (j.has_swing_track) {
    r["from_swing"] = fits(j.from_swing);
    if (j.from_swing.type == "revolute")
      r["from_swing"]["visibility"] = j.swing_visibility, r["from_swing"]["about_itself"] = j.swing_about_itself;
  }
  if (j.has_grip_track) {
    r["from_grip"] = fits(j.from_grip);
    r["grip_visibility"] = j.grip_visibility;
    if (!j.grip_frames_left_out.empty()) r["grip_frames_left_out"] = j.grip_frames_left_out;
  }
  if (!j.frames_off_axis.empty()) r["frames_off_axis"] = j.frames_off_axis;
  r["hand_samples"] = j.hand_samples;
  if (j.has_part_track) r["part_visibility"] = j.part_visibility;
  return r;
}

}  // namespace

int infer_sequence(const std::string& sequence_dir, const InferOptions& options, Diagnostics& diags,
                   InferResult* result) {
  const auto t_all = Clock::now();
  const ProgressFn& progress = options.progress;
  seq::Sequence sequence;
  if (!sequence.open(sequence_dir, diags)) return 1;
  const seq::Meta& meta = sequence.meta();
  const std::string meta_file = sequence.dir() + "/meta.json";
  ojson report;
  report["sequence"] = sequence.dir();
  report["frames"] = meta.frames;
  ojson stages = ojson::array();

  // 1. Observations.
  auto t0 = Clock::now();
  Observations obs;
  if (!observe(sequence, options.observe, diags, progress, &obs)) return 1;
  if (!options.use_hands) obs.hands.clear(), obs.hand_clouds.clear();
  {
    ojson s = stage("observations", since(t0));
    s["parts"] = obs.parts.size();
    s["hand_track"] = !obs.hands.empty();
    s["masks"] = obs.motion_masks ? "motion fallback" : "sequence";
    stages.push_back(s);
  }
  const int n = meta.frames;

  // 2. Ego-motion, on the static parts (role object; else the best-seen part).
  t0 = Clock::now();
  std::vector<int> static_parts, moving_parts;
  for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p)
    (obs.parts[p].role == "object" ? static_parts : moving_parts).push_back(p);
  if (static_parts.empty()) {
    int best = 0;
    size_t most = 0;
    for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p) {
      size_t s = 0;
      for (const Cloud& c : obs.parts[p].clouds) s += c.size();
      if (s > most) most = s, best = p;
    }
    static_parts.push_back(best);
    moving_parts.erase(std::remove(moving_parts.begin(), moving_parts.end(), best), moving_parts.end());
    diags.warning("E1056", meta_file, 0, 0, "/parts",
                  "no part has the role 'object': '" + obs.parts[best].name +
                      "' (seen most) is taken as the static body the camera is registered on");
  }
  // Effectors are registered on too, at a fraction of the body's weight
  // (ego_motion.h): most never move, and a small one beside the body holds
  // a direction the body's faces leave nearly free.
  std::vector<int> effectors;
  for (int p : moving_parts)
    if (obs.parts[p].role == "effector") effectors.push_back(p);
  const EgoMotion ego =
      refine_ego_motion(obs, static_parts, std::max(1, options.observe.threads), progress, effectors);
  if (ego.model.size() < 100) {
    diags.error("E1057", sequence.dir(), 0, 0, "",
                "the static parts are not seen well enough to register the camera on them (" +
                    std::to_string(ego.model.size()) + " points)",
                "check the masks of the 'object' parts and the depth");
    return 1;
  }
  const Eigen::Isometry3d object_to_world = object_frame(ego.model, meta.gravity);
  const Eigen::Isometry3d world_to_object = object_to_world.inverse();
  std::vector<Eigen::Isometry3d> to_object(n);
  std::vector<Eigen::Isometry3d> camera_to_world(n);
  for (int f = 0; f < n; ++f) {
    to_object[f] = world_to_object * ego.correction[f];
    camera_to_world[f] = ego.correction[f] * obs.camera_to_world[f];
  }
  {
    ojson s = stage("ego_motion", ego.seconds);
    int registered = 0;
    double rmse = 0;
    for (int f = 0; f < n; ++f)
      if (ego.registered[f]) ++registered, rmse += ego.rmse[f] * ego.rmse[f];
    s["frames_registered"] = registered;
    s["rmse_m"] = registered ? std::sqrt(rmse / registered) : 0.0;
    s["reference_frame"] = ego.reference_frame;
    s["model_points"] = ego.model.size();
    // Where the refined world was anchored (ego_anchor.h): the tracker's
    // noise read off the corrections, and how the frames were weighted.
    s["anchor"] = {{"jitter_m", ego.anchor.jitter_m},
                   {"walk_m_per_sqrt_s", ego.anchor.walk_m_per_sqrt_s},
                   {"frames_weighted", ego.anchor.frames},
                   {"weight_first_second", ego.anchor.weight_first_second}};
    stages.push_back(s);
  }
  if (progress) progress("infer: camera registered on " + std::to_string(static_parts.size()) + " static part(s)");

  // 3. Part motion, two parts at a time: every part but the body (the
  // best-seen static part). The other 'object' parts were assumed still for
  // the camera's registration, which the body dominates, but an object may
  // carry parts no function drives that move all the same (a lamp's head
  // sagging on its hinge, a lid pushed aside): their joints are estimated
  // like any other, and one that never moves comes out fixed.
  int body = -1;
  {
    size_t most = 0;
    for (int p : static_parts) {
      size_t s = 0;
      for (const Cloud& c : obs.parts[p].clouds) s += c.size();
      if (body < 0 || s > most) most = s, body = p;
    }
  }
  for (int p : static_parts)
    if (p != body) moving_parts.push_back(p);
  std::sort(moving_parts.begin(), moving_parts.end());
  t0 = Clock::now();
  std::vector<std::unique_ptr<PartTrack>> tracks(obs.parts.size());
  {
    std::atomic<size_t> next{0};
    auto worker = [&]() {
      for (size_t k = next++; k < moving_parts.size(); k = next++)
        tracks[moving_parts[k]] = std::make_unique<PartTrack>(track_part(obs, moving_parts[k], to_object));
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::max(1, options.observe.threads); ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  }
  stages.push_back(stage("part_motion", since(t0)));
  if (progress) progress("infer: part motion tracked (" + std::to_string(moving_parts.size()) + " parts)");

  // 4. Joints: the hand's contact points go to the part they touch.
  t0 = Clock::now();
  std::vector<std::vector<Eigen::Vector3d>> hand_points(obs.parts.size(), std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Constant(kNaN)));
  if (!obs.hands.empty()) {
    std::vector<Eigen::Vector3d> hand(n, Eigen::Vector3d::Constant(kNaN));
    for (int f = 0; f < n && f < static_cast<int>(obs.hands.size()); ++f)
      if (obs.hands[f].seen)
        hand[f] = world_to_object * Eigen::Vector3d(obs.hands[f].p[0], obs.hands[f].p[1], obs.hands[f].p[2]);
    std::vector<const PartTrack*> tracked(obs.parts.size(), nullptr);
    for (int p : moving_parts) tracked[p] = tracks[p].get();
    hand_points = assign_hand_contacts(hand, tracked);
    // Only receptors keep the hand's contacts (an effector is driven).
    std::vector<std::string> roles;
    for (const PartFrames& pf : obs.parts) roles.push_back(pf.role);
    keep_receptor_contacts(roles, &hand_points);
  }
  auto operated = [&](int p) {  // as spec_role names receptors
    const std::string& role = obs.parts[p].role;
    return role == "receptor" || role == "receptor+effector";
  };
  const double contacts_seconds = since(t0);  // counted with the joints' estimation

  // 4a. The grip: the hand's own points while it holds an operated part,
  // tracked like a part (grip_track.h).
  t0 = Clock::now();
  std::vector<std::unique_ptr<PartTrack>> grips(obs.parts.size());
  // The grip's points in the object frame, for the twist search about the
  // hinge (twist_search.h).
  std::vector<std::vector<Cloud>> grip_points(obs.parts.size());
  std::vector<int> held;  // the operated parts the hand holds in some frame
  if (!obs.hand_clouds.empty()) {
    for (int p : moving_parts) {
      bool any = false;
      for (const Eigen::Vector3d& h : hand_points[p]) any |= !std::isnan(h.x());
      if (tracks[p] && operated(p) && any) held.push_back(p);
    }
    const TrackOptions grip_tracking = grip_tracking_options();
    std::atomic<size_t> next{0};
    auto worker = [&]() {
      for (size_t k = next++; k < held.size(); k = next++) {
        const int p = held[k];
        std::vector<Cloud> clouds = grip_clouds(obs, hand_points[p], to_object);
        grips[p] = std::make_unique<PartTrack>(track_clouds(clouds, to_object, grip_tracking));
        for (size_t f = 0; f < clouds.size() && f < to_object.size(); ++f) transform_cloud(to_object[f], &clouds[f]);
        grip_points[p] = std::move(clouds);
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::max(1, options.observe.threads); ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  }
  stages.push_back(stage("grip_motion", since(t0)));
  if (progress && !obs.hand_clouds.empty())
    progress("infer: the hand's grip tracked on " + std::to_string(held.size()) + " receptor(s)");

  t0 = Clock::now();
  std::vector<JointEstimate> joints(obs.parts.size());
  {
    // Two parts at a time, as their tracks were: a held part's grip is
    // typed again with each of a few samples left out (estimate_joint),
    // about 60 ms a time.
    std::atomic<size_t> next{0};
    auto worker = [&]() {
      for (size_t k = next++; k < moving_parts.size(); k = next++) {
        const int p = moving_parts[k];
        if (tracks[p])
          joints[p] = estimate_joint(*tracks[p], hand_points[p], operated(p), grips[p].get(),
                                     joint_named(obs.parts[p].name), !obs.hands.empty(),
                                     grips[p] ? &grip_points[p] : nullptr);
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::max(1, options.observe.threads); ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  }
  for (int p : moving_parts) {
    if (!tracks[p]) continue;
    if (joints[p].assumed_moving)
      diags.warning("E1059", meta_file, 0, 0, "/parts/" + obs.parts[p].name,
                    "part '" + obs.parts[p].name +
                        (obs.hands.empty() ? "': a receptor (the recording has no hands.txt), but its own track does not show it moving; it is taken as "
                                           : "': the hand held it, but neither its own track nor the hand's shows it moving; it is taken as ") +
                        joints[p].type + (joints[p].type_from_name ? " (as its name says)" : " (the likelier moving joint)") +
                        ", with low confidence",
                    "film the part from where its motion shows, not hidden by the hand");
  }
  stages.push_back(stage("articulation", contacts_seconds + since(t0)));
  if (progress) progress("infer: joints estimated");

  // 5. Reconstruction.
  t0 = Clock::now();
  std::vector<PartReconstruction> recon(obs.parts.size());
  {
    std::atomic<size_t> next{0};
    auto worker = [&]() {
      for (size_t p = next++; p < obs.parts.size(); p = next++)
        recon[p] = reconstruct_part(obs, static_cast<int>(p), to_object, tracks[p].get(), &joints[p]);
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::max(1, options.observe.threads); ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  }

  // The parts that made it: a mesh is needed for the spec.
  int root = recon[body].ok ? body : -1;
  if (root < 0) {  // the body could not be reconstructed: the best static part that could
    size_t root_points = 0;
    for (int p : static_parts)
      if (recon[p].ok && recon[p].fused.size() > root_points) root_points = recon[p].fused.size(), root = p;
  }
  if (root < 0) {
    diags.error("E1057", sequence.dir(), 0, 0, "", "no static part could be reconstructed: there is no body to build on");
    return 1;
  }
  // The body stands on its foot (a static part: its points need no track).
  recon[root].stood = stand_on_its_foot(obs, root, to_object, &recon[root]);
  // A box-shaped body is its box (what the corner of it in view implies).
  recon[root].squared = square_the_body(&recon[root]);
  stages.push_back(stage("reconstruction", since(t0)));
  if (progress) progress("infer: parts reconstructed");

  // 5a. The body's axes as a prior on the joints' axes (axis_prior.h). After
  // the reconstruction, which follows each part's registered motion: the
  // prior moves the joints' axes, not the parts' points.
  t0 = Clock::now();
  const BodyFrame& frame = recon[root].frame;  // square_the_body found it
  std::vector<AxisPrior> axis_priors(obs.parts.size());
  for (int p : moving_parts)
    if (tracks[p]) {
      const Eigen::Vector3d part_at = recon[p].bounds.center();
      // A press goes into the face it sits on, a knob turns about its
      // normal: the body's surface there says which way that is.
      const bool about_its_face = (press_named(obs.parts[p].name) || face_turn_named(obs.parts[p].name)) &&
                                  recon[root].ok && recon[p].ok;
      axis_priors[p] = apply_axis_prior(frame, &joints[p], &tracks[p]->model,
                                        about_its_face ? &recon[root].fused : nullptr,
                                        about_its_face ? &part_at : nullptr);
    }
  {
    ojson s = stage("axis_prior", since(t0));
    s["body_axes_found"] = frame.found;
    s["yaw_rad"] = frame.yaw;
    s["box_share"] = frame.box_share;
    s["upright_share"] = frame.upright_share;
    stages.push_back(s);
  }
  std::vector<AssembledPart> assembled;
  std::vector<int> part_of_assembled;
  for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p) {
    if (!recon[p].ok) {
      diags.warning("E1058", meta_file, 0, 0, "/parts/" + obs.parts[p].name,
                    "part '" + obs.parts[p].name + "' is left out: it could not be reconstructed (" + recon[p].error + ")",
                    "it needs depth readings inside its mask in several frames");
      continue;
    }
    AssembledPart a;
    a.name = spec_name(obs.parts[p].name);
    a.role = obs.parts[p].role;
    a.root = p == root;
    a.joint = joints[p];
    a.mesh = "meshes/" + a.name + ".obj";
    a.parent = spec_name(obs.parts[root].name);
    if (a.root) assembled.insert(assembled.begin(), a), part_of_assembled.insert(part_of_assembled.begin(), p);
    else assembled.push_back(a), part_of_assembled.push_back(p);
  }

  // 6. Function templates.
  t0 = Clock::now();
  TemplateInput tin;
  tin.sequence = &sequence;
  tin.camera_to_world = camera_to_world;
  tin.object_to_world = object_to_world;
  tin.functions = meta.functions;
  if (tin.functions.empty()) {
    bool r = false, e = false;
    for (const PartFrames& pf : obs.parts) r |= pf.name == "receptor", e |= pf.name == "effector";
    if (r && e) tin.functions.push_back({"function", "receptor", "effector"});
  }
  for (size_t k = 0; k < assembled.size(); ++k) {
    const int p = part_of_assembled[k];
    const AssembledPart& a = assembled[k];
    PartObservation po;
    po.name = obs.parts[p].name;
    po.role = a.role;
    po.joint_type = a.root ? "fixed" : a.joint.type;
    po.axis = a.joint.axis;
    po.origin = a.joint.origin;
    po.range_lo = a.joint.range_lo;
    po.range_hi = a.joint.range_hi;
    po.motion.assign(n, Eigen::Isometry3d::Identity());
    if (po.joint_type != "fixed") {
      po.q = a.joint.q;
      po.q_hand = a.joint.q_hand;
      po.q_seen = a.joint.q_seen;
      for (int f = 0; f < n && f < static_cast<int>(po.q.size()); ++f) po.motion[f] = joint_motion(a.joint, po.q[f]);
    } else if (a.joint.registration_slipped() && tracks[p]) {
      // Fixed, but its registration places it in each frame better than the
      // object's alone does (as in its fusion): its pixels are found there.
      for (int f = 0; f < n && f < static_cast<int>(tracks[p]->motion.size()); ++f)
        if (tracks[p]->tracked[f]) po.motion[f] = tracks[p]->motion[f];
    }
    po.bounds = recon[p].bounds;
    po.surface = recon[p].fused.points;
    tin.parts.push_back(std::move(po));
  }
  std::vector<InferredFunction> functions = infer_templates(tin, options.templates, diags);
  stages.push_back(stage("templates", since(t0)));
  if (progress) progress("infer: " + std::to_string(functions.size()) + " function template(s) inferred");

  // 7. The spec.
  std::string name = sequence.dir();
  while (!name.empty() && name.back() == '/') name.pop_back();
  name = name.substr(name.find_last_of('/') + 1);
  StandIns unseen;
  unseen.centre = recon[root].bounds.center();
  for (size_t p = 0; p < obs.parts.size(); ++p)
    if (!recon[p].ok) unseen.names.push_back(spec_name(obs.parts[p].name));
  result->spec = assemble_spec(name, "Inferred by efc infer from the recording " + name + ".", assembled, functions,
                               unseen, object_to_world, meta_file, diags);
  result->meshes.clear();
  for (size_t k = 0; k < assembled.size(); ++k)
    result->meshes.push_back({assembled[k].mesh, recon[part_of_assembled[k]].mesh});

  // The report.
  ojson jparts = ojson::array();
  for (size_t k = 0; k < assembled.size(); ++k) {
    const int p = part_of_assembled[k];
    ojson jp;
    jp["name"] = assembled[k].name;
    jp["role"] = assembled[k].role;
    int seen = 0;
    for (const Cloud& c : obs.parts[p].clouds) seen += c.size() > 0;
    jp["frames_seen"] = seen;
    if (assembled[k].root) jp["root"] = true;
    if (tracks[p]) {
      const PartTrack& t = *tracks[p];
      double rmse = 0;
      for (int f = 0; f < n; ++f)
        if (t.tracked[f]) rmse += t.rmse[f] * t.rmse[f];
      jp["icp"] = {{"frames_tracked", t.frames_tracked},
                   {"rmse_m", t.frames_tracked ? std::sqrt(rmse / t.frames_tracked) : 0.0},
                   {"reference_frame", t.reference_frame},
                   {"model_points", t.model.size()},

                   {"seconds", t.seconds}};
      jp["joint"] = joint_report(joints[p]);
      if (joints[p].type != "fixed") {
        const AxisPrior& prior = axis_priors[p];
        jp["joint"]["axis_prior"] = {{"estimated_axis", vec(prior.estimated)}, {"angle_to_body_axis_rad", prior.angle}};
        if (!prior.axis.empty()) jp["joint"]["axis_prior"]["taken_onto"] = prior.axis;
        if (prior.by_face) jp["joint"]["axis_prior"]["by_face"] = true;
        if (prior.by_body_face) jp["joint"]["axis_prior"]["by_body_face"] = true;
      }
    } else {
      jp["joint"] = {{"type", assembled[k].root ? "root" : "fixed"}, {"source", "static"}};
    }
    jp["mesh"] = {{"points", recon[p].fused.size()},
                  {"vertices", recon[p].mesh.vertices.size()},
                  {"volume_m3", recon[p].volume},
                  {"frames_fused", recon[p].frames_fused},
                  {"outline_voxels_dropped", recon[p].outline_dropped}};
    if (recon[p].stood) jp["mesh"]["stood_on_foot"] = true;
    if (recon[p].squared) jp["mesh"]["squared"] = true;
    if (recon[p].box_share > 0) {
      jp["mesh"]["box_share"] = recon[p].box_share;
      jp["mesh"]["box_surface_share"] = recon[p].box_surface_share;
      jp["mesh"]["box_fill"] = recon[p].box_fill;
    }
    jparts.push_back(jp);
  }
  ojson jfun = ojson::array();
  for (const InferredFunction& f : functions) {
    ojson jf;
    jf["name"] = f.name;
    jf["confidence"] = f.confidence;
    jf["mapping"] = ojson::parse(f.mapping.dump());
    jf["effect"] = ojson::parse(f.effect.dump());
    jf["report"] = ojson::parse(f.report.dump());
    jfun.push_back(jf);
  }
  report["stages"] = stages;
  report["parts"] = jparts;
  report["functions"] = jfun;
  report["seconds"] = since(t_all);
  result->report = std::move(report);
  return 0;
}

}  // namespace efc::pipeline
