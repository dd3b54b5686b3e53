// How well `efc infer` tracks each moving part (stage 3) and types its joint
// (stage 4), measured against the truth of synthetic recordings
// (bench/README.md):
//
//   part_motion_eval SUITE_OR_SEQUENCE... [--threads T] [--part NAME] [--frames] [--axes]
//
// Each argument is a sequence folder (with truth/, as efc synth writes) or a
// suite folder (every */seq inside). Each sequence is observed and its
// camera registered as efc infer does it; then every part with a joint in
// truth/spec.json is tracked (track_part) in the refined world frame and its
// joint estimated (estimate_joint, with the hand's contacts and, for a
// receptor the hand holds, the grip's track and its points, as efc infer
// does). The true motion
// of the part from the track's reference frame to frame f follows from
// truth/joints.csv and the true joints (chained through moving parents).
// Per part, one line: the true joint type and travel (max rotation deg, max
// displacement of the part's centre mm), the share of frames tracked, the
// median and 90th percentile over tracked frames of the rotation error (deg)
// and of the centre's position error (mm), then the part track's type, the
// hand track's, the grip's and the type chosen (x: not the true type;
// revolute and continuous count as one, as efc eval counts them); last, how
// many were typed right. The refined world differs from the true one by a
// few millimetres (ego_motion_eval), which sets the floor. --part NAME: only
// that part; --frames: every frame's true and tracked motion too, the
// tracked displacement along the true axis (of the centre, and of the part
// track's own hinge axis point nearest it, which a spin about that axis
// leaves in place: a round button's press shows there under any spin), and
// the grip's twist about the true axis and slide along it. --axes: under each
// part, how far (deg) the chosen joint's axis and the part's, the hand's and
// the grip's fitted axes lie off the true axis, and the track the geometry
// came from. --twists: under each held receptor that turns, how far (deg, 90th
// percentile over the frames with a twist, after the better sign and the
// median offset) the grip's twist about the TRUE hinge lies from the truth,
// as efc infer's twist search and half-turn unwrapping give it
// (twist_search.h, twist_unwrap.h) and as the registration alone gives it:
// the receptor's state, apart from any error in the hinge; and the same
// error of the state estimate_joint gave about its own hinge.
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/infer/ego_motion.h"
#include "pipeline/infer/grip_track.h"
#include "pipeline/infer/hand_contacts.h"
#include "pipeline/infer/joint_estimate.h"
#include "pipeline/infer/joint_names.h"
#include "pipeline/infer/observations.h"
#include "pipeline/infer/part_tracking.h"
#include "bench/truth_sequences.h"
#include "sequence/sequence.h"

namespace fs = std::filesystem;
using efc::bench::percentile;
using efc::bench::sequences_in;
using nlohmann::json;

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

Eigen::Vector3d vec3(const json& v) { return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}; }

// The true joints: per part, its parent, type, axis and origin (object frame).
struct TrueJoint {
  std::string parent, type;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(), origin = Eigen::Vector3d::Zero();
};

Eigen::Isometry3d joint_transform(const TrueJoint& j, double q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (j.type == "prismatic") {
    T.translation() = q * j.axis.normalized();
  } else if (j.type == "revolute" || j.type == "continuous") {
    T.linear() = Eigen::AngleAxisd(q, j.axis.normalized()).toRotationMatrix();
    T.translation() = j.origin - T.linear() * j.origin;
  }
  return T;
}

// The part's pose in the object frame at the joint positions of one frame.
Eigen::Isometry3d part_pose(const std::map<std::string, TrueJoint>& joints, const std::map<std::string, double>& q,
                            const std::string& part) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  std::string p = part;
  for (int depth = 0; depth < 32; ++depth) {
    const auto j = joints.find(p);
    if (j == joints.end()) break;
    const auto qi = q.find(p);
    T = joint_transform(j->second, qi == q.end() ? 0.0 : qi->second) * T;
    p = j->second.parent;
  }
  return T;
}

