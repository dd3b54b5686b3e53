// Convex hulls through Qhull's reentrant C API (libqhull_r).
#include <cstdio>
#include <cstdlib>
#include <map>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "compiler/geometry/geometry.h"
#include "compiler/geometry/vec.h"

namespace efc {

using namespace geom;

bool convex_hull(const std::vector<Vec3>& points, MeshData* out, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  *out = MeshData{};
  if (points.size() < 4) return fail("convex hull needs at least 4 points");
  std::vector<coordT> coords;
  coords.reserve(points.size() * 3);
  for (const Vec3& p : points) {
    for (double x : p) {
      if (!std::isfinite(x)) return fail("convex hull of non-finite points");
      coords.push_back(x);
    }
  }

  // Qhull reports through FILE*; collect its messages in memory so a
  // degenerate input gives a one-line reason instead of noise on stderr.
  char* err_text = nullptr;
  size_t err_len = 0;
  FILE* errfile = open_memstream(&err_text, &err_len);

  qhT qh_qh;
  qhT* qh = &qh_qh;
  qh_zero(qh, errfile);
  // Qt: triangulated output (every facet simplicial). No joggle: an exact
  // hull of the given points is what the mass and the OBB need.
  char flags[] = "qhull Qt";
  const int exitcode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(),
                                    False, flags, nullptr, errfile);
  bool ok = exitcode == 0;
  if (ok) {
    std::map<int, int> remap;  // input point id -> hull vertex index
    facetT* facet;
    FORALLfacets {
      if (facet->upperdelaunay || !facet->simplicial) continue;
      std::array<int, 3> tri{};
      int c = 0;
      vertexT* vertex;
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) {
        if (c >= 3) break;
        const int id = qh_pointid(qh, vertex->point);
        auto it = remap.find(id);
        if (it == remap.end()) {
          it = remap.emplace(id, static_cast<int>(out->vertices.size())).first;
          out->vertices.push_back(points[id]);
        }
        tri[c++] = it->second;
      }
      if (c != 3) continue;
      // Qhull's vertex order does not fix the winding (that is toporient's
      // job); comparing with the outward facet normal is simpler and exact.
      const Vec3& a = out->vertices[tri[0]];
      const Vec3 n = cross(sub(out->vertices[tri[1]], a), sub(out->vertices[tri[2]], a));
      const Vec3 outward{facet->normal[0], facet->normal[1], facet->normal[2]};
      if (dot(n, outward) < 0) std::swap(tri[1], tri[2]);
      out->triangles.push_back(tri);
    }
    ok = out->triangles.size() >= 4;
  }
  // Release everything Qhull allocated, long and short memory alike.
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (errfile) std::fclose(errfile);
  std::string qhull_msg;
  if (err_text) {
    qhull_msg.assign(err_text, err_len);
    std::free(err_text);
  }
  if (!ok) {
    *out = MeshData{};
    // Qhull's first line is the QH code and the reason (e.g. "initial simplex is flat").
    std::string first = qhull_msg.substr(0, qhull_msg.find('\n'));
    while (!first.empty() && (first.back() == '\r' || first.back() == ' ')) first.pop_back();
    return fail("degenerate point set (coplanar or collinear): " +
                (first.empty() ? std::string("qhull failed") : first));
  }
  out->closed = true;
  return true;
}

}  // namespace efc
