#include "pipeline/infer/reconstruction.h"

#include <chrono>

#include "pipeline/cloud/fusion.h"

namespace efc::pipeline {

PartReconstruction reconstruct_part(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object,
                                    const PartTrack* track, const JointEstimate* joint) {
  const auto start = std::chrono::steady_clock::now();
  PartReconstruction out;
  // A part typed fixed because its turn is its registration slipping round a
  // near-symmetry still has that registration: its frames are fused along
  // it, as a moving part's (the slip turns the shape into itself, and the
  // frames the registration refused, a swapped or spilt mask, stay out).
  const bool moves = track && joint && (joint->type != "fixed" || joint->turn_taken_for_slip);
  FusionOptions fo;
  fo.voxel = 0.003;
  fo.min_observations = 2;
  PartFusion fusion(fo);
  const int n = static_cast<int>(obs.times.size());
  for (int f = 0; f < n; ++f) {
    if (moves && !track->tracked[f]) continue;
    Cloud c = part_cloud_in_object(obs, part, f, to_object);
    if (c.size() == 0) continue;
    // Frame -> reference configuration -> q = 0.
    if (moves) transform_cloud(joint->reference_to_zero * track->motion[f].inverse(), &c);
    fusion.add_frame(c);
    ++out.frames_fused;
  }
  out.fused = fusion.fused();
  std::string error;
  out.ok = closed_mesh(out.fused, &out.mesh, &error);
  if (!out.ok) {
    out.error = error.empty() ? "too few points" : error;
  } else {
    out.volume = mesh_volume(out.mesh);
    for (const Eigen::Vector3d& v : out.mesh.vertices) out.bounds.extend(v);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace efc::pipeline
