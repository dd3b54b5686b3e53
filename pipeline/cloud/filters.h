// Cloud clean-up: downsampling, outlier removal and normal estimation.
// Every filter skips points with non-finite coordinates and returns the
// points it keeps in their input order (deterministic output).
#pragma once

#include <Eigen/Core>

#include "pipeline/cloud/cloud.h"

namespace efc::pipeline {

// Every k-th point, so that at most max_points remain: deterministic and
// spread over the whole cloud (normals kept with their points).
// max_points <= 0 or a cloud that small already: unchanged.
void thin(Cloud* cloud, int max_points);
// Centroid per occupied voxel; normals averaged then normalised. Voxels come
// out in the order their first point came in. voxel not > 0: a copy of the
// finite points.
Cloud voxel_downsample(const Cloud& cloud, double voxel);
// Drops points whose mean distance to their k nearest neighbours exceeds mean + std_ratio * stddev of that statistic.
// k < 1 or fewer than k + 1 finite points: nothing is dropped (there is no
// statistic to judge by).
Cloud remove_statistical_outliers(const Cloud& cloud, int k, double std_ratio);
// Keeps points with at least min_neighbours others within radius.
Cloud remove_radius_outliers(const Cloud& cloud, double radius, int min_neighbours);
// PCA normals over k neighbours, oriented towards `viewpoint` (or away from the centroid when viewpoint is nullptr).
// k is clamped to [3, size]; a cloud of fewer than 3 points gets no normals.
void estimate_normals(Cloud* cloud, int k, const Eigen::Vector3d* viewpoint);

}  // namespace efc::pipeline
