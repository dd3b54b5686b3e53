// Triangle meshes for a part's collision and inertia: the convex hull, its
// volume and area, and OBJ output.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace efc::pipeline {

struct TriMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;  // counter-clockwise seen from outside
};

// The convex hull (qhull, reentrant API, option "Qt" triangulated) of the points; false with *error when fewer than 4 non-coplanar points.
// Non-finite points are ignored. Only the hull's vertices are kept
// (renumbered densely, in input order).
bool convex_hull(const std::vector<Eigen::Vector3d>& points, TriMesh* out, std::string* error);
double mesh_volume(const TriMesh& mesh);   // signed divergence-theorem volume (positive for outward faces)
double mesh_area(const TriMesh& mesh);
// Wavefront OBJ ("v x y z" / "f i j k", 1-based), numbers as %.9g; writes to a temp file then renames (no partial output).
bool write_obj(const std::string& path, const TriMesh& mesh, std::string* error);

}  // namespace efc::pipeline
