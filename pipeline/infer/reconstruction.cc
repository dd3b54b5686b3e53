#include "pipeline/infer/reconstruction.h"

#include <algorithm>
#include <chrono>

#include "pipeline/cloud/fusion.h"
#include "pipeline/infer/body_frame.h"

namespace efc::pipeline {

PartReconstruction reconstruct_part(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object,
                                    const PartTrack* track, const JointEstimate* joint) {
  const auto start = std::chrono::steady_clock::now();
  PartReconstruction out;
  // A part typed fixed because its turn or slide is its registration
  // slipping round a near-symmetry or across a flat face still has that
  // registration: its frames are fused along it, as a moving part's (the
  // slip turns the shape into itself, and the frames the registration
  // refused, a swapped or spilt mask, stay out).
  const bool moves = track && joint && (joint->type != "fixed" || joint->registration_slipped());
  FusionOptions fo;
  fo.voxel = 0.003;
  fo.min_observations = 2;
  PartFusion fusion(fo), outside(fo);
  const std::vector<Cloud>& outlines = obs.parts[part].outlines;
  const int n = static_cast<int>(obs.times.size());
  for (int f = 0; f < n; ++f) {
    if (moves && !track->tracked[f]) continue;
    Cloud c = part_cloud_in_object(obs, part, f, to_object);
    if (c.size() == 0) continue;
    Cloud o = f < static_cast<int>(outlines.size()) ? outlines[f] : Cloud{};
    transform_cloud(to_object[f], &o);
    // Frame -> reference configuration -> q = 0.
    if (moves) {
      const Eigen::Isometry3d to_zero = joint->reference_to_zero * track->motion[f].inverse();
      transform_cloud(to_zero, &c);
      transform_cloud(to_zero, &o);
    }
    fusion.add_frame(c);
    outside.add_frame(o);
    ++out.frames_fused;
  }
  // The masks' vote (fusion.h): the face behind a knob's rim, 2.6 cm deep,
  // that a mask drawn too wide took in stretched its hull by as much.
  out.fused = fusion.fused(&outside, &out.outline_dropped);
  std::string error;
  out.ok = closed_mesh(out.fused, &out.mesh, &error);
  if (!out.ok && out.outline_dropped > 0) {
    // A part barely seen (a few voxels, each in a frame or two) may lose to
    // its outline all it has: the vote never costs a part its mesh.
    out.fused = fusion.fused();
    out.outline_dropped = 0;
    out.ok = closed_mesh(out.fused, &out.mesh, &error);
  }
  if (!out.ok) {
    out.error = error.empty() ? "too few points" : error;
  } else {
    out.volume = mesh_volume(out.mesh);
    for (const Eigen::Vector3d& v : out.mesh.vertices) out.bounds.extend(v);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

bool stand_on_its_foot(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object,
                       PartReconstruction* recon) {
  if (recon->mesh.vertices.size() < 4) return false;
  const auto start = std::chrono::steady_clock::now();
  // How low the body goes: a coarse fusion's lowest points but a few (a
  // half percent: a stray below the floor would otherwise sink it).
  FusionOptions fo;
  fo.voxel = kStandingVoxel;
  fo.min_observations = 2;
  PartFusion fusion(fo);
  const int n = static_cast<int>(obs.times.size());
  for (int f = 0; f < n; ++f) {
    Cloud c = part_cloud_in_object(obs, part, f, to_object);
    if (c.size() > 0) fusion.add_frame(c);
  }
  std::vector<double> z;
  for (const Eigen::Vector3d& p : fusion.fused().points)
    if (p.allFinite()) z.push_back(p.z());
  for (const Eigen::Vector3d& v : recon->mesh.vertices) z.push_back(v.z());
  const size_t k = z.size() / 200;
  std::nth_element(z.begin(), z.begin() + static_cast<long>(k), z.end());
  const double foot = z[k];
  // The fine hull's corners as they are, and the body's top, where it faces
  // up, on columns down to the foot. Only what faces up stands on a column:
  // a mask that spills past the body's outline takes in the wall behind it
  // (its face towards the camera) or the floor around it (at the foot
  // already), and a column under the wall would fill the gap between them.
  // (The coarse points themselves stay out: they keep more of such a spill
  // than the fine fusion's outlier test does.)
  std::vector<Eigen::Vector3d> standing(recon->mesh.vertices.begin(), recon->mesh.vertices.end());
  if (recon->fused.has_normals())
    for (size_t i = 0; i < recon->fused.size(); ++i) {
      const Eigen::Vector3d& p = recon->fused.points[i];
      if (!p.allFinite() || recon->fused.normals[i].z() < kFacingUp || p.z() <= foot) continue;
      standing.push_back(p);
      standing.emplace_back(p.x(), p.y(), foot);
    }
  TriMesh mesh;
  std::string error;
  if (!convex_hull(standing, &mesh, &error)) return false;
  recon->mesh = std::move(mesh);
  recon->volume = mesh_volume(recon->mesh);
  recon->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

bool square_the_body(PartReconstruction* recon) {
  const Cloud& c = recon->fused;
  // The box's axes (body_frame.h): the upright faces' yaw, and whether most
  // of the surface faces the box's six faces. Kept for the joints' axis
  // prior (axis_prior.h), whatever becomes of the mesh.
  recon->frame = body_frame(c);
  const BodyFrame& frame = recon->frame;
  if (!c.has_normals() || c.size() < 50 || recon->mesh.vertices.size() < 4) return false;
  recon->box_share = frame.box_share;
  if (!frame.found) return false;
  const Eigen::Vector3d &u = frame.u, &v = frame.v, &up = frame.up;
  // The box: the standing hull's extent along u, v and up.
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : recon->mesh.vertices) box.extend(Eigen::Vector3d(p.dot(u), p.dot(v), p.z()));
  // A box seen is its faces: what was seen lies on the box's surface. Two
  // boxes in one (a hood's chimney on its canopy) or a disc and a pole (a
  // lamp's base) leave much of it inside.
  const Eigen::Vector3d size = box.sizes();
  const double near = std::max(kBoxSurfaceNear, kBoxSurfaceShareOfSize * size.minCoeff());
  size_t on_surface = 0, counted = 0;  // counted: the points with a normal, as body_frame counts them
  for (size_t i = 0; i < c.size(); ++i) {
    counted += c.points[i].allFinite() && c.normals[i].allFinite();
    if (!c.points[i].allFinite()) continue;
    const Eigen::Vector3d q(c.points[i].dot(u), c.points[i].dot(v), c.points[i].z());
    const double inside = (q - box.min()).cwiseMin(box.max() - q).minCoeff();
    on_surface += inside <= near;
  }
  recon->box_surface_share = counted ? static_cast<double>(on_surface) / counted : 0.0;
  if (recon->box_surface_share < kBoxSurfaceShare) return false;
  // A hull that fills its box already gains nothing (its bevels fit a
  // body's inset foot better than the box's corners do).
  const double box_volume = size.prod();
  recon->box_fill = box_volume > 0 ? recon->volume / box_volume : 1.0;
  if (recon->box_fill >= kBoxFilled) return false;
  std::vector<Eigen::Vector3d> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d b((k & 1) ? box.max().x() : box.min().x(), (k & 2) ? box.max().y() : box.min().y(),
                            (k & 4) ? box.max().z() : box.min().z());
    corners.push_back(b.x() * u + b.y() * v + b.z() * up);
  }
  TriMesh mesh;
  std::string error;
  if (!convex_hull(corners, &mesh, &error)) return false;
  recon->mesh = std::move(mesh);
  recon->volume = mesh_volume(recon->mesh);
  return true;
}

}  // namespace efc::pipeline
