#include "synth/hand.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "synth/scene.h"

namespace efc::synth {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.5g", std::fabs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

Eigen::Isometry3d body_pose(const mjData* d, int body) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = d->xmat[9 * body + 3 * r + c];
  T.linear() = R;
  T.translation() = Vector3d(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]);
  return T;
}

// The hand at rest, relative to the camera: low and to the right, below
// the image, fingers forward.
Eigen::Isometry3d hand_rest(const CameraPose& cam) {
  Eigen::Isometry3d H = Eigen::Isometry3d::Identity();
  Matrix3d R;
  R.col(2) = cam.rotation.col(2);  // fingers along the view
  R.col(0) = cam.rotation.col(0);  // across: the camera's right
  R.col(1) = R.col(2).cross(R.col(0));
  H.linear() = R;
  H.translation() = cam.position + cam.rotation * Vector3d(0.16, 0.42, 0.30);
  return H;
}

Eigen::Isometry3d blend(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double w) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() =
      Eigen::Quaterniond(a.linear()).slerp(w, Eigen::Quaterniond(b.linear())).toRotationMatrix();
  out.translation() = (1 - w) * a.translation() + w * b.translation();
  return out;
}

}  // namespace

HandState hand_at(double t, const CameraPose& camera, const std::vector<Grasp>& grasps,
                  const std::vector<Visit>& visits, const mjData* d) {
  HandState h;
  h.pose = hand_rest(camera);
  for (size_t i = 0; i < grasps.size() && i < visits.size(); ++i) {
    const Visit& v = visits[i];
    if (t < v.reach || t > v.leave) continue;
    const Eigen::Isometry3d held = grasps[i].hand_pose(d);
    if (t < v.grasp) {
      h.pose = blend(h.pose, held, smoothstep((t - v.reach) / (v.grasp - v.reach)));
    } else if (t <= v.release) {
      h.pose = held;
      h.holding = &grasps[i];
    } else {
      h.pose = blend(held, h.pose, smoothstep((t - v.release) / (v.leave - v.release)));
    }
  }
  return h;
}

std::string hand_body_xml(const SceneKnobs& knobs, const Vector3d& parked) {
  static constexpr std::array<std::array<double, 3>, 4> kSkin = {
      {{0.87, 0.70, 0.58}, {0.76, 0.57, 0.45}, {0.55, 0.38, 0.28}, {0.36, 0.24, 0.17}}};
  static constexpr std::array<std::array<double, 3>, 4> kSleeve = {
      {{0.15, 0.2, 0.35}, {0.5, 0.1, 0.1}, {0.2, 0.2, 0.2}, {0.35, 0.45, 0.3}}};
  const int tone = ((knobs.skin_tone % 4) + 4) % 4;
  const double s = std::clamp(knobs.hand_scale, 0.5, 2.0);
  const auto& k = kSkin[tone];
  const auto& v = kSleeve[(tone + knobs.room_style) % 4];
  const std::string skin = num(k[0]) + " " + num(k[1]) + " " + num(k[2]) + " 1";
  const std::string sleeve = num(v[0]) + " " + num(v[1]) + " " + num(v[2]) + " 1";
  auto p = [s](double x, double y, double z) { return num(s * x) + " " + num(s * y) + " " + num(s * z); };
  std::ostringstream os;
  os << "<body name=\"" << kHandBody << "\" mocap=\"true\" pos=\"" << num(parked.x()) << " " << num(parked.y())
     << " " << num(parked.z()) << "\">";
  auto geom = [&](const std::string& attrs, const std::string& color) {
    os << "<geom " << attrs << " contype=\"0\" conaffinity=\"0\" rgba=\"" << color << "\"/>";
  };
  // Palm behind the grasp point; fingers curl from its top edge to just past
  // the grasp point; the thumb comes in from the side.
  geom("type=\"box\" size=\"" + p(0.040, 0.012, 0.045) + "\" pos=\"" + p(0, 0, -0.075) + "\"", skin);
  for (double x : {-0.03, -0.01, 0.01, 0.03})
    geom("type=\"capsule\" size=\"" + num(0.0085 * s) + "\" fromto=\"" + p(x, 0, -0.03) + " " +
             p(x * 0.8, 0.016, 0.01 - 0.006 * std::fabs(x) / 0.03) + "\"",
         skin);
  geom("type=\"capsule\" size=\"" + num(0.010 * s) + "\" fromto=\"" + p(0.045, 0.0, -0.085) + " " +
           p(0.032, 0.022, -0.018) + "\"",
       skin);
  geom("type=\"capsule\" size=\"" + num(0.026 * s) + "\" fromto=\"" + p(0, -0.004, -0.125) + " " +
           p(0, -0.02, -0.17) + "\"",
       skin);
  // The sleeve runs on to the shoulder, below and behind the eye: it leaves
  // the picture at its edge instead of ending in mid-air.
  geom("type=\"capsule\" size=\"" + num(0.034 * s) + "\" fromto=\"" + p(0, -0.02, -0.18) + " " +
           p(0, -0.06, -0.80) + "\"",
       sleeve);
  os << "</body>";
  return os.str();
}

