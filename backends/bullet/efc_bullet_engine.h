#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "efc_runtime/efc_profile.h"
#include "efc_runtime/efc_runtime.h"

#ifndef BT_USE_DOUBLE_PRECISION
#error "build against bullet-float64 (pkg-config --cflags bullet-float64 defines BT_USE_DOUBLE_PRECISION)"
#endif

namespace efcb {

enum JointKind { kFixed = 0, kRevolute = 1, kContinuous = 2, kPrismatic = 3 };
enum ShapeKind { kBox = 0, kCylinder = 1, kSphere = 2, kHull = 3 };

// One link per non-root part, parents first. Link frame: at the part's centre
// of mass, rotated onto its principal axes (frame_quat, object frame).
struct LinkSpec {
  const char* name;
  int parent;  // link index, -1 = base
  int type;    // JointKind
  double mass;
  double inertia[3];             // principal moments
  double rot_parent_to_this[4];  // x y z w, at joint position 0
  double axis[3];                // this link's frame
  double parent_com_to_pivot[3];  // parent frame
  double pivot_to_com[3];         // this frame
  int limited;
  double lo, hi, initial;
  double damping, friction, spring_k, spring_rest;
  double joint_inertia;  // joint-space inertia at q = 0 (the MuJoCo target's rule)
  double kp;             // geometry-effect drive stiffness (0 = no drive)
  double kv_explicit;    // the effect's damping when the spec gives it, else -1
  int kinematic;         // receptor that the profile moves
  double com[3];         // object frame at q = 0 (self-check)
  double frame_quat[4];  // object frame at q = 0 (self-check)
};

struct ShapeSpec {
  int link;  // -1 = base
  int kind;  // ShapeKind
  double pos[3];
  double rot[4];
  double size[3];  // box half extents; cylinder r, r, half length; sphere r
  int first_point, point_count;  // hull points in kPoints
};

struct FunctionSpec {
  const char* name;
  efc_rt::FunctionParams params;
  int receptor_link;
  int effector_link;
  double cone_angle, reach;  // airflow
  int droplets;              // fluid: the MuJoCo target's pool size (0 = none)
};

struct ModelSpec {
  const char* name;
  double base_mass;
  double base_inertia[3];
  double base_com[3];
  double base_quat[4];
  const LinkSpec* links;
  int nlinks;
  const ShapeSpec* shapes;
  int nshapes;
  const double* points;
  const FunctionSpec* functions;  // evaluation order (topological over chains)
  int nfunctions;
};

constexpr double kPi = 3.14159265358979323846;
constexpr double kGravity = -9.81;
constexpr double kFlowWindow = 0.5;     // s, as efc_mj::kFlowWindow
constexpr double kHugeImpulse = 1e12;   // a kinematic receptor's motor never saturates

btQuaternion quat(const double* q) { return btQuaternion(q[0], q[1], q[2], q[3]); }
btVector3 vec(const double* v) { return btVector3(v[0], v[1], v[2]); }

struct Options {
  std::string profile, csv;
  double duration = -1, dt = 0.002;
  int precision = 9;
  bool self_check = false, quiet = false;
};

int usage(const char* prog, const std::string& why) {
  std::fprintf(stderr, "%s: %s\nusage: %s --profile P --duration S [--dt D] [--csv FILE] "
               "[--precision N] [--quiet]\n       %s --self-check\n", prog, why.c_str(), prog, prog);
  return 2;
}

bool parse_number(const char* s, double* v) {
  char* end = nullptr;
  *v = std::strtod(s, &end);
  return end && *end == 0 && end != s && std::isfinite(*v);
}

class Sim {
 public:
  explicit Sim(const ModelSpec& m, double dt) : m_(m), dt_(dt) {
    cfg_ = new btDefaultCollisionConfiguration();
    dispatcher_ = new btCollisionDispatcher(cfg_);
    broadphase_ = new btDbvtBroadphase();
    solver_ = new btMultiBodyConstraintSolver();
    world_ = new btMultiBodyDynamicsWorld(dispatcher_, broadphase_, solver_, cfg_);
    world_->setGravity(btVector3(0, 0, kGravity));
    mb_ = new btMultiBody(m.nlinks, m.base_mass, vec(m.base_inertia), true, false);
    mb_->setBaseWorldTransform(btTransform(quat(m.base_quat), vec(m.base_com)));
    for (int i = 0; i < m.nlinks; ++i) {
      const LinkSpec& l = m.links[i];
      const btVector3 I = vec(l.inertia);
      const btQuaternion r = quat(l.rot_parent_to_this);
      switch (l.type) {
        case kRevolute:
        case kContinuous:
          mb_->setupRevolute(i, l.mass, I, l.parent, r, vec(l.axis), vec(l.parent_com_to_pivot),
                             vec(l.pivot_to_com), true);
          break;
        case kPrismatic:
          mb_->setupPrismatic(i, l.mass, I, l.parent, r, vec(l.axis), vec(l.parent_com_to_pivot),
                              vec(l.pivot_to_com), true);
          break;
        default:
          mb_->setupFixed(i, l.mass, I, l.parent, r, vec(l.parent_com_to_pivot), vec(l.pivot_to_com));
      }
    }
    mb_->finalizeMultiDof();
    mb_->setLinearDamping(0);
    mb_->setAngularDamping(0);
    mb_->setMaxCoordinateVelocity(1e6);
    mb_->setHasSelfCollision(false);
    mb_->setCanSleep(false);
    world_->addMultiBody(mb_);
    make_colliders();
    // Subtrees (for the gravity load on each joint): parents precede children.
    subtree_.resize(m.nlinks);
    for (int j = 0; j < m.nlinks; ++j)
      for (int a = j; a >= 0; a = m.links[a].parent) subtree_[a].push_back(j);
    target_.assign(m.nlinks, 0);
    motors_.assign(m.nlinks, nullptr);
    armature_.assign(m.nlinks, 0);
    kv_.assign(m.nlinks, 0);
    for (int i = 0; i < m.nlinks; ++i) {
      const LinkSpec& l = m.links[i];
      if (l.type == kFixed) continue;
      // The MuJoCo target's drive: kp from the compiler; rotor inertia
      // (armature) where kp is too stiff for the part at this dt; kv critically damps.
      if (l.kp > 0) {
        const double inertia = std::max(l.joint_inertia, 1e-9);
        const double need = (l.kp + l.spring_k) * dt * dt;
        armature_[i] = need > inertia ? need - inertia : 0;
        kv_[i] = l.kv_explicit >= 0
                     ? l.kv_explicit
                     : std::max(0.0, 2 * std::sqrt((l.kp + l.spring_k) * (inertia + armature_[i])) -
                                         l.damping);
      }
      if (l.kinematic) {
        auto* motor = new btMultiBodyJointMotor(mb_, i, 0, 0, kHugeImpulse);
        motor->setPositionTarget(0, 0);
        motor->setVelocityTarget(0, 1);
        world_->addMultiBodyConstraint(motor);
        motors_[i] = motor;
        continue;
      }
      if (l.limited) {
        auto* lim = new btMultiBodyJointLimitConstraint(mb_, i, l.lo, l.hi);
        world_->addMultiBodyConstraint(lim);
        constraints_.push_back(lim);
      }
      if (l.friction > 0) {
        auto* fr = new btMultiBodyJointMotor(mb_, i, 0, 0, l.friction * dt);
        fr->setPositionTarget(0, 0);
        fr->setVelocityTarget(0, 1);
        world_->addMultiBodyConstraint(fr);
        constraints_.push_back(fr);
      }
    }
    for (auto* c : motors_)
      if (c) constraints_.push_back(c);
  }

