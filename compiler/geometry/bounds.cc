// Extents of a geometry: axis-aligned boxes, representative surface points,
// and the oriented bounding box behind EgoFun3D's emitter rule.
#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "compiler/geometry/geometry.h"
#include "compiler/geometry/vec.h"

namespace efc {

using namespace geom;

namespace {

constexpr int kRimPoints = 32;  // per cylinder rim: a 32-gon is within 0.5% of the circle
constexpr size_t kMaxFacePlanes = 128;  // OBB candidates from hull faces (see oriented_bounding_box)

std::array<Vec3, 8> box_corners(const Geometry& g) {
  const Mat3 r = rpy_to_matrix(g.rpy);
  std::array<Vec3, 8> out;
  for (int i = 0; i < 8; ++i) {
    const Vec3 local{(i & 1 ? 0.5 : -0.5) * g.size[0], (i & 2 ? 0.5 : -0.5) * g.size[1],
                     (i & 4 ? 0.5 : -0.5) * g.size[2]};
    out[i] = add(g.center, apply(r, local));
  }
  return out;
}

// Grows [lo, hi] by [a, b]; `any` says whether [lo, hi] holds anything yet.
void grow(bool* any, Vec3* lo, Vec3* hi, const Vec3& a, const Vec3& b) {
  for (int k = 0; k < 3; ++k) {
    (*lo)[k] = *any ? std::min((*lo)[k], a[k]) : a[k];
    (*hi)[k] = *any ? std::max((*hi)[k], b[k]) : b[k];
  }
  *any = true;
}

// Exact boxes per kind; false for a geometry with no extent (an unloaded
// mesh, an empty compound), which a compound then skips.
bool exact_box(const Geometry& g, Vec3* lo, Vec3* hi) {
  bool any = false;
  switch (g.kind) {
    case GeomKind::Box:
      for (const Vec3& c : box_corners(g)) grow(&any, lo, hi, c, c);
      break;
    case GeomKind::Cylinder: {
      // Along coordinate k the rim circle reaches r * sqrt(1 - a_k^2) and
      // the caps l/2 * |a_k| beyond the centre.
      const Vec3 a = normalized(g.axis);
      Vec3 e;
      for (int k = 0; k < 3; ++k)
        e[k] = 0.5 * g.length * std::fabs(a[k]) + g.radius * std::sqrt(std::max(0.0, 1 - a[k] * a[k]));
      grow(&any, lo, hi, sub(g.center, e), add(g.center, e));
      break;
    }
    case GeomKind::Sphere: {
      const Vec3 e{g.radius, g.radius, g.radius};
      grow(&any, lo, hi, sub(g.center, e), add(g.center, e));
      break;
    }
    case GeomKind::Mesh:
      if (g.mesh)
        for (const Vec3& p : g.mesh->vertices) grow(&any, lo, hi, p, p);
      break;
    case GeomKind::Compound:
      for (const Geometry& c : g.children) {
        Vec3 clo, chi;
        if (exact_box(c, &clo, &chi)) grow(&any, lo, hi, clo, chi);
      }
      break;
  }
  return any;
}

// ---------------------------------------------------------------- OBB helpers
struct Frame {
  Mat3 axes;  // columns
};

// Area-weighted covariance of a closed surface (Gottschalk's OBB-tree
// formula): unlike the vertex covariance it does not depend on how densely
// each region happens to be tessellated.
Mat3 surface_covariance(const MeshData& m) {
  double area = 0;
  Vec3 mean{0, 0, 0};
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  for (const auto& t : m.triangles) {
    const Vec3 &p = m.vertices[t[0]], &q = m.vertices[t[1]], &r = m.vertices[t[2]];
    const double a = 0.5 * norm(cross(sub(q, p), sub(r, p)));
    const Vec3 c = mul(add(add(p, q), r), 1.0 / 3);
    area += a;
    mean = add(mean, mul(c, a));
    Eigen::Vector3d ce(c[0], c[1], c[2]), pe(p[0], p[1], p[2]), qe(q[0], q[1], q[2]), re(r[0], r[1], r[2]);
    s += a / 12.0 * (9 * ce * ce.transpose() + pe * pe.transpose() + qe * qe.transpose() + re * re.transpose());
  }
  Mat3 out{};
  if (area <= 0) return out;
  mean = mul(mean, 1.0 / area);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i][j] = s(i, j) / area - mean[i] * mean[j];
  return out;
}

Mat3 point_covariance(const std::vector<Vec3>& pts) {
  Vec3 mean{0, 0, 0};
  for (const Vec3& p : pts) mean = add(mean, p);
  mean = mul(mean, 1.0 / pts.size());
  Mat3 out{};
  for (const Vec3& p : pts) {
    const Vec3 d = sub(p, mean);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out[i][j] += d[i] * d[j] / pts.size();
  }
  return out;
}

Frame eigen_frame(const Mat3& cov) {
  Eigen::Matrix3d c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c(i, j) = cov[i][j];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(c);
  Frame f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.axes[i][j] = es.eigenvectors()(i, j);
  return f;
}

// A unit vector perpendicular to n, chosen from the world axis least
// aligned with n so the choice is stable.
Vec3 any_perpendicular(const Vec3& n) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(n[i]) < std::fabs(n[k])) k = i;
  Vec3 e{0, 0, 0};
  e[k] = 1;
  return normalized(cross(n, e));
}

