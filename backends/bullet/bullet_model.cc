// make_model: the decisions behind the generated Bullet program (bullet_model.h).
#include "backends/bullet/bullet_model.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "backends/common/lowering.h"
#include "compiler/geometry/geometry.h"

namespace efc {
namespace bullet {

namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

// R^T v
Vec3 tmul(const Mat3& r, const Vec3& v) {
  Vec3 o{0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) o[i] += r[k][i] * v[k];
  return o;
}

// A^T B
Mat3 tmulm(const Mat3& a, const Mat3& b) {
  Mat3 o{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) o[i][j] += a[k][i] * b[k][j];
  return o;
}

Mat3 identity() {
  Mat3 r{};
  for (int i = 0; i < 3; ++i) r[i][i] = 1;
  return r;
}

void add_shapes(const Geometry& g, int link, const Vec3& com, const Mat3& frame,
                std::vector<Shape>* out) {
  Shape s;
  s.link = link;
  switch (g.kind) {
    case GeomKind::Compound:
      for (const Geometry& c : g.children) add_shapes(c, link, com, frame, out);
      return;
    case GeomKind::Box:
      s.kind = Shape::Box;
      s.size = {g.size[0] / 2, g.size[1] / 2, g.size[2] / 2};
      s.pos = tmul(frame, sub(g.center, com));
      s.rot = to_quat(tmulm(frame, rpy_to_matrix(g.rpy)));
      break;
    case GeomKind::Cylinder: {
      Vec3 a = g.axis;
      const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
      if (n > 0)
        for (double& v : a) v /= n;
      s.kind = Shape::Cylinder;
      s.size = {g.radius, g.radius, g.length / 2};
      s.pos = tmul(frame, sub(g.center, com));
      s.rot = to_quat(tmulm(frame, rotation_z_to(a)));
      break;
    }
    case GeomKind::Sphere:
      s.kind = Shape::Sphere;
      s.size = {g.radius, 0, 0};
      s.pos = tmul(frame, sub(g.center, com));
      break;
    case GeomKind::Mesh: {
      s.kind = Shape::Hull;
      if (!g.mesh) return;
      // Collision uses the convex hull, as MuJoCo does for every mesh geom.
      MeshData hull;
      std::string error;
      const std::vector<Vec3>& pts =
          convex_hull(g.mesh->vertices, &hull, &error) ? hull.vertices : g.mesh->vertices;
      for (const Vec3& p : pts) s.points.push_back(tmul(frame, sub(p, com)));
      break;
    }
  }
  out->push_back(s);
}

}  // namespace

void principal_axes(const Mat3& inertia, Vec3* moments, Mat3* axes) {
  Mat3 a = inertia, v = identity();
  const double scale = std::fabs(a[0][0]) + std::fabs(a[1][1]) + std::fabs(a[2][2]);
  const double off = std::fabs(a[0][1]) + std::fabs(a[0][2]) + std::fabs(a[1][2]);
  if (!(scale > 0) || off <= 1e-12 * scale) {
    *moments = {a[0][0], a[1][1], a[2][2]};
    *axes = identity();
    return;
  }
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double o = std::fabs(a[0][1]) + std::fabs(a[0][2]) + std::fabs(a[1][2]);
    if (o <= 1e-15 * scale) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1 : -1) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A <- A J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // A <- J^T A
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {  // V <- V J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  const double det = v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) -
                     v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) +
                     v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]);
  if (det < 0)
    for (int k = 0; k < 3; ++k) v[k][2] = -v[k][2];
  *moments = {a[0][0], a[1][1], a[2][2]};
  *axes = v;
}

Quat to_quat(const Mat3& m) {
  // Shepperd's method; q rotates v as R v.
  const double tr = m[0][0] + m[1][1] + m[2][2];
  Quat q;
  if (tr > 0) {
    const double s = std::sqrt(tr + 1) * 2;
    q = {(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4};
  } else if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
    const double s = std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]) * 2;
    q = {s / 4, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s};
  } else if (m[1][1] > m[2][2]) {
    const double s = std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]) * 2;
    q = {(m[0][1] + m[1][0]) / s, s / 4, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s};
  } else {
    const double s = std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]) * 2;
    q = {(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / 4, (m[1][0] - m[0][1]) / s};
  }
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= n;
  return q;
}

