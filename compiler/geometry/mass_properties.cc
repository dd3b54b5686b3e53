// Mass properties at unit density: closed-form for primitives, exact volume
// integrals for closed triangle meshes, parallel-axis sums for compounds.
#include <cmath>

#include "compiler/geometry/geometry.h"
#include "compiler/geometry/vec.h"

namespace efc {

using namespace geom;

namespace {

// Inertia `local` given in a frame rotated by R, expressed in object axes.
Mat3 rotate_tensor(const Mat3& r, const Mat3& local) { return matmul(matmul(r, local), transpose(r)); }

MassProperties solid(double volume, const Vec3& com, const Mat3& inertia) {
  MassProperties mp;
  mp.mass = mp.volume = volume;
  mp.com = com;
  mp.inertia = inertia;
  return mp;
}

MassProperties box(const Geometry& g) {
  const double a = g.size[0], b = g.size[1], c = g.size[2];
  const double v = a * b * c;
  const Mat3 local{{{v * (b * b + c * c) / 12, 0, 0}, {0, v * (a * a + c * c) / 12, 0}, {0, 0, v * (a * a + b * b) / 12}}};
  return solid(v, g.center, rotate_tensor(rpy_to_matrix(g.rpy), local));
}

MassProperties cylinder(const Geometry& g) {
  const double r = g.radius, l = g.length;
  const double v = M_PI * r * r * l;
  const double side = v * (3 * r * r + l * l) / 12;
  const Mat3 local{{{side, 0, 0}, {0, side, 0}, {0, 0, v * r * r / 2}}};
  return solid(v, g.center, rotate_tensor(rotation_z_to(g.axis), local));
}

MassProperties sphere(const Geometry& g) {
  const double r = g.radius;
  const double v = 4.0 / 3.0 * M_PI * r * r * r;
  const double i = 0.4 * v * r * r;
  return solid(v, g.center, Mat3{{{i, 0, 0}, {0, i, 0}, {0, 0, i}}});
}

// Polyhedral mass properties by the divergence theorem over the triangles
// (D. Eberly, "Polyhedral Mass Properties (Revisited)", after Mirtich 1996).
// Exact for any closed, consistently wound mesh; the sign of the volume
// tells the winding, and an inward mesh is handled by negating everything.
MassProperties closed_mesh(const MeshData& m) {
  if (m.vertices.empty() || m.triangles.empty()) return MassProperties{};
  // Integrate about the vertex mean: far from the origin, the cubic terms
  // would otherwise cancel catastrophically.
  Vec3 ref{0, 0, 0};
  for (const Vec3& p : m.vertices) ref = add(ref, p);
  ref = mul(ref, 1.0 / m.vertices.size());

  double in[10] = {};
  auto sub_expr = [](double w0, double w1, double w2, double& f1, double& f2, double& f3, double& g0,
                     double& g1, double& g2) {
    const double t0 = w0 + w1;
    f1 = t0 + w2;
    const double t1 = w0 * w0;
    const double t2 = t1 + w1 * t0;
    f2 = t2 + w2 * f1;
    f3 = w0 * t1 + w1 * t2 + w2 * f2;
    g0 = f2 + w0 * (f1 + w0);
    g1 = f2 + w1 * (f1 + w1);
    g2 = f2 + w2 * (f1 + w2);
  };
  const int nv = static_cast<int>(m.vertices.size());
  for (const auto& t : m.triangles) {
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= nv || t[1] >= nv || t[2] >= nv) continue;
    const Vec3 p0 = sub(m.vertices[t[0]], ref), p1 = sub(m.vertices[t[1]], ref), p2 = sub(m.vertices[t[2]], ref);
    const Vec3 d = cross(sub(p1, p0), sub(p2, p0));
    double f1[3], f2[3], f3[3], g0[3], g1[3], g2[3];
    for (int k = 0; k < 3; ++k) sub_expr(p0[k], p1[k], p2[k], f1[k], f2[k], f3[k], g0[k], g1[k], g2[k]);
    in[0] += d[0] * f1[0];
    in[1] += d[0] * f2[0];
    in[2] += d[1] * f2[1];
    in[3] += d[2] * f2[2];
    in[4] += d[0] * f3[0];
    in[5] += d[1] * f3[1];
    in[6] += d[2] * f3[2];
    in[7] += d[0] * (p0[1] * g0[0] + p1[1] * g1[0] + p2[1] * g2[0]);
    in[8] += d[1] * (p0[2] * g0[1] + p1[2] * g1[1] + p2[2] * g2[1]);
    in[9] += d[2] * (p0[0] * g0[2] + p1[0] * g1[2] + p2[0] * g2[2]);
  }
  const double mult[10] = {1.0 / 6, 1.0 / 24, 1.0 / 24, 1.0 / 24, 1.0 / 60, 1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (int i = 0; i < 10; ++i) in[i] *= mult[i];
  if (in[0] < 0)  // wound inward: the same solid with every normal flipped
    for (double& x : in) x = -x;
  const double v = in[0];
  if (!(v > 0)) return MassProperties{};
  const Vec3 c{in[1] / v, in[2] / v, in[3] / v};
  const double xx = in[5] + in[6] - v * (c[1] * c[1] + c[2] * c[2]);
  const double yy = in[4] + in[6] - v * (c[2] * c[2] + c[0] * c[0]);
  const double zz = in[4] + in[5] - v * (c[0] * c[0] + c[1] * c[1]);
  const double xy = -(in[7] - v * c[0] * c[1]);
  const double yz = -(in[8] - v * c[1] * c[2]);
  const double zx = -(in[9] - v * c[2] * c[0]);
  return solid(v, add(c, ref), Mat3{{{xx, xy, zx}, {xy, yy, yz}, {zx, yz, zz}}});
}

MassProperties mesh(const Geometry& g) {
  if (!g.mesh) return MassProperties{};  // not loaded: resolve() loads meshes first
  if (g.mesh->closed) return closed_mesh(*g.mesh);
  // An open surface bounds no volume; its convex hull is the spec's stand-in.
  MeshData hull;
  std::string why;
  if (!convex_hull(g.mesh->vertices, &hull, &why)) return MassProperties{};  // flat: no volume
  return closed_mesh(hull);
}

// Sum of pieces about their common centre of mass (parallel-axis theorem).
MassProperties compound(const Geometry& g) {
  std::vector<MassProperties> parts;
  MassProperties total;
  Vec3 moment{0, 0, 0};
  for (const Geometry& child : g.children) {
    parts.push_back(unit_density_mass_properties(child));
    total.mass += parts.back().mass;
    total.volume += parts.back().volume;
    moment = add(moment, mul(parts.back().com, parts.back().mass));
  }
  if (!(total.mass > 0)) return MassProperties{};
  total.com = mul(moment, 1.0 / total.mass);
  for (const MassProperties& p : parts) {
    const Vec3 d = sub(p.com, total.com);
    const double d2 = dot(d, d);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        total.inertia[i][j] += p.inertia[i][j] + p.mass * ((i == j ? d2 : 0.0) - d[i] * d[j]);
  }
  return total;
}

}  // namespace

MassProperties unit_density_mass_properties(const Geometry& g) {
  switch (g.kind) {
    case GeomKind::Box: return box(g);
    case GeomKind::Cylinder: return cylinder(g);
    case GeomKind::Sphere: return sphere(g);
    case GeomKind::Mesh: return mesh(g);
    case GeomKind::Compound: return compound(g);
  }
  return MassProperties{};
}

MassProperties with_mass(const MassProperties& unit, double mass) {
  // Inertia scales linearly with density; the com and volume do not change.
  // A geometry without volume has no inertia to scale: the caller diagnoses.
  MassProperties mp = unit;
  mp.mass = mass;
  const double k = unit.mass > 0 ? mass / unit.mass : 0.0;
  for (auto& row : mp.inertia)
    for (double& x : row) x *= k;
  return mp;
}

}  // namespace efc
