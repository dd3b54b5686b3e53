#include "pipeline/cloud/mesh.h"

#include <Eigen/Geometry>  // cross products

#include <cstdio>
#include <cstdlib>
#include <map>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace efc::pipeline {

namespace {

void set_error(std::string* error, const std::string& text) {
  if (error != nullptr) *error = text;
}

// The first non-empty line of qhull's error report (it writes several; the
// first names the QH code and the problem).
std::string first_line(const std::string& text) {
  const size_t start = text.find_first_not_of(" \n");
  if (start == std::string::npos) return "";
  const size_t end = text.find('\n', start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

bool face_index_ok(const TriMesh& mesh, const Eigen::Vector3i& f) {
  const int n = static_cast<int>(mesh.vertices.size());
  return f.minCoeff() >= 0 && f.maxCoeff() < n;
}

}  // namespace

bool convex_hull(const std::vector<Eigen::Vector3d>& points, TriMesh* out, std::string* error) {
  if (out == nullptr) {
    set_error(error, "no output mesh");
    return false;
  }
  *out = TriMesh{};
  std::vector<coordT> coords;
  std::vector<size_t> origin;  // qhull's point id -> input index
  coords.reserve(points.size() * 3);
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) continue;
    coords.insert(coords.end(), {points[i].x(), points[i].y(), points[i].z()});
    origin.push_back(i);
  }
  if (origin.size() < 4) {
    set_error(error, "a convex hull needs at least 4 points, got " + std::to_string(origin.size()));
    return false;
  }

  // qhull reports errors to a FILE*: collect them in memory for *error.
  char* err_buf = nullptr;
  size_t err_len = 0;
  FILE* err_file = open_memstream(&err_buf, &err_len);
  qhT qh_storage;
  qhT* qh = &qh_storage;  // the qhull_ra.h macros expect the name `qh`
  qh_zero(qh, err_file);
  char command[] = "qhull Qt";
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(origin.size()), coords.data(), False, command,
                                     nullptr, err_file);
  bool ok = exit_code == 0;
  if (ok) {
    std::map<int, int> vertex_of_point;  // qhull point id -> mesh vertex (ordered: input order)
    facetT* facet;
    vertexT* vertex;
    vertexT** vertexp;
    FORALLfacets {
      FOREACHvertex_(facet->vertices) vertex_of_point.emplace(qh_pointid(qh, vertex->point), 0);
    }
    for (auto& [id, v] : vertex_of_point) {
      if (id < 0 || static_cast<size_t>(id) >= origin.size()) {
        ok = false;  // not an input point: cannot happen without options that add points
        break;
      }
      v = static_cast<int>(out->vertices.size());
      out->vertices.push_back(points[origin[static_cast<size_t>(id)]]);
    }
    if (ok) FORALLfacets {
      int ids[3];
      int n = 0;
      FOREACHvertex_(facet->vertices) {
        if (n < 3) ids[n] = vertex_of_point[qh_pointid(qh, vertex->point)];
        ++n;
      }
      if (n != 3) continue;  // "Qt" makes every facet a triangle; be safe anyway
      Eigen::Vector3i f(ids[0], ids[1], ids[2]);
      // qhull's vertex order says nothing about orientation: compare with the
      // facet's outward normal and flip when needed.
      const Eigen::Vector3d& a = out->vertices[f[0]];
      const Eigen::Vector3d& b = out->vertices[f[1]];
      const Eigen::Vector3d& c = out->vertices[f[2]];
      const Eigen::Vector3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
      if ((b - a).cross(c - a).dot(normal) < 0) std::swap(f[1], f[2]);
      out->faces.push_back(f);
    }
    if (out->faces.size() < 4) ok = false;
  }
  qh_freeqhull(qh, !qh_ALL);
  int cur_long = 0, tot_long = 0;
  qh_memfreeshort(qh, &cur_long, &tot_long);
  if (err_file != nullptr) std::fclose(err_file);
  const std::string qhull_text = err_buf != nullptr ? std::string(err_buf, err_len) : std::string();
  std::free(err_buf);
  if (!ok) {
    *out = TriMesh{};
    const std::string why = first_line(qhull_text);
    set_error(error, "no convex hull: the points are coplanar, collinear or coincident" +
                         (why.empty() ? std::string() : " (qhull: " + why + ")"));
  }
  return ok;
}

double mesh_volume(const TriMesh& mesh) {
  double six_v = 0;
  for (const auto& f : mesh.faces) {
    if (!face_index_ok(mesh, f)) continue;
    six_v += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]]));
  }
  return six_v / 6.0;
}

double mesh_area(const TriMesh& mesh) {
  double twice = 0;
  for (const auto& f : mesh.faces) {
    if (!face_index_ok(mesh, f)) continue;
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    twice += (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a).norm();
  }
  return twice / 2.0;
}

bool write_obj(const std::string& path, const TriMesh& mesh, std::string* error) {
  for (const auto& f : mesh.faces) {
    if (!face_index_ok(mesh, f)) {
      set_error(error, "cannot write " + path + ": a face names a vertex the mesh does not have");
      return false;
    }
  }
  const std::string temp = path + ".tmp";
  FILE* file = std::fopen(temp.c_str(), "w");
  if (file == nullptr) {
    set_error(error, "cannot write " + temp);
    return false;
  }
  bool ok = true;
  for (const auto& v : mesh.vertices)
    ok = ok && std::fprintf(file, "v %.9g %.9g %.9g\n", v.x(), v.y(), v.z()) > 0;
  for (const auto& f : mesh.faces)
    ok = ok && std::fprintf(file, "f %d %d %d\n", f[0] + 1, f[1] + 1, f[2] + 1) > 0;
  ok = (std::fclose(file) == 0) && ok;
  if (!ok || std::rename(temp.c_str(), path.c_str()) != 0) {
    std::remove(temp.c_str());
    set_error(error, "cannot write " + path);
    return false;
  }
  return true;
}

}  // namespace efc::pipeline