// truth/joints.csv: t, then one column per moving part.
bool read_joint_positions(const fs::path& file, std::vector<std::map<std::string, double>>* rows) {
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) return false;
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) names.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::map<std::string, double> q;
    size_t c = 0;
    for (std::string cell; std::getline(row, cell, ','); ++c)
      if (c > 0 && c < names.size()) q[names[c]] = std::atof(cell.c_str());
    rows->push_back(q);
  }
  return true;
}

Eigen::Isometry3d matrix16(const json& m) {
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = m[4 * r + c].get<double>();
  Eigen::Isometry3d T;
  T.matrix() = M;
  return T;
}

// The p90 error (rad) of a twist estimate against the truth, over the frames
// it has one, after the better sign and the median offset.
double twist_error_p90(const std::vector<double>& twist, const std::vector<std::map<std::string, double>>& q_rows,
                       const std::string& name, size_t* frames) {
  double best = std::numeric_limits<double>::infinity();
  for (double sign : {1.0, -1.0}) {
    std::vector<double> d;
    for (size_t f = 0; f < twist.size() && f < q_rows.size(); ++f) {
      const auto q = q_rows[f].find(name);
      if (std::isfinite(twist[f]) && q != q_rows[f].end()) d.push_back(sign * twist[f] - q->second);
    }
    *frames = d.size();
    if (d.empty()) return std::numeric_limits<double>::quiet_NaN();
    const double offset = percentile(d, 0.5);
    for (double& x : d) x = std::abs(x - offset);
    best = std::min(best, percentile(d, 0.9));
  }
  return best;
}