// Andrew's monotone chain; returns hull indices counter-clockwise.
std::vector<std::array<double, 2>> hull_2d(std::vector<std::array<double, 2>> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto turn = [](const std::array<double, 2>& o, const std::array<double, 2>& a, const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::array<double, 2>> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && turn(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// The box with one face on the plane of normal n: the minimum-area
// rectangle of the points projected on that plane has a side along an edge
// of their 2D hull (Freeman & Shapira), so trying every edge finds it.
Frame face_frame(const Vec3& n, const std::vector<Vec3>& pts) {
  const Vec3 u = any_perpendicular(n), v = cross(n, u);
  std::vector<std::array<double, 2>> flat;
  flat.reserve(pts.size());
  for (const Vec3& p : pts) flat.push_back({dot(p, u), dot(p, v)});
  const auto h = hull_2d(flat);
  double best = INFINITY;
  std::array<double, 2> dir{1, 0};
  for (size_t i = 0; i < h.size() && h.size() >= 3; ++i) {
    const auto& a = h[i];
    const auto& b = h[(i + 1) % h.size()];
    double ex = b[0] - a[0], ey = b[1] - a[1];
    const double len = std::hypot(ex, ey);
    if (len == 0) continue;
    ex /= len;
    ey /= len;
    double lo0 = INFINITY, hi0 = -INFINITY, lo1 = INFINITY, hi1 = -INFINITY;
    for (const auto& q : h) {
      const double s = q[0] * ex + q[1] * ey, t = -q[0] * ey + q[1] * ex;
      lo0 = std::min(lo0, s), hi0 = std::max(hi0, s), lo1 = std::min(lo1, t), hi1 = std::max(hi1, t);
    }
    const double area = (hi0 - lo0) * (hi1 - lo1);
    if (area < best * (1 - 1e-12)) best = area, dir = {ex, ey};
  }
  const Vec3 a0 = add(mul(u, dir[0]), mul(v, dir[1]));
  const Vec3 a1 = cross(n, a0);
  Frame f;
  for (int i = 0; i < 3; ++i) f.axes[i] = {a0[i], a1[i], n[i]};
  return f;
}

// Deterministic, readable axes: column k is the one closest to world axis k,
// the first two point along their world axis, the third completes a
// right-handed frame.
Mat3 canonical(const Mat3& axes) {
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  int best = 0;
  double best_score = -1;
  for (int p = 0; p < 6; ++p) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += std::fabs(axes[k][perms[p][k]]);
    if (s > best_score + 1e-12) best_score = s, best = p;
  }
  Vec3 c[3];
  for (int k = 0; k < 3; ++k) c[k] = normalized(column(axes, perms[best][k]));
  for (int k = 0; k < 2; ++k)
    if (c[k][k] < 0) c[k] = mul(c[k], -1);
  c[2] = normalized(cross(c[0], c[1]));
  Mat3 out{};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = c[k][i];
  return out;
}

OrientedBox fit(const Mat3& axes, const std::vector<Vec3>& pts) {
  OrientedBox b;
  b.axes = canonical(axes);
  Vec3 mid{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = column(b.axes, k);
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& p : pts) lo = std::min(lo, dot(p, a)), hi = std::max(hi, dot(p, a));
    b.half[k] = 0.5 * (hi - lo);
    mid = add(mid, mul(a, 0.5 * (hi + lo)));
  }
  b.center = mid;
  return b;
}

}  // namespace

void bounding_box(const Geometry& g, Vec3* min, Vec3* max) {
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
  if (!exact_box(g, &lo, &hi)) lo = hi = Vec3{0, 0, 0};
  *min = lo;
  *max = hi;
}

