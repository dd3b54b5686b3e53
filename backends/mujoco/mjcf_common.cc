// Shared helpers of the MuJoCo backend: numbers, escaping, body layout, gains.
#include <algorithm>
#include <charconv>
#include <cmath>

#include "backends/mujoco/mjcf_internal.h"

namespace efc {
namespace mjcf {

std::string num(double v) {
  if (v == 0) return "0";  // also turns -0 into 0: nicer XML, same value
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string vec(const Vec3& v) { return num(v[0]) + " " + num(v[1]) + " " + num(v[2]); }

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '-': out += (!out.empty() && out.back() == '-') ? " -" : "-"; break;  // no "--" in comments
      default:
        // Control characters are not allowed in XML 1.0.
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') ? ' ' : c;
    }
  }
  return out;
}

Layout make_layout(const Object& obj) {
  Layout L;
  const size_t n = obj.parts.size();
  L.root = obj.root_index();
  L.body_world.assign(n, Vec3{0, 0, 0});
  L.children.assign(n, {});
  for (size_t i = 0; i < n; ++i) {
    const Part& p = obj.parts[i];
    if (!p.joint) continue;
    int parent = p.joint->parent_index >= 0 ? p.joint->parent_index : obj.find_part(p.joint->parent);
    if (parent >= 0) L.children[parent].push_back(static_cast<int>(i));
  }
  // A hinge body sits on its axis (so the joint is at the body origin);
  // every other body at its part's centre of mass.
  for (size_t i = 0; i < n; ++i) {
    const Part& p = obj.parts[i];
    const bool hinge = p.joint && (p.joint->type == JointType::Revolute ||
                                   p.joint->type == JointType::Continuous);
    L.body_world[i] = hinge ? p.joint->origin : p.mass_props.com;
  }
  return L;
}

void receptor_range(const Object& obj, const Function& f, double* lo, double* hi) {
  const int r = f.receptor_index >= 0 ? f.receptor_index : obj.find_part(f.receptor);
  const Joint& j = *obj.parts[r].joint;
  if (j.type == JointType::Continuous) {
    *lo = 0;
    *hi = 2 * 3.14159265358979323846;
  } else {
    *lo = j.lo;
    *hi = j.hi;
  }
}

namespace {

struct Composite {
  double mass = 0;
  Vec3 com{0, 0, 0};
  Mat3 inertia{};  // about com
};

void collect(const Object& obj, const Layout& L, int part, std::vector<int>* out) {
  out->push_back(part);
  for (int c : L.children[part]) collect(obj, L, c, out);
}

// Mass properties of a part and everything it carries.
Composite subtree(const Object& obj, const Layout& L, int part) {
  std::vector<int> parts;
  collect(obj, L, part, &parts);
  Composite c;
  for (int i : parts) {
    const MassProperties& mp = obj.parts[i].mass_props;
    c.mass += mp.mass;
    for (int k = 0; k < 3; ++k) c.com[k] += mp.mass * mp.com[k];
  }
  if (c.mass > 0)
    for (int k = 0; k < 3; ++k) c.com[k] /= c.mass;
  for (int i : parts) {
    const MassProperties& mp = obj.parts[i].mass_props;
    Vec3 d;
    for (int k = 0; k < 3; ++k) d[k] = mp.com[k] - c.com[k];
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s)
        c.inertia[r][s] += mp.inertia[r][s] + mp.mass * ((r == s ? dd : 0) - d[r] * d[s]);
  }
  return c;
}

}  // namespace

DriveGains drive_gains(const Object& obj, const Layout& L, int part, double q_lo, double q_hi,
                       double tolerance, double hz, double timestep, const double* stiffness,
                       const double* damping) {
  constexpr double kG = 9.81;
  const Joint& j = *obj.parts[part].joint;
  const Vec3& a = j.axis;
  // Inertia about the joint axis: of the rigid subtree (what the drive must
  // hold against) and of the part alone (what the joint may feel when the
  // parts it carries swing freely on their own joints).
  auto about_axis = [&](const Composite& c) {
    if (j.type == JointType::Prismatic) return c.mass;
    Vec3 r, aI{0, 0, 0};
    for (int k = 0; k < 3; ++k) r[k] = c.com[k] - j.origin[k];
    const double ra = r[0] * a[0] + r[1] * a[1] + r[2] * a[2];
    const double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    for (int k = 0; k < 3; ++k)
      for (int s = 0; s < 3; ++s) aI[k] += c.inertia[k][s] * a[s];
    return a[0] * aI[0] + a[1] * aI[1] + a[2] * aI[2] + c.mass * std::max(0.0, rr - ra * ra);
  };
  const Composite c = subtree(obj, L, part);
  Composite alone;
  alone.mass = obj.parts[part].mass_props.mass;
  alone.com = obj.parts[part].mass_props.com;
  alone.inertia = obj.parts[part].mass_props.inertia;
  double gravity = 0;
  if (j.type == JointType::Prismatic) {
    gravity = c.mass * kG * std::fabs(a[2]);
  } else {
    Vec3 r;
    for (int k = 0; k < 3; ++k) r[k] = c.com[k] - j.origin[k];
    const double ra = r[0] * a[0] + r[1] * a[1] + r[2] * a[2];
    const double perp = std::sqrt(std::max(0.0, r[0] * r[0] + r[1] * r[1] + r[2] * r[2] - ra * ra));
    // Worst case over the joint's rotation: the lever arm perpendicular to
    // both the axis and gravity's component across it.
    gravity = c.mass * kG * std::sqrt(std::max(0.0, 1 - a[2] * a[2])) * perp;
  }
  const double inertia = std::max(about_axis(c), 1e-9);
  const double own = std::max(about_axis(alone), 1e-9);
  const double ks = j.spring ? j.spring->stiffness : 0;
  const double rest = j.spring ? j.spring->rest : 0;
  const double stretch = std::max(std::fabs(q_lo - rest), std::fabs(q_hi - rest));
  const double load = ks * stretch + gravity + j.friction;
  DriveGains g;
  if (stiffness) {
    g.kp = *stiffness;
  } else {
    const double w = 2 * 3.14159265358979323846 * hz;
    g.kp = std::max(inertia * w * w, tolerance > 0 ? load / tolerance : 0.0);
  }
  // Semi-implicit Euler integrates the servo's stiffness and the velocity
  // actuator's damping explicitly: stable while omega dt <= 0.4 and
  // kv dt / I <= 1 for the inertia the joint actually feels, which can be as
  // low as the part's own when what it carries swings freely. Rotor inertia
  // (armature) bounds that inertia from below (M >= diag(armature)), so a stiff
  // servo on a light part keeps its gain and stays stable.
  const double wmax = 0.4 / timestep;
  const double kv_rigid =
      damping ? *damping : std::max(0.0, 2 * std::sqrt((g.kp + ks) * inertia) - j.damping);
  const double need = std::max((g.kp + ks) / (wmax * wmax), kv_rigid * timestep);
  if (need > own) g.armature = need - own;
  g.inertia = inertia + g.armature;
  if (damping) {
    g.kv = *damping;
  } else {
    g.kv = std::max(0.0, 2 * std::sqrt((g.kp + ks) * g.inertia) - j.damping);
  }
  return g;
}

}  // namespace mjcf
}  // namespace efc