  ~Sim() {
    for (auto* c : constraints_) {
      world_->removeMultiBodyConstraint(c);
      delete c;
    }
    for (auto* c : colliders_) {
      world_->removeCollisionObject(c);
      delete c;
    }
    for (auto* s : shapes_) delete s;
    world_->removeMultiBody(mb_);
    delete mb_;
    delete world_;
    delete solver_;
    delete broadphase_;
    delete dispatcher_;
    delete cfg_;
  }

  btMultiBody* body() { return mb_; }
  double q(int link) const { return mb_->getJointPos(link); }

  void set_initial() {
    for (int i = 0; i < m_.nlinks; ++i)
      if (m_.links[i].type != kFixed) {
        mb_->setJointPos(i, m_.links[i].initial);
        mb_->setJointVel(i, 0);
        target_[i] = m_.links[i].initial;
      }
    kinematics();
  }

  // Prescribes a kinematic receptor: at q now, moving at v through the step.
  void prescribe(int link, double q, double v) {
    mb_->setJointPos(link, q);
    mb_->setJointVel(link, v);
    motors_[link]->setVelocityTarget(v, 1);
  }
  void set_target(int link, double q) { target_[link] = q; }

  void kinematics() {
    mb_->forwardKinematics(w2l_, origin_);
    mb_->updateCollisionObjectWorldTransforms(w2l_, origin_);
  }