std::vector<Vec3> sample_points(const Geometry& g) {
  std::vector<Vec3> out;
  switch (g.kind) {
    case GeomKind::Box: {
      const auto c = box_corners(g);
      out.assign(c.begin(), c.end());
      break;
    }
    case GeomKind::Cylinder: {
      const Mat3 r = rotation_z_to(g.axis);
      for (int cap = 0; cap < 2; ++cap)
        for (int i = 0; i < kRimPoints; ++i) {
          const double t = 2 * M_PI * i / kRimPoints;
          const Vec3 local{g.radius * std::cos(t), g.radius * std::sin(t), (cap ? 0.5 : -0.5) * g.length};
          out.push_back(add(g.center, apply(r, local)));
        }
      break;
    }
    case GeomKind::Sphere: {
      // The 6 axis extremes (so the axis-aligned box is exact), plus the 8
      // cube diagonals and 12 edge directions: 26 points, symmetric.
      for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
          for (int z = -1; z <= 1; ++z) {
            if (!x && !y && !z) continue;
            out.push_back(add(g.center, mul(normalized(Vec3{double(x), double(y), double(z)}), g.radius)));
          }
      break;
    }
    case GeomKind::Mesh:
      if (g.mesh) out = g.mesh->vertices;
      break;
    case GeomKind::Compound:
      for (const Geometry& c : g.children) {
        const auto p = sample_points(c);
        out.insert(out.end(), p.begin(), p.end());
      }
      break;
  }
  return out;
}

std::vector<Vec3> OrientedBox::corners() const {
  // Corner i takes +half along axis k where bit k of i is set, else -half.
  std::vector<Vec3> out(8);
  for (int i = 0; i < 8; ++i) {
    Vec3 p = center;
    for (int k = 0; k < 3; ++k) p = add(p, mul(column(axes, k), (i >> k & 1 ? 1 : -1) * half[k]));
    out[i] = p;
  }
  return out;
}

OrientedBox oriented_bounding_box(const Geometry& g) {
  // Candidates: the world axes, the principal axes of the hull surface, and
  // one box per distinct hull face (face on that plane, minimal rectangle in
  // it). The smallest volume wins, except that the world axes are kept
  // unless another box is clearly (kWorldBias) smaller: a modelled part that
  // is nearly axis-aligned should not get a box tilted by a few degrees for
  // a sub-percent gain. Ties go to the earlier candidate (deterministic).
  std::vector<Vec3> pts = sample_points(g);
  if (pts.empty()) {
    OrientedBox b;
    b.axes = identity();
    return b;
  }
  std::vector<Mat3> candidates{identity()};
  MeshData hull;
  std::string why;
  if (convex_hull(pts, &hull, &why)) {
    pts = hull.vertices;  // only hull vertices can touch a bounding box
    candidates.push_back(eigen_frame(surface_covariance(hull)).axes);
    // Hull faces grouped by plane (Qt splits a planar facet into triangles),
    // largest first; a dense reconstructed hull is capped at the
    // kMaxFacePlanes biggest planes, which keeps this O(hull size).
    struct Plane {
      Vec3 n;
      double area;
    };
    std::vector<Plane> planes;
    for (const auto& t : hull.triangles) {
      const Vec3& a = hull.vertices[t[0]];
      const Vec3 c = cross(sub(hull.vertices[t[1]], a), sub(hull.vertices[t[2]], a));
      const Vec3 n = normalized(c);
      if (norm(n) == 0) continue;
      bool seen = false;
      if (planes.size() < 4 * kMaxFacePlanes)  // beyond that, merging is not worth O(n^2)
        for (Plane& p : planes)
          if (dot(p.n, n) > 1 - 1e-10) {
            p.area += norm(c);
            seen = true;
            break;
          }
      if (!seen) planes.push_back({n, norm(c)});
    }
    std::stable_sort(planes.begin(), planes.end(), [](const Plane& a, const Plane& b) { return a.area > b.area; });
    if (planes.size() > kMaxFacePlanes) planes.resize(kMaxFacePlanes);
    for (const Plane& p : planes) candidates.push_back(face_frame(p.n, pts).axes);
  } else {
    // Flat or collinear points (a planar mesh): principal axes of the points
    // (one of them is the plane's normal).
    candidates.push_back(eigen_frame(point_covariance(pts)).axes);
  }
  // Volume padded by a hair of the size, so flat candidates still compare
  // by their area.
  Vec3 lo, hi;
  exact_box(g, &lo, &hi);
  const double pad = 1e-9 * (norm(sub(hi, lo)) + 1e-300);
  constexpr double kWorldBias = 0.98;
  OrientedBox best;
  double best_score = INFINITY;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const OrientedBox b = fit(candidates[i], pts);
    double score = (b.half[0] + pad) * (b.half[1] + pad) * (b.half[2] + pad);
    if (i == 0) score *= kWorldBias;  // candidates[0] is the world frame
    if (score < best_score * (1 - 1e-9)) best_score = score, best = b;
  }
  return best;
}

}  // namespace efc
