// How well `efc infer` registers the camera (stage 2, ego-motion), measured
// against the truth of synthetic recordings (bench/README.md):
//
//   ego_motion_eval SUITE_OR_SEQUENCE... [--no-background] [--threads T]
//
// Each argument is a sequence folder (with truth/poses.txt, as efc synth
// writes) or a suite folder (every */seq inside). For each sequence the
// camera poses are refined as efc infer refines them (observe, then
// refine_ego_motion on the 'object' parts, the 'effector' parts at their
// reduced share and, unless --no-background, the room), and compared with the true poses: the error of frame f is
// E_f = T_true,f T_est,f^-1, less the mean of all E_f (the refined world is
// anchored on the first frames, so it may differ from the true one by a
// constant). Reported per sequence, for poses.txt as given ("tracker") and
// for the refined poses: the median and 90th percentile over frames of the
// position error at the object's centre (mm) and of the rotation error (deg),
// and, for the refined poses, that constant at the object's centre (mm:
// where the whole reconstruction sits off the truth, which every part's
// Chamfer distance and every axis's origin sees); then the medians of those
// over all sequences. EFC_EGO_VERBOSE=1 adds the anchor's noise estimates
// (ego_anchor.h); EFC_EGO_FRAMES=1 every fifth frame's error at the centre
// (mm, world axes) and its rotation, the tracker's then the refined poses'.
// Exit 1 when a sequence cannot be read.
#include <Eigen/Geometry>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/infer/ego_motion.h"
#include "pipeline/infer/observations.h"
#include "bench/truth_sequences.h"
#include "sequence/sequence.h"

namespace fs = std::filesystem;
using efc::bench::percentile;
using efc::bench::sequences_in;
using efc::pipeline::pose_to_isometry;