  // Joint torques: spring, damping and the effect drives. MuJoCo integrates
  // damping implicitly and adds armature; Bullet integrates explicitly, so
  // the torque is scaled by M / (M + armature + dt (kv + b)) around gravity,
  // which gives each joint the MuJoCo target's velocity update.
  void apply_torques() {
    mb_->clearForcesAndTorques();
    for (int i = 0; i < m_.nlinks; ++i) {
      const LinkSpec& l = m_.links[i];
      if (l.type == kFixed || l.kinematic) continue;
      const double q = mb_->getJointPos(i), v = mb_->getJointVel(i);
      double f = -l.spring_k * (q - l.spring_rest) - (kv_[i] + l.damping) * v;
      if (l.kp > 0) f += l.kp * (target_[i] - q);
      const double M = std::max(l.joint_inertia, 1e-9);
      const double s = M / (M + armature_[i] + dt_ * (kv_[i] + l.damping));
      if (s == 1.0) {
        mb_->addJointTorque(i, f);
        continue;
      }
      const double g = gravity_load(i);
      mb_->addJointTorque(i, s * (f + g) - g);
    }
  }

  void step() { world_->stepSimulation(dt_, 0, dt_); }

  // Generalised gravity force on link i's joint (from the last kinematics()).
  double gravity_load(int i) const {
    const LinkSpec& l = m_.links[i];
    const btQuaternion to_world = w2l_[i + 1].inverse();
    const btVector3 axis = quatRotate(to_world, vec(l.axis));
    const btVector3 gvec(0, 0, kGravity);
    double g = 0;
    if (l.type == kPrismatic) {
      for (int j : subtree_[i]) g += axis.dot(m_.links[j].mass * gvec);
      return g;
    }
    const btVector3 pivot = origin_[i + 1] - quatRotate(to_world, vec(l.pivot_to_com));
    for (int j : subtree_[i]) g += axis.dot((origin_[j + 1] - pivot).cross(m_.links[j].mass * gvec));
    return g;
  }

  // World position and rotation of link i's frame (after kinematics()).
  btVector3 com(int i) const { return origin_[i + 1]; }
  btQuaternion rot(int i) const { return w2l_[i + 1].inverse(); }

