// Robust point-to-plane ICP: how `efc infer` tracks a part (and the camera
// against the static scene) from frame to frame.
#pragma once

#include <Eigen/Geometry>

#include "pipeline/cloud/cloud.h"
#include "pipeline/cloud/kdtree.h"

namespace efc::pipeline {

enum class RobustLoss { Huber, Tukey, Cauchy };

struct IcpOptions {
  int max_iterations = 30;
  double max_correspondence = 0.02;   // m: pairs farther apart are ignored
  RobustLoss loss = RobustLoss::Tukey;
  double kernel_scale = 0.005;        // m: the robust kernel's scale on the point-to-plane residual
  double min_rotation_step = 1e-5;    // rad: stop when an update is smaller than both
  double min_translation_step = 1e-6; // m
  int subsample = 0;                  // >0: use at most this many source points (deterministic stride)
  // Directions whose normalized eigenvalue (IcpResult) is below this are left
  // alone: the data does not show motion along them. Tracking a part wants a
  // higher value than registering a whole scene: noise along a near-symmetry
  // (a round knob's spin) is not motion.
  double degenerate_threshold = 1e-3;
  // > -1 (and source normals given): pairs whose normals (the source's
  // turned by the current transform) have a smaller dot product are not
  // pairs. 0.5 (60 degrees) keeps a thin part from matching itself flipped.
  double min_normal_dot = -1;
};

struct IcpResult {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();  // maps source onto target
  bool converged = false;
  int iterations = 0;
  size_t correspondences = 0;   // pairs within max_correspondence at the end
  double inlier_fraction = 0;   // correspondences / source points used
  double rmse = 0;              // RMS point-to-plane residual over the pairs (m)
  // Eigenvalues (ascending) of the 6x6 Gauss-Newton Hessian J^T W J at the end: a
  // tiny smallest one means a direction the data does not constrain (a plane
  // sliding on itself, a cylinder turning about its axis).
  Eigen::Matrix<double, 6, 1> hessian_eigenvalues = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 6> hessian = Eigen::Matrix<double, 6, 6>::Zero();  // at the end, rotation first then translation

  // Additions. The Hessian's rotation part is about `hessian_center` (the
  // centroid of the matched, transformed source points), not the origin, so
  // it does not depend on where the camera is. Its blocks have different
  // units (rad vs m); `normalized_eigenvalues` are those of the Hessian with
  // rotations measured as arc length at `scale_length` (the RMS distance of
  // the matched points from the centre) and divided by the sum of weights:
  // unitless, about 1 for the best-constrained direction (a plane's normal),
  // ~0 for an unconstrained one. Compare those with a fixed threshold
  // (say 1e-3), not hessian_eigenvalues.
  Eigen::Vector3d hessian_center = Eigen::Vector3d::Zero();
  double scale_length = 0;
  Eigen::Matrix<double, 6, 1> normalized_eigenvalues = Eigen::Matrix<double, 6, 1>::Zero();
  // The unconstrained directions the solver left alone at the end (count of
  // normalized eigenvalues below its truncation threshold, 1e-3).
  int degenerate_directions = 0;
};

// Robust point-to-plane ICP (IRLS with the loss's weights; linearised small-angle
// update, re-orthonormalised): minimises sum rho(n_j . (T s_i - t_j)) over the
// nearest target point t_j of each transformed source point s_i. The target must have normals.
// Degenerate systems are solved in the constrained subspace only (do not blow up along
// an unconstrained direction: e.g. use a damped/truncated solve).
//
// Details: the update is solved in the eigenbasis of the normalized Hessian
// (see IcpResult) and directions with eigenvalue < 1e-3 are left at zero. The
// rotation step is applied exactly (angle-axis about the centroid), so T stays
// a rigid transform. The kernel's scale each iteration is
//   clamp(c * 1.4826 * median|r|, kernel_scale, max(kernel_scale, max_correspondence))
// (c: the loss's 95%-efficiency constant: Huber 1.345, Tukey 4.685, Cauchy
// 2.385), so a start misaligned by more than kernel_scale still pulls (Tukey
// would otherwise give every pair zero weight) and the kernel narrows to
// kernel_scale as the residuals shrink. Returns `initial` (converged false)
// when the target has no normals, either cloud is empty, or fewer than 6
// pairs are found.
IcpResult icp_point_to_plane(const Cloud& source, const Cloud& target, const KdTree& target_tree,
                             const Eigen::Isometry3d& initial, const IcpOptions& options);

// An IcpResult's `hessian` without the directions the solver leaves alone:
// those whose normalized eigenvalue (the Hessian with rotations as arc
// length at `scale_length`, over the weight sum, as in IcpResult) is below
// `threshold` get no information; the others keep theirs. Returns `hessian`
// unchanged when scale_length or the weight sum is not positive.
Eigen::Matrix<double, 6, 6> hessian_without_unconstrained(const Eigen::Matrix<double, 6, 6>& hessian,
                                                          double scale_length, double threshold);

}  // namespace efc::pipeline
