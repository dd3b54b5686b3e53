// Geometry of parts: meshes (read with Assimp), convex hulls (Qhull), mass
// properties (primitive formulas, mesh volume integrals), bounding boxes, and
// the oriented bounding box used by EgoFun3D's emitter rule.
//
// Everything is in the object frame (spec v1: meshes arrive in the object
// frame, at joint position 0).
#pragma once

#include <string>
#include <vector>

#include "compiler/ir.h"

namespace efc {

// 3x3 rotation from roll-pitch-yaw (extrinsic x, then y, then z: R = Rz*Ry*Rx,
// the URDF convention).
Mat3 rpy_to_matrix(const Vec3& rpy);
// Rotation taking +z onto `axis` (unit), for cylinders.
Mat3 rotation_z_to(const Vec3& axis);

// Loads an OBJ, STL or PLY file, applies `scale` per axis, merges all meshes
// in the file into one, and sets `closed` (every edge shared by exactly two
// triangles). Returns false with a one-line reason in *error.
bool load_mesh(const std::string& path, const Vec3& scale, MeshData* out, std::string* error);

// Convex hull of a point set (Qhull). Returns a closed, outward-oriented mesh.
// Returns false if the points are degenerate (fewer than 4, coplanar).
bool convex_hull(const std::vector<Vec3>& points, MeshData* out, std::string* error);

// Mass properties at unit density (mass == volume). For a mesh that is not
// closed, the convex hull is used (the caller warns). For a compound, the
// pieces are summed (overlaps are counted twice, as every simulator does).
// Requires meshes to be loaded (Geometry::mesh set).
MassProperties unit_density_mass_properties(const Geometry& g);

// Mass properties scaled to a total mass.
MassProperties with_mass(const MassProperties& unit, double mass);

// Axis-aligned bounding box in the object frame.
void bounding_box(const Geometry& g, Vec3* min, Vec3* max);

// Representative surface points: mesh vertices, box corners, points on the
// rims of cylinders and on spheres (enough for bounding boxes and hulls).
std::vector<Vec3> sample_points(const Geometry& g);

struct OrientedBox {
  Vec3 center{0, 0, 0};
  Mat3 axes{};        // columns are the box's unit axes, right-handed
  Vec3 half{0, 0, 0};  // half extents along each axis
  std::vector<Vec3> corners() const;  // the 8 corners
};
// Oriented bounding box by principal components of the sample points' hull.
OrientedBox oriented_bounding_box(const Geometry& g);

// A binary STL of `mesh` translated by `offset` (for backends that place
// meshes in a link frame), as bytes.
std::string binary_stl(const MeshData& mesh, const Vec3& offset);
// The same, written to `path`. Returns false with a reason on I/O failure.
bool write_binary_stl(const std::string& path, const MeshData& mesh, const Vec3& offset,
                      std::string* error);

}  // namespace efc