Eigen::Isometry3d Grasp::hand_pose(const mjData* d) const {
  Eigen::Isometry3d H = Eigen::Isometry3d::Identity();
  H.linear() = hand_body.toRotationMatrix();
  H.translation() = point_body;
  return body_pose(d, body) * H;
}

Vector3d Grasp::point(const mjData* d) const { return body_pose(d, body) * point_body; }

Grasp plan_grasp(const Object& obj, int part, const mjModel* m, const mjData* d, const Vector3d& eye) {
  Grasp g;
  g.part = part;
  const Part& p = obj.parts[part];
  g.body = mj_name2id(m, mjOBJ_BODY, p.name.c_str());
  if (g.body < 0) return g;
  const Eigen::Isometry3d body_now = body_pose(d, g.body);

  // The part's box and joint in the object frame, at the spec's reference
  // configuration; the body's reference pose takes them into its own frame.
  mjData* ref = mj_makeData(m);
  mj_kinematics(m, ref);
  const Eigen::Isometry3d body_ref = body_pose(ref, g.body);
  mj_deleteData(ref);
  const Vector3d lo(p.bbox_min[0], p.bbox_min[1], p.bbox_min[2]);
  const Vector3d hi(p.bbox_max[0], p.bbox_max[1], p.bbox_max[2]);
  const Vector3d mid = 0.5 * (lo + hi);
  Vector3d axis = Vector3d::UnitZ(), origin = mid;
  JointType type = JointType::Fixed;
  if (p.joint) {
    type = p.joint->type;
    axis = Vector3d(p.joint->axis[0], p.joint->axis[1], p.joint->axis[2]).normalized();
    origin = Vector3d(p.joint->origin[0], p.joint->origin[1], p.joint->origin[2]);
  }
  auto off_axis = [&](const Vector3d& q) { return ((q - origin) - (q - origin).dot(axis) * axis).norm(); };
  double reach = 0;  // how far the part extends from its hinge
  for (int c = 0; c < 8; ++c)
    reach = std::max(reach, off_axis(Vector3d(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z())));
  const bool knob = type == JointType::Continuous || (type == JointType::Revolute && reach < 0.05);

  // Reference (object frame) -> the part's pose now.
  const Eigen::Isometry3d ref_to_now = body_now * body_ref.inverse();
  double best = -1e300;
  Vector3d best_point = mid, best_normal = -Vector3d::UnitY();
  for (int f = 0; f < 6; ++f) {
    Vector3d n = Vector3d::Zero();
    n[f / 2] = f % 2 ? 1 : -1;
    if (n.z() < -0.5 || n.y() > 0.5) continue;  // bottom and back: out of reach
    Vector3d q = mid;
    q[f / 2] = f % 2 ? hi[f / 2] : lo[f / 2];
    const Vector3d q_now = ref_to_now * q;
    const double facing = (ref_to_now.linear() * n).dot((eye - q_now).normalized());
    double score;
    if (knob || type == JointType::Prismatic)
      score = std::fabs(n.dot(axis)) + 0.5 * facing;
    else if (type == JointType::Revolute)
      score = off_axis(q) / std::max(reach, 1e-6) + 0.4 * facing;
    else
      score = facing;
    if (score > best) best = score, best_point = q, best_normal = n;
  }
  // Object frame at reference -> body frame -> the part's surface now.
  const Vector3d point_body = body_ref.inverse() * best_point;
  const Vector3d normal_body = body_ref.linear().transpose() * best_normal;
  Vector3d point_now = body_now * point_body;
  const Vector3d normal_now = body_now.linear() * normal_body;
  const Vector3d from = point_now + 0.1 * normal_now;
  const Vector3d dir = -normal_now;
  int geom = -1;
  const mjtNum dist = mj_ray(m, d, from.data(), dir.data(), nullptr, 1, -1, &geom);
  if (dist >= 0 && dist < 0.2 && geom >= 0 && m->geom_bodyid[geom] == g.body) point_now = from + dist * dir;
  g.point_body = body_now.inverse() * point_now;

  // The arm comes from the wearer's shoulder (below and right of the eye):
  // fingers point from there to the grasp point, bent a little into the
  // surface; the palm's width stays level.
  // A knob is held on its face with the fingers along its axis, so turning
  // it rolls the hand about the forearm instead of swinging the arm round.
  const Vector3d shoulder = eye + Vector3d(0, 0, -0.45);
  Vector3d z = knob ? Vector3d(-normal_now)
                    : Vector3d((0.75 * (point_now - shoulder).normalized() - 0.25 * normal_now).normalized());
  Vector3d x = z.cross(Vector3d::UnitZ());
  if (x.norm() < 1e-3) x = Vector3d::UnitX();
  x.normalize();
  const Vector3d y = z.cross(x);
  Matrix3d R;
  R.col(0) = x, R.col(1) = y, R.col(2) = z;
  g.hand_body = Eigen::Quaterniond(body_now.linear().transpose() * R).normalized();
  return g;
}

}  // namespace efc::synth
