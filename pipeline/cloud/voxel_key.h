// The integer voxel a point falls in (internal to pipeline/cloud/: the
// downsampling filter and the per-part fusion share it).
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace efc::pipeline::detail {

struct VoxelKey {
  int64_t x = 0, y = 0, z = 0;
  bool operator==(const VoxelKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct VoxelKeyHash {
  size_t operator()(const VoxelKey& k) const {
    // Three large primes (Teschner et al.'s spatial hash).
    return static_cast<size_t>(k.x * 73856093LL) ^ static_cast<size_t>(k.y * 19349663LL) ^
           static_cast<size_t>(k.z * 83492791LL);
  }
};

// floor(p / voxel); the caller passes finite p and voxel > 0.
inline VoxelKey voxel_of(const Eigen::Vector3d& p, double voxel) {
  return {static_cast<int64_t>(std::floor(p.x() / voxel)), static_cast<int64_t>(std::floor(p.y() / voxel)),
          static_cast<int64_t>(std::floor(p.z() / voxel))};
}

}  // namespace efc::pipeline::detail