Model make_model(const Object& obj, double timestep) {
  Model M;
  const size_t n = obj.parts.size();
  const lowering::Layout L = lowering::make_layout(obj);
  M.part_link.assign(n, -1);

  // Links in breadth-first order from the root: parents before children.
  std::vector<int> order;
  std::vector<int> queue{L.root};
  for (size_t i = 0; i < queue.size(); ++i) {
    for (int c : L.children[queue[i]]) {
      order.push_back(c);
      queue.push_back(c);
    }
  }
  for (size_t i = 0; i < order.size(); ++i) M.part_link[order[i]] = static_cast<int>(i);

  // Receptors the profile moves are prescribed kinematically.
  const std::vector<int> profile_driven = lowering::profile_driven_receptors(obj);
  const std::set<int> kinematic(profile_driven.begin(), profile_driven.end());

  auto frame_of = [&](const Part& p, Vec3* moments, Mat3* frame) {
    principal_axes(p.mass_props.inertia, moments, frame);
    if (!(frame == nullptr) && (*frame != identity())) M.off_diagonal = true;
  };

  const Part& root = obj.parts[L.root];
  M.base.part = L.root;
  M.base.mass = root.mass_props.mass;
  M.base.com = root.mass_props.com;
  frame_of(root, &M.base.inertia, &M.base.frame);
  add_shapes(root.geometry, -1, M.base.com, M.base.frame, &M.shapes);

  for (int pi : order) {
    const Part& p = obj.parts[pi];
    const Joint& j = *p.joint;
    Link k;
    k.part = pi;
    const int parent_part = j.parent_index >= 0 ? j.parent_index : obj.find_part(j.parent);
    k.parent = M.part_link[parent_part];
    const Vec3 pcom = k.parent < 0 ? M.base.com : M.links[k.parent].com;
    const Mat3 pframe = k.parent < 0 ? M.base.frame : M.links[k.parent].frame;
    k.type = j.type;
    k.mass = p.mass_props.mass;
    k.com = p.mass_props.com;
    frame_of(p, &k.inertia, &k.frame);
    for (double& v : k.inertia) v = std::max(v, 1e-12);
    k.rot_parent_to_this = to_quat(tmulm(k.frame, pframe));
    k.axis = tmul(k.frame, j.axis);
    if (j.type == JointType::Revolute || j.type == JointType::Continuous) {
      k.parent_com_to_pivot = tmul(pframe, sub(j.origin, pcom));
      k.pivot_to_com = tmul(k.frame, sub(k.com, j.origin));
    } else {
      k.parent_com_to_pivot = tmul(pframe, sub(k.com, pcom));
      k.pivot_to_com = {0, 0, 0};
    }
    k.limited = j.type == JointType::Revolute || j.type == JointType::Prismatic;
    k.lo = j.lo;
    k.hi = j.hi;
    double init = j.initial.value_or(0.0);
    if (k.limited) init = std::clamp(init, j.lo, j.hi);
    k.initial = j.movable() ? init : 0;
    k.damping = j.damping;
    k.friction = j.friction;
    if (j.spring) {
      k.spring_k = j.spring->stiffness;
      k.spring_rest = j.spring->rest;
    }
    if (j.movable()) {
      const lowering::DriveGains g =
          lowering::drive_gains(obj, L, pi, j.lo, j.hi, 0, 0, timestep, nullptr, nullptr);
      k.joint_inertia = g.inertia - g.armature;
      k.kinematic = kinematic.count(pi) > 0;
      // Geometry effects take the common layer's gains (as the MuJoCo target).
      for (const Function& f : obj.functions)
        if (f.effect.type == EffectType::Geometry && lowering::effector_part(obj, f) == pi) {
          k.kp = lowering::geometry_drive(obj, L, f, timestep).kp;
          if (f.effect.damping) k.kv_explicit = *f.effect.damping;
        }
    }
    M.links.push_back(k);
    add_shapes(p.geometry, static_cast<int>(M.links.size()) - 1, k.com, k.frame, &M.shapes);
  }

  // What Bullet cannot express (W0900): effects it does not simulate.
  for (size_t fi = 0; fi < obj.functions.size(); ++fi) {
    const Function& f = obj.functions[fi];
    std::string what;
    switch (f.effect.type) {
      case EffectType::Geometry: break;
      case EffectType::Illumination:
        what = "illumination (Bullet has no lights): no light is emitted; measured is the runtime's lumens";
        break;
      case EffectType::Temperature:
        what = "temperature (Bullet has no heat): measured is the runtime's lagged temperature";
        break;
      case EffectType::Fluid:
        what = "fluid (Bullet here simulates no droplets): measured is the flow of droplets the runtime "
               "emits, counted over 0.5 s as the MuJoCo target counts them";
        break;
      case EffectType::Airflow:
        what = "airflow (Bullet has no air): no drag is applied; measured is the runtime's outlet speed";
        break;
    }
    if (what.empty()) continue;
    M.warnings.push_back("bullet: function '" + f.name + "': " + what);
    M.warning_pointers.push_back(f.effect.loc.pointer);
  }
  for (const Part& p : obj.parts)
    if (p.rgba) {  // said once, at the first colour
      M.warnings.push_back("bullet: rgba (the program is headless and draws nothing): colours are not emitted");
      M.warning_pointers.push_back(p.loc.pointer + "/rgba");
      break;
    }
  for (const Link& k : M.links)
    if (k.friction > 0 && !k.kinematic) {
      // Represented, with a different model: say so once.
      M.warnings.push_back("bullet: joint friction is a velocity motor with impulse limit friction*dt "
                           "(MuJoCo: frictionloss); part '" + obj.parts[k.part].name + "'");
      M.warning_pointers.push_back(obj.parts[k.part].joint->loc.pointer + "/friction");
    }
  return M;
}

}  // namespace bullet
}  // namespace efc