// --twists: the grip's twist about the true hinge (world frame), searched
// and unwrapped as efc infer does, the registration's alone, and the state
// estimate_joint gave (about its own hinge, in the frames it measured).
void print_twist_errors(const std::vector<efc::pipeline::Cloud>& clouds, const std::vector<Eigen::Vector3d>& contacts,
                        const efc::pipeline::PartTrack& grip, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& axis, const std::vector<std::map<std::string, double>>& q_rows,
                        const std::string& name, const efc::pipeline::JointEstimate& est) {
  const size_t n = clouds.size();
  std::vector<double> registered(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<bool> held(n, false);
  for (size_t f = 0; f < n && f < grip.motion.size(); ++f) {
    held[f] = f < contacts.size() && !std::isnan(contacts[f].x());
    if (grip.tracked[f]) registered[f] = efc::pipeline::twist_about(grip.motion[f], axis);
  }
  const std::vector<double> searched = efc::pipeline::grip_twists_about(grip, clouds, axis, origin, held);
  size_t frames_searched = 0, frames_registered = 0;
  const double e_searched = twist_error_p90(searched, q_rows, name, &frames_searched);
  const double e_registered = twist_error_p90(registered, q_rows, name, &frames_registered);
  size_t frames_estimated = 0;
  std::vector<double> estimated = est.q_seen;
  const double e_estimated = twist_error_p90(estimated, q_rows, name, &frames_estimated);
  std::printf("  twist about the true hinge, p90 error (deg): searched %.1f over %zu frames, registered %.1f over %zu;"
              " estimate_joint's state %.1f over %zu (%s, from the %s)\n",
              e_searched * kDeg, frames_searched, e_registered * kDeg, frames_registered, e_estimated * kDeg,
              frames_estimated, est.type.c_str(), est.source.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage = "usage: part_motion_eval SUITE_OR_SEQUENCE... [--threads T] [--part NAME] [--frames] [--axes] [--twists]\n";
  std::vector<fs::path> sequences;
  efc::pipeline::ObserveOptions observe;
  std::string only_part;
  bool per_frame = false, axes = false, twists = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) {
      observe.threads = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--frames") {
      per_frame = true;
    } else if (a == "--axes") {
      axes = true;
    } else if (a == "--twists") {
      twists = true;
    } else if (a == "--part" && i + 1 < argc) {
      only_part = argv[++i];
    } else if (a == "-h" || a == "--help") {
      std::cout << usage;
      return 0;
    } else {
      const auto found = sequences_in(a, "truth/joints.csv");
      if (found.empty()) {
        std::cerr << "part_motion_eval: " << a << ": no sequence with truth/joints.csv\n";
        return 1;
      }
      sequences.insert(sequences.end(), found.begin(), found.end());
    }
  }
  if (sequences.empty()) {
    std::cerr << usage;
    return 1;
  }
  std::printf("%-30s %-14s %-10s %6s %6s %5s %11s %11s  %-10s %-10s %-10s %-10s\n", "sequence", "part", "truth",
              "deg", "mm", "trk%", "deg med/90", "mm med/90", "from part", "from hand", "from grip", "chosen");
  int parts_total[2] = {0, 0}, typed_right[2] = {0, 0};  // [0] moving joints, [1] fixed parts
  for (const fs::path& dir : sequences) {
    efc::Diagnostics diags;
    efc::seq::Sequence sequence;
    efc::pipeline::Observations obs;
    if (!sequence.open(dir.string(), diags) || !efc::pipeline::observe(sequence, observe, diags, nullptr, &obs)) {
      diags.print(std::cerr, false);
      return 1;
    }
    std::ifstream spec_file(dir / "truth/spec.json"), pose_file(dir / "truth/object_pose.json");
    const json spec = json::parse(spec_file, nullptr, false);
    const json pose = json::parse(pose_file, nullptr, false);
    std::vector<std::map<std::string, double>> q_rows;
    if (!spec.is_object() || !pose.is_object() || !read_joint_positions(dir / "truth/joints.csv", &q_rows)) {
      std::cerr << "part_motion_eval: " << dir.string() << ": truth unreadable\n";
      return 1;
    }
    std::map<std::string, TrueJoint> joints;
    for (const json& p : spec["parts"]) {
      if (!p.contains("joint")) continue;
      TrueJoint j;
      j.parent = p["joint"].value("parent", "");
      j.type = p["joint"].value("type", "fixed");
      if (p["joint"].contains("axis")) j.axis = vec3(p["joint"]["axis"]);
      if (p["joint"].contains("origin")) j.origin = vec3(p["joint"]["origin"]);
      joints[p["name"].get<std::string>()] = j;
    }
    const Eigen::Isometry3d object_to_world = matrix16(pose["object_to_world"]);

    std::vector<int> static_parts;
    for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p)
      if (obs.parts[p].role == "object") static_parts.push_back(p);
    const efc::pipeline::EgoMotion ego = efc::pipeline::refine_ego_motion(obs, static_parts, observe.threads, nullptr);
    const int n = static_cast<int>(obs.times.size());
    // Tracked in the refined world (efc infer uses an object frame fitted to
    // the static model: the same up to one rigid transform).
    std::vector<Eigen::Isometry3d> to_world(ego.correction.begin(), ego.correction.end());
    to_world.resize(n, Eigen::Isometry3d::Identity());
    std::vector<std::unique_ptr<efc::pipeline::PartTrack>> tracks(obs.parts.size());
    std::vector<const efc::pipeline::PartTrack*> tracked(obs.parts.size(), nullptr);
    for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p) {
      const auto j = joints.find(obs.parts[p].name);
      if (j == joints.end() || (!only_part.empty() && obs.parts[p].name != only_part)) continue;
      tracks[p] = std::make_unique<efc::pipeline::PartTrack>(efc::pipeline::track_part(obs, p, to_world));
      tracked[p] = tracks[p].get();
    }
    std::vector<Eigen::Vector3d> hand(n, Eigen::Vector3d::Constant(std::nan("")));
    for (int f = 0; f < n && f < static_cast<int>(obs.hands.size()); ++f)
      if (obs.hands[f].seen) hand[f] = Eigen::Vector3d(obs.hands[f].p[0], obs.hands[f].p[1], obs.hands[f].p[2]);
    auto hand_points = efc::pipeline::assign_hand_contacts(hand, tracked);
    // As efc infer: only receptors keep the hand's contacts, and the hand's
    // own points near its contact (the grip) are tracked while it holds one.
    std::vector<std::string> roles;
    for (const auto& pf : obs.parts) roles.push_back(pf.role);
    efc::pipeline::keep_receptor_contacts(roles, &hand_points);
    auto operated = [&](int p) { return roles[p] == "receptor" || roles[p] == "receptor+effector"; };
    std::vector<std::unique_ptr<efc::pipeline::PartTrack>> grips(obs.parts.size());
    if (!obs.hand_clouds.empty()) {
      const efc::pipeline::TrackOptions grip_tracking = efc::pipeline::grip_tracking_options();
      for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p) {
        bool held = false;
        for (const Eigen::Vector3d& h : hand_points[p]) held |= !std::isnan(h.x());
        if (tracks[p] && operated(p) && held)
          grips[p] = std::make_unique<efc::pipeline::PartTrack>(efc::pipeline::track_clouds(
              efc::pipeline::grip_clouds(obs, hand_points[p], to_world), to_world, grip_tracking));
      }
    }

    for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p) {
      if (!tracks[p]) continue;
      const efc::pipeline::PartTrack& track = *tracks[p];
      const std::string& name = obs.parts[p].name;
      const std::string true_type = joints[name].type;
      const efc::pipeline::PartTrack* grip = grips[p].get();
      // The grip's points per frame in the refined world, for the twist
      // search about the hinge (as efc infer passes them).
      std::vector<efc::pipeline::Cloud> grip_points;
      if (grip) {
        grip_points = efc::pipeline::grip_clouds(obs, hand_points[p], to_world);
        for (size_t f = 0; f < grip_points.size() && f < to_world.size(); ++f)
          efc::pipeline::transform_cloud(to_world[f], &grip_points[f]);
      }
      const efc::pipeline::JointEstimate est =
          efc::pipeline::estimate_joint(track, hand_points[p], operated(p), grip, efc::pipeline::joint_named(name),
                                        true, grip ? &grip_points : nullptr);
      // The true axis in the world frame and the grip's centre: the grip's
      // twist about that axis and its slide along it, per frame (--frames).
      const Eigen::Vector3d true_axis = (object_to_world.linear() * joints[name].axis).normalized();
      const Eigen::Vector3d grip_centre =
          grip && grip->model.size() ? efc::pipeline::centroid(grip->model) : Eigen::Vector3d::Zero();
      // The part's own hinge axis point nearest its centroid: a spin about
      // that axis leaves it where it is.
      Eigen::Vector3d hinge_point = efc::pipeline::centroid(track.model);
      if (est.has_part_track && est.from_part.type == "revolute") {
        const Eigen::Vector3d a = est.from_part.axis.normalized(), o = est.from_part.origin;
        hinge_point = o + (hinge_point - o).dot(a) * a;
      }
      auto grip_text = [&](int f) {
        char buf[96] = "";
        if (grip && f < static_cast<int>(grip->tracked.size()) && grip->tracked[f]) {
          const Eigen::Isometry3d& g = grip->motion[f];
          std::snprintf(buf, sizeof buf, "  grip twist %6.1f deg slide %6.1f mm",
                        efc::pipeline::twist_about(g, true_axis) * kDeg,
                        1000 * (g * grip_centre - grip_centre).dot(true_axis));
        }
        return std::string(buf);
      };
      // As efc eval scores it: revolute and continuous are one type.
      auto turns = [](const std::string& t) { return t == "revolute" || t == "continuous"; };
      const bool right = est.type == true_type || (turns(est.type) && turns(true_type));
      const int kind = true_type == "fixed" ? 1 : 0;
      ++parts_total[kind];
      typed_right[kind] += right;
      std::vector<double> rot_err, pos_err;
      double travel_rot = 0, travel_pos = 0;
      const int ref = track.reference_frame;
      if (ref >= 0 && ref < static_cast<int>(q_rows.size())) {
        const Eigen::Vector3d centre_world = efc::pipeline::centroid(track.model);
        const Eigen::Isometry3d ref_pose = part_pose(joints, q_rows[ref], name);
        for (int f = 0; f < n && f < static_cast<int>(q_rows.size()); ++f) {
          const Eigen::Isometry3d truth =
              object_to_world * part_pose(joints, q_rows[f], name) * ref_pose.inverse() * object_to_world.inverse();
          travel_rot = std::max(travel_rot, Eigen::AngleAxisd(truth.rotation()).angle() * kDeg);
          travel_pos = std::max(travel_pos, 1000 * (truth * centre_world - centre_world).norm());
          if (!track.tracked[f]) {
            if (per_frame)
              std::printf("  %3d true %6.1f deg %6.1f mm  untracked (%zu points, inl %.2f)%s\n", f,
                          Eigen::AngleAxisd(truth.rotation()).angle() * kDeg,
                          1000 * (truth * centre_world - centre_world).norm(), obs.parts[p].clouds[f].size(),
                          track.inliers[f], grip_text(f).c_str());
            continue;
          }
          const Eigen::Isometry3d& m = track.motion[f];
          if (per_frame)
            std::printf("  %3d true %6.1f deg %6.1f mm  tracked %6.1f deg %6.1f mm (%6.1f along the axis; hinge point %5.1f mm, %5.1f along)  err %5.1f mm  inl %.2f cond %.3f%s\n", f,
                        Eigen::AngleAxisd(truth.rotation()).angle() * kDeg,
                        1000 * (truth * centre_world - centre_world).norm(),
                        Eigen::AngleAxisd(m.rotation()).angle() * kDeg, 1000 * (m * centre_world - centre_world).norm(),
                        1000 * (m * centre_world - centre_world).dot(true_axis),
                        1000 * (m * hinge_point - hinge_point).norm(), 1000 * (m * hinge_point - hinge_point).dot(true_axis),
                        1000 * (m * centre_world - truth * centre_world).norm(), track.inliers[f], track.conditioning[f],
                        grip_text(f).c_str());
          rot_err.push_back(Eigen::AngleAxisd(m.rotation() * truth.rotation().transpose()).angle() * kDeg);
          pos_err.push_back(1000 * (m * centre_world - truth * centre_world).norm());
        }
      }
      std::printf("%-30s %-14s %-10s %6.1f %6.1f %5.0f %5.2f/%5.2f %5.1f/%5.1f  %-10s %-10s %-10s %-10s%s\n",
                  dir.parent_path().filename().string().substr(0, 30).c_str(), name.substr(0, 14).c_str(),
                  true_type.c_str(), travel_rot, travel_pos, 100.0 * track.frames_tracked / std::max(1, n),
                  percentile(rot_err, 0.5), percentile(rot_err, 0.9), percentile(pos_err, 0.5),
                  percentile(pos_err, 0.9), est.has_part_track ? est.from_part.type.c_str() : "-",
                  est.has_hand_track ? est.from_hand.type.c_str() : "-",
                  est.has_grip_track ? est.from_grip.type.c_str() : "-", est.type.c_str(), right ? "" : "  x");
      if (axes) {
        // Off the true axis in degrees, either sign (a fit's sign is arbitrary).
        auto off = [&](bool has, const std::string& type, const Eigen::Vector3d& axis) {
          if (!has || type == "fixed" || !axis.allFinite() || axis.norm() == 0) return std::string("-");
          char buf[16];
          std::snprintf(buf, sizeof buf, "%.1f",
                        std::acos(std::min(1.0, std::abs(axis.normalized().dot(true_axis)))) * kDeg);
          return std::string(buf);
        };
        std::printf("  axes off the truth (deg): chosen %s (from %s)  part %s  hand %s  grip %s  (hand frames %d, grip samples %zu)\n",
                    off(true, est.type, est.axis).c_str(), est.source.c_str(),
                    off(est.has_part_track, est.from_part.type, est.from_part.axis).c_str(),
                    off(est.has_hand_track, est.from_hand.type, est.from_hand.axis).c_str(),
                    off(est.has_grip_track, est.from_grip.type, est.from_grip.axis).c_str(), est.hand_samples,
                    est.has_grip_track ? est.from_grip.samples : size_t{0});
      }
      if (twists && grip && turns(true_type) && grip->reference_frame >= 0)
        print_twist_errors(grip_points, hand_points[p], *grip, object_to_world * joints[name].origin, true_axis,
                           q_rows, name, est);
      std::fflush(stdout);
    }
  }
  std::printf("typed right: %d of %d moving joints, %d of %d fixed parts\n", typed_right[0], parts_total[0],
              typed_right[1], parts_total[1]);
  return 0;
}