 private:
  void make_colliders() {
    for (int link = -1; link < m_.nlinks; ++link) {
      auto* compound = new btCompoundShape();
      shapes_.push_back(compound);
      for (int s = 0; s < m_.nshapes; ++s) {
        const ShapeSpec& sp = m_.shapes[s];
        if (sp.link != link) continue;
        btCollisionShape* shape = nullptr;
        switch (sp.kind) {
          case kBox: shape = new btBoxShape(vec(sp.size)); break;
          case kCylinder: shape = new btCylinderShapeZ(vec(sp.size)); break;
          case kSphere: shape = new btSphereShape(sp.size[0]); break;
          default: {
            auto* hull = new btConvexHullShape();
            for (int p = 0; p < sp.point_count; ++p)
              hull->addPoint(vec(m_.points + 3 * (sp.first_point + p)), false);
            hull->recalcLocalAabb();
            shape = hull;
          }
        }
        shape->setMargin(0);
        shapes_.push_back(shape);
        compound->addChildShape(btTransform(quat(sp.rot), vec(sp.pos)), shape);
      }
      auto* col = new btMultiBodyLinkCollider(mb_, link);
      col->setCollisionShape(compound);
      // Object parts: group 2, mask 1 (MuJoCo contype 2 / conaffinity 1): they
      // never hit each other (they overlap at joints); a prop in group 1 hits them.
      world_->addCollisionObject(col, 2, 1);
      colliders_.push_back(col);
      if (link < 0)
        mb_->setBaseCollider(col);
      else
        mb_->getLink(link).m_collider = col;
    }
    kinematics();
  }