namespace {

struct Errors {
  double pos_median = 0, pos_p90 = 0, rot_median = 0, rot_p90 = 0;  // mm, deg
  double offset = 0;         // mm: the constant left out of the above, at the centre
  double offset_deg = 0;     // its rotation
};

// The errors of `estimate` against `truth` (camera-to-world per frame),
// measured at `centre` (world).
Errors errors(const std::vector<Eigen::Isometry3d>& truth, const std::vector<Eigen::Isometry3d>& estimate,
              const Eigen::Vector3d& centre) {
  const size_t n = std::min(truth.size(), estimate.size());
  std::vector<Eigen::Isometry3d> E(n);
  std::vector<Eigen::Vector3d> at_centre(n);
  Eigen::Vector3d mean_centre = Eigen::Vector3d::Zero();
  for (size_t f = 0; f < n; ++f) {
    E[f] = truth[f] * estimate[f].inverse();
    at_centre[f] = E[f] * centre;
    mean_centre += at_centre[f];
  }
  if (n == 0) return {};
  mean_centre /= static_cast<double>(n);
  const Eigen::Matrix3d mean_rotation = efc::pipeline::mean_transform(E).rotation();
  std::vector<double> pos, rot;
  if (std::getenv("EFC_EGO_FRAMES"))  // every fifth frame's error, before the constant is taken out
    for (size_t f = 0; f < n; f += 5) {
      const Eigen::Vector3d e = 1000 * (at_centre[f] - centre);
      std::printf("   f %3zu err mm %6.1f %6.1f %6.1f  rot deg %.2f\n", f, e.x(), e.y(), e.z(), Eigen::AngleAxisd(E[f].rotation()).angle() * 180 / 3.14159265358979);
    }
  for (size_t f = 0; f < n; ++f) {
    pos.push_back(1000 * (at_centre[f] - mean_centre).norm());
    rot.push_back(Eigen::AngleAxisd(E[f].rotation() * mean_rotation.transpose()).angle() * 180 / 3.14159265358979);
  }
  return {percentile(pos, 0.5), percentile(pos, 0.9), percentile(rot, 0.5), percentile(rot, 0.9),
          1000 * (mean_centre - centre).norm(), Eigen::AngleAxisd(mean_rotation).angle() * 180 / 3.14159265358979};
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<fs::path> sequences;
  efc::pipeline::ObserveOptions observe;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-background") {
      observe.background = false;
    } else if (a == "--threads" && i + 1 < argc) {
      observe.threads = std::max(1, std::atoi(argv[++i]));
    } else if (a == "-h" || a == "--help") {
      std::cout << "usage: ego_motion_eval SUITE_OR_SEQUENCE... [--no-background] [--threads T]\n";
      return 0;
    } else {
      const auto found = sequences_in(a, "truth/poses.txt");
      if (found.empty()) {
        std::cerr << "ego_motion_eval: " << a << ": no sequence with truth/poses.txt\n";
        return 1;
      }
      sequences.insert(sequences.end(), found.begin(), found.end());
    }
  }
  if (sequences.empty()) {
    std::cerr << "usage: ego_motion_eval SUITE_OR_SEQUENCE... [--no-background] [--threads T]\n";
    return 1;
  }
  std::printf("%-44s %21s   %21s\n", "", "tracker (poses.txt)", "refined (efc infer)");
  std::printf("%-44s %10s %10s   %10s %10s %6s %6s\n", "sequence", "mm med/90", "deg med/90", "mm med/90", "deg med/90",
              "off mm", "deg");
  std::vector<double> all[10];
  for (const fs::path& dir : sequences) {
    efc::Diagnostics diags;
    efc::seq::Sequence sequence;
    efc::pipeline::Observations obs;
    std::vector<efc::seq::Pose> true_poses;
    if (!sequence.open(dir.string(), diags) || !efc::pipeline::observe(sequence, observe, diags, nullptr, &obs) ||
        !efc::seq::read_poses((dir / "truth/poses.txt").string(), diags, &true_poses)) {
      diags.print(std::cerr, false);
      return 1;
    }
    std::vector<int> static_parts, effectors;
    for (int p = 0; p < static_cast<int>(obs.parts.size()); ++p) {
      if (obs.parts[p].role == "object") static_parts.push_back(p);
      if (obs.parts[p].role == "effector") effectors.push_back(p);
    }
    const efc::pipeline::EgoMotion ego =
        efc::pipeline::refine_ego_motion(obs, static_parts, observe.threads, nullptr, effectors);
    std::vector<Eigen::Isometry3d> truth, refined;
    for (const auto& p : true_poses) truth.push_back(pose_to_isometry(p));
    for (size_t f = 0; f < obs.camera_to_world.size() && f < ego.correction.size(); ++f)
      refined.push_back(ego.correction[f] * obs.camera_to_world[f]);
    // The object's centre in the world: its pose from the truth, lifted by
    // half a typical object's height (the pose is at its base).
    Eigen::Vector3d centre(0, 0, 0.3);
    std::ifstream pose_file(dir / "truth/object_pose.json");
    const nlohmann::json pose = nlohmann::json::parse(pose_file, nullptr, false);
    if (pose.is_object() && pose.contains("object_to_world") && pose["object_to_world"].size() == 16) {
      const auto& m = pose["object_to_world"];
      centre = Eigen::Vector3d(m[3].get<double>(), m[7].get<double>(), m[11].get<double>() + 0.3);
    }
    const Errors tracker = errors(truth, obs.camera_to_world, centre);
    const Errors ours = errors(truth, refined, centre);
    std::printf("%-44s %4.1f/%5.1f %4.2f/%5.2f   %4.1f/%5.1f %4.2f/%5.2f %6.1f %6.2f\n",
                dir.parent_path().filename().string().substr(0, 44).c_str(), tracker.pos_median, tracker.pos_p90,
                tracker.rot_median, tracker.rot_p90, ours.pos_median, ours.pos_p90, ours.rot_median, ours.rot_p90,
                ours.offset, ours.offset_deg);
    if (std::getenv("EFC_EGO_VERBOSE"))
      std::printf("  anchor: jitter %.1f mm, walk %.1f mm/sqrt(s), %d frames weighted, %.2f of it in the first second\n",
                  1000 * ego.anchor.jitter_m, 1000 * ego.anchor.walk_m_per_sqrt_s, ego.anchor.frames,
                  ego.anchor.weight_first_second);
    const double v[10] = {tracker.pos_median, tracker.pos_p90, tracker.rot_median, tracker.rot_p90,
                         ours.pos_median,    ours.pos_p90,    ours.rot_median,    ours.rot_p90, ours.offset,
                          ours.offset_deg};
    for (int k = 0; k < 10; ++k) all[k].push_back(v[k]);
  }
  std::printf("%-44s %4.1f/%5.1f %4.2f/%5.2f   %4.1f/%5.1f %4.2f/%5.2f %6.1f %6.2f\n", "median over sequences",
              percentile(all[0], 0.5), percentile(all[1], 0.5), percentile(all[2], 0.5), percentile(all[3], 0.5),
              percentile(all[4], 0.5), percentile(all[5], 0.5), percentile(all[6], 0.5), percentile(all[7], 0.5),
              percentile(all[8], 0.5), percentile(all[9], 0.5));
  return 0;
}