  const ModelSpec& m_;
  double dt_;
  btDefaultCollisionConfiguration* cfg_;
  btCollisionDispatcher* dispatcher_;
  btBroadphaseInterface* broadphase_;
  btMultiBodyConstraintSolver* solver_;
  btMultiBodyDynamicsWorld* world_;
  btMultiBody* mb_;
  std::vector<btCollisionShape*> shapes_;
  std::vector<btMultiBodyLinkCollider*> colliders_;
  std::vector<btMultiBodyConstraint*> constraints_;
  std::vector<btMultiBodyJointMotor*> motors_;
  std::vector<std::vector<int>> subtree_;
  std::vector<double> target_, armature_, kv_;
  btAlignedObjectArray<btQuaternion> w2l_;
  btAlignedObjectArray<btVector3> origin_;
};

// Frames at q = 0 match the object frame, and each joint moves its link the
// way the spec says (+q turns about +axis, right-handed; slides along +axis).
int self_check(const ModelSpec& m) {
  Sim sim(m, 0.002);
  int bad = 0;
  auto near = [](const btVector3& a, const btVector3& b) { return (a - b).length() < 1e-9; };
  for (int i = 0; i < m.nlinks; ++i) {
    const LinkSpec& l = m.links[i];
    const btVector3 want = vec(l.com);
    const btQuaternion fr = quat(l.frame_quat);
    if (!near(sim.com(i), want) ||
        !near(quatRotate(sim.rot(i), btVector3(1, 0, 0)), quatRotate(fr, btVector3(1, 0, 0))) ||
        !near(quatRotate(sim.rot(i), btVector3(0, 1, 0)), quatRotate(fr, btVector3(0, 1, 0)))) {
      std::fprintf(stderr, "self-check: link '%s' frame at q = 0 is wrong\n", l.name);
      ++bad;
    }
  }
  for (int i = 0; i < m.nlinks; ++i) {
    const LinkSpec& l = m.links[i];
    if (l.type == kFixed) continue;
    const double dq = 0.1;
    const btQuaternion fr = quat(l.frame_quat);
    const btVector3 axis = quatRotate(fr, vec(l.axis));
    const btVector3 com = vec(l.com);
    btVector3 want;
    if (l.type == kPrismatic) {
      want = com + dq * axis;
    } else {
      const btVector3 pivot = com - quatRotate(fr, vec(l.pivot_to_com));
      want = pivot + quatRotate(btQuaternion(axis, dq), com - pivot);
    }
    sim.body()->setJointPos(i, dq);
    sim.kinematics();
    if (!near(sim.com(i), want)) {
      std::fprintf(stderr, "self-check: joint '%s' moves its link the wrong way\n", l.name);
      ++bad;
    }
    sim.body()->setJointPos(i, 0);
    sim.kinematics();
  }
  std::fprintf(stderr, "self-check: %d links, %s\n", m.nlinks, bad ? "FAILED" : "ok");
  return bad ? 1 : 0;
}

int run(const ModelSpec& m, int argc, char** argv) {
  Options o;
  const char* prog = argv[0];
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char** out) {
      if (i + 1 >= argc) return false;
      *out = argv[++i];
      return true;
    };
    const char* v = nullptr;
    double x;
    if (a == "--self-check") o.self_check = true;
    else if (a == "--quiet") o.quiet = true;
    else if (a == "--profile" && value(&v)) o.profile = v;
    else if (a == "--csv" && value(&v)) o.csv = v;
    else if (a == "--duration" && value(&v) && parse_number(v, &x)) o.duration = x;
    else if (a == "--dt" && value(&v) && parse_number(v, &x)) o.dt = x;
    else if (a == "--precision" && value(&v) && parse_number(v, &x) && x >= 1 && x <= 17)
      o.precision = static_cast<int>(x);
    else return usage(prog, "bad or incomplete option '" + a + "'");
  }
  if (o.self_check) return self_check(m);
  if (o.profile.empty()) return usage(prog, "--profile is required");
  if (!(o.duration > 0) || o.duration > 1e5) return usage(prog, "--duration must be a positive number of seconds");
  if (!(o.dt > 0) || o.dt > 0.1 || o.dt > o.duration)
    return usage(prog, "--dt must be in (0, 0.1] seconds and not exceed --duration");
  if (o.duration / o.dt > 5e7) return usage(prog, "--duration / --dt is more than 50 million steps");
  efc::Profile profile;
  std::string error;
  int line = 0;
  bool io = false;
  if (!efc::parse_profile(o.profile, &profile, &error, &line, &io)) {
    std::fprintf(stderr, "%s: %s%s\n", prog, line > 0 ? ("line " + std::to_string(line) + ": ").c_str() : "",
                 error.c_str());
    return io || line == 0 ? 2 : 1;
  }

  Sim sim(m, o.dt);
  sim.set_initial();
  // Receptors the profile moves (kinematically: the joint is where the profile says).
  struct Drive { int link; double lo, hi, q0; bool clamp; };
  std::vector<Drive> drives;
  for (int i = 0; i < m.nlinks; ++i) {
    const LinkSpec& l = m.links[i];
    if (!l.kinematic) continue;
    const bool cont = l.type == kContinuous;
    // Positions from a csv: profile are followed as given (efc parity hands over
    // the harness's realised positions, which may sit a hair past a soft limit);
    // every other profile is clamped into the joint's range, as a limit would.
    const bool csv = profile.kind == efc::Profile::Kind::Csv;
    drives.push_back({i, cont ? 0 : l.lo, cont ? 2 * kPi : l.hi, l.initial, !cont && !csv});
    if (profile.kind == efc::Profile::Kind::Csv && !profile.csv_parts.count(l.name))
      std::fprintf(stderr, "%s: warning: profile CSV has no column for receptor '%s'; it holds its initial position\n",
                   prog, l.name);
    if (profile.kind == efc::Profile::Kind::Hold && profile.hold_at == efc::Profile::HoldAt::Value &&
        (profile.hold_value < l.lo || profile.hold_value > l.hi) && !cont)
      std::fprintf(stderr, "%s: warning: hold value %g is outside the range of receptor '%s'; its joint limit stops it\n",
                   prog, profile.hold_value, l.name);
  }
  auto target = [&](const Drive& d, double t) {
    double q = efc::profile_target(profile, m.links[d.link].name, d.lo, d.hi, d.q0, t, o.duration);
    return d.clamp ? std::min(std::max(q, d.lo), d.hi) : q;
  };
  for (int f = 0; f < m.nfunctions; ++f) {
    const int kind = m.functions[f].params.effect.kind;
    static const char* names[] = {"geometry", "light", "heat", "fluid", "air"};
    if (kind != efc_rt::kGeometry && !o.quiet)
      std::fprintf(stderr, "bullet: '%s': Bullet does not simulate %s; measured is the runtime's effect state\n",
                   m.functions[f].name, names[kind]);
  }

  std::vector<efc_rt::FunctionState> st(m.nfunctions);
  std::vector<std::deque<double>> emitted(m.nfunctions);
  for (int f = 0; f < m.nfunctions; ++f)
    efc_rt::function_init(m.functions[f].params, sim.q(m.functions[f].receptor_link), &st[f]);

  const long steps = std::lround(o.duration / o.dt);
  const int cols = 1 + 3 * m.nfunctions;
  std::vector<double> rows;
  rows.reserve(static_cast<size_t>(steps + 1) * cols);
  double now = 0;  // accumulated like MuJoCo's d->time (the flow window uses it)
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k <= steps; ++k) {
    const double t = k * o.dt;
    for (const Drive& d : drives) {
      const double q = target(d, t), next = target(d, (k + 1) * o.dt);
      sim.prescribe(d.link, q, (next - q) / o.dt);
    }
    sim.kinematics();
    rows.push_back(t);
    for (int f = 0; f < m.nfunctions; ++f) {
      const FunctionSpec& fs = m.functions[f];
      const double s_R = sim.q(fs.receptor_link);
      const int emit = efc_rt::function_step(fs.params, s_R, o.dt, &st[f]);
      const double out = st[f].effect.output;
      double measured = out;
      switch (fs.params.effect.kind) {
        case efc_rt::kGeometry:
          sim.set_target(fs.effector_link, out);
          measured = sim.q(fs.effector_link);
          break;
        case efc_rt::kFluid: {
          std::deque<double>& e = emitted[f];
          for (int i = 0; i < emit; ++i) e.push_back(now);
          while (!e.empty() && !(e.front() > now - kFlowWindow)) e.pop_front();
          measured = fs.droplets > 0 ? e.size() * fs.params.effect.droplet_volume_l / kFlowWindow * 60.0 : 0.0;
          break;
        }
        case efc_rt::kAirflow:
          measured = efc_rt::air_speed_at(out, 0, 0, fs.cone_angle, fs.reach);
          break;
        default:
          break;
      }
      rows.push_back(s_R);
      rows.push_back(st[f].mapping.s_E);
      rows.push_back(measured);
    }
    if (k == steps) break;
    sim.apply_torques();
    sim.step();
    now += o.dt;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (!o.csv.empty()) {
    const std::string tmp = o.csv + ".tmp";
    FILE* out = std::fopen(tmp.c_str(), "w");
    if (!out) {
      std::fprintf(stderr, "%s: cannot write '%s'\n", prog, o.csv.c_str());
      return 2;
    }
    std::fputs("t", out);
    for (int f = 0; f < m.nfunctions; ++f)
      std::fprintf(out, ",%s.s_R,%s.s_E,%s.measured", m.functions[f].name, m.functions[f].name,
                   m.functions[f].name);
    std::fputs("\n", out);
    for (size_t r = 0; r < rows.size(); r += cols) {
      for (int c = 0; c < cols; ++c) std::fprintf(out, c ? ",%.*g" : "%.*g", o.precision, rows[r + c]);
      std::fputs("\n", out);
    }
    const bool ok = std::fflush(out) == 0 && !std::ferror(out);
    std::fclose(out);
    if (!ok || std::rename(tmp.c_str(), o.csv.c_str()) != 0) {
      std::fprintf(stderr, "%s: cannot write '%s'\n", prog, o.csv.c_str());
      return 2;
    }
  }
  std::fprintf(stderr, "bullet: %ld steps in %.3f s (%.0f steps/s)\n", steps, secs,
               secs > 0 ? steps / secs : 0.0);
  return 0;
}

}  // namespace efcb
