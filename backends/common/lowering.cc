#include "backends/common/lowering.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "backends/common/text.h"

namespace efc {
namespace lowering {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

struct Composite {
  double mass = 0;
  Vec3 com{0, 0, 0};
  Mat3 inertia{};  // about com
};

void collect(const Layout& L, int part, std::vector<int>* out) {
  out->push_back(part);
  for (int c : L.children[part]) collect(L, c, out);
}

// Mass properties of a part and everything it carries.
Composite subtree(const Object& obj, const Layout& L, int part) {
  std::vector<int> parts;
  collect(L, part, &parts);
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

int receptor_part(const Object& obj, const Function& f) {
  return f.receptor_index >= 0 ? f.receptor_index : obj.find_part(f.receptor);
}

int effector_part(const Object& obj, const Function& f) {
  return f.effector_index >= 0 ? f.effector_index : obj.find_part(f.effector);
}

Layout make_layout(const Object& obj) {
  Layout L;
  const size_t n = obj.parts.size();
  L.root = obj.root_index();
  L.frame.assign(n, Vec3{0, 0, 0});
  L.children.assign(n, {});
  for (size_t i = 0; i < n; ++i) {
    const Part& p = obj.parts[i];
    if (!p.joint) continue;
    const int parent = p.joint->parent_index >= 0 ? p.joint->parent_index : obj.find_part(p.joint->parent);
    if (parent >= 0) L.children[parent].push_back(static_cast<int>(i));
  }
  for (size_t i = 0; i < n; ++i) {
    const Part& p = obj.parts[i];
    const bool hinge = p.joint && (p.joint->type == JointType::Revolute ||
                                   p.joint->type == JointType::Continuous);
    L.frame[i] = hinge ? p.joint->origin : p.mass_props.com;
  }
  return L;
}

std::vector<int> evaluation_order(const Object& obj) {
  const size_t n = obj.functions.size();
  std::vector<int> order, indegree(n, 0);
  std::vector<std::vector<int>> after(n);
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b)
      if (a != b && obj.functions[b].receptor == obj.functions[a].effector) {
        after[a].push_back(static_cast<int>(b));
        indegree[b]++;
      }
  std::vector<bool> done(n, false);
  while (order.size() < n) {
    int next = -1;
    for (size_t i = 0; i < n && next < 0; ++i)
      if (!done[i] && indegree[i] == 0) next = static_cast<int>(i);
    if (next < 0)  // a cycle (check() rejects these): keep spec order for the rest
      for (size_t i = 0; i < n && next < 0; ++i)
        if (!done[i]) next = static_cast<int>(i);
    done[next] = true;
    order.push_back(next);
    for (int b : after[next]) indegree[b]--;
  }
  return order;
}

std::vector<int> profile_driven_receptors(const Object& obj) {
  std::set<int> driven_by_function;
  for (const Function& f : obj.functions)
    if (f.effect.type == EffectType::Geometry) driven_by_function.insert(effector_part(obj, f));
  std::vector<int> out;
  std::set<int> seen;
  for (const Function& f : obj.functions) {
    const int r = receptor_part(obj, f);
    if (driven_by_function.count(r) || !seen.insert(r).second) continue;
    out.push_back(r);
  }
  return out;
}

Vec3 effect_point(const Object& obj, const Function& f) {
  if (f.effect.position) return *f.effect.position;
  const Part& p = obj.parts[effector_part(obj, f)];
  return {(p.bbox_min[0] + p.bbox_max[0]) / 2, (p.bbox_min[1] + p.bbox_max[1]) / 2,
          (p.bbox_min[2] + p.bbox_max[2]) / 2};
}

Vec3 effect_direction(const Effect& e) {
  const Vec3 fallback = e.type == EffectType::Airflow ? Vec3{1, 0, 0} : Vec3{0, 0, -1};
  const Vec3 d = e.direction.value_or(fallback);
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(n > 0)) return fallback;
  return {d[0] / n, d[1] / n, d[2] / n};
}

const char* effect_unit(const Object& obj, const Function& f) {
  switch (f.effect.type) {
    case EffectType::Geometry:
      return obj.parts[effector_part(obj, f)].joint->type == JointType::Prismatic ? "m" : "rad";
    case EffectType::Illumination: return "lm";
    case EffectType::Temperature: return "C";
    case EffectType::Fluid: return "L/min";
    case EffectType::Airflow: return "m/s";
  }
  return "";
}

std::vector<FunctionRow> function_rows(const Object& obj) {
  std::vector<FunctionRow> rows;
  const std::vector<int> pools = droplet_pool_sizes(obj);
  for (int fi : evaluation_order(obj)) {
    const Function& f = obj.functions[fi];
    const Mapping& mp = f.mapping;
    const Effect& e = f.effect;
    FunctionRow b;
    b.function = fi;
    b.receptor = receptor_part(obj, f);
    b.effector = effector_part(obj, f);

    // Mapping: resolve() fills every optional; the fallbacks repeat the
    // spec's defaults so a hand-built IR still yields a sane table.
    efc_rt::MappingParams& m = b.params.mapping;
    double r_lo, r_hi;
    receptor_range(obj, f, &r_lo, &r_hi);
    m.kind = static_cast<int>(mp.type);
    m.r_lo = r_lo;
    m.r_hi = r_hi;
    m.e_lo = e.lo;
    m.e_hi = e.hi;
    const double mid = (r_lo + r_hi) / 2;
    m.threshold = mp.threshold.value_or(mp.type == MappingType::Step ? r_lo + 0.7 * (r_hi - r_lo) : mid);
    m.hysteresis = mp.hysteresis.value_or(0.02 * (r_hi - r_lo));
    m.latching = mp.latching.value_or(false) ? 1 : 0;
    m.gain = mp.gain.value_or((e.hi - e.lo) / (r_hi - r_lo));
    m.offset = mp.offset.value_or(e.lo);
    m.delta = mp.delta.value_or(0);
    m.initial = mp.initial.value_or(e.lo);

    efc_rt::EffectParams& ep = b.params.effect;
    ep.kind = static_cast<int>(e.type);
    ep.e_lo = e.lo;
    ep.e_hi = e.hi;
    ep.time_constant = e.type == EffectType::Temperature ? e.time_constant.value_or(kDefaultTimeConstant) : 0;
    ep.droplet_volume_l =
        e.type == EffectType::Fluid ? droplet_volume_litres(e.droplet_radius.value_or(kDefaultDropletRadius)) : 0;

    const bool directed = e.type == EffectType::Fluid || e.type == EffectType::Airflow;
    if (directed) b.direction = effect_direction(e);
    if (e.type == EffectType::Illumination) b.color = e.color.value_or(Vec3{1, 1, 1});
    if (e.type == EffectType::Fluid) {
      b.speed = e.speed.value_or(kDefaultFluidSpeed);
      b.droplet_radius = e.droplet_radius.value_or(kDefaultDropletRadius);
      b.droplet_count = pools[fi];
    }
    if (e.type == EffectType::Airflow) {
      b.cone_angle = e.cone_angle.value_or(kDefaultConeAngle);
      b.reach = e.reach.value_or(kDefaultReach);
    }
    // A part glows red-hot only at kGlowFullC: an oven at 250 C glows
    // partly, a kettle at 100 C barely.
    if (e.type == EffectType::Temperature) b.glow_max = std::max(e.hi, kGlowFullC);
    rows.push_back(b);
  }
  return rows;
}

ReplayModel replay_model(const Object& obj) {
  ReplayModel model;
  const std::vector<int> profile = profile_driven_receptors(obj);
  std::vector<int> joint_of(obj.parts.size(), -1);
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    const Part& p = obj.parts[i];
    if (!p.joint || !p.joint->movable()) continue;
    const Joint& j = *p.joint;
    const bool continuous = j.type == JointType::Continuous;
    joint_of[i] = static_cast<int>(model.joints.size());
    model.joints.push_back({p.name, continuous ? 0.0 : j.lo, continuous ? 2 * kPi : j.hi,
                            j.initial.value_or(0.0),
                            std::find(profile.begin(), profile.end(), static_cast<int>(i)) != profile.end()});
  }
  for (const FunctionRow& r : function_rows(obj)) {
    const bool geometry = r.params.effect.kind == efc_rt::kGeometry;
    model.functions.push_back({obj.functions[r.function].name, r.params, joint_of[r.receptor],
                               geometry ? joint_of[r.effector] : -1});
  }
  return model;
}

DriveGains drive_gains(const Object& obj, const Layout& L, int part, double q_lo, double q_hi,
                       double tolerance, double hz, double timestep, const double* stiffness,
                       const double* damping) {
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
    const double w = 2 * kPi * hz;
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

DriveGains geometry_drive(const Object& obj, const Layout& L, const Function& f, double timestep) {
  const Effect& e = f.effect;
  const double lo = std::min(e.lo, e.hi), hi = std::max(e.lo, e.hi);
  const double stiffness = e.stiffness.value_or(0), damping = e.damping.value_or(0);
  return drive_gains(obj, L, effector_part(obj, f), lo, hi, kHoldTolerance * (hi - lo),
                     kEffectDriveHz, timestep, e.stiffness ? &stiffness : nullptr,
                     e.damping ? &damping : nullptr);
}

DriveGains receptor_drive(const Object& obj, const Layout& L, int part, double timestep) {
  const Joint& j = *obj.parts[part].joint;
  const bool continuous = j.type == JointType::Continuous;
  const double lo = continuous ? 0 : j.lo, hi = continuous ? 2 * kPi : j.hi;
  return drive_gains(obj, L, part, lo, hi, kHoldTolerance * (hi - lo), kReceptorDriveHz, timestep,
                     nullptr, nullptr);
}

std::string weak_stiffness_warning(const Object& obj, const Layout& L, const Function& f,
                                   double timestep) {
  const Effect& e = f.effect;
  if (e.type != EffectType::Geometry || !e.stiffness) return "";
  const double lo = std::min(e.lo, e.hi), hi = std::max(e.lo, e.hi);
  const DriveGains need = drive_gains(obj, L, effector_part(obj, f), lo, hi,
                                      kWeakStiffness * (hi - lo), 0.0, timestep, nullptr, nullptr);
  if (*e.stiffness >= need.kp) return "";
  return "geometry effect '" + f.name + "': stiffness " + text::number(*e.stiffness) +
         " is below the " + text::number(need.kp) +
         " needed to hold the effector within 2% of its range against its spring, gravity and "
         "friction; emitted as given";
}

double droplet_volume_litres(double radius) { return 4.0 / 3.0 * kPi * radius * radius * radius * 1000.0; }

int droplet_pool_size(const Effect& e) {
  const double radius = e.droplet_radius.value_or(kDefaultDropletRadius);
  efc_rt::EffectParams p{efc_rt::kFluid, e.lo, e.hi, 0, droplet_volume_litres(radius)};
  const double peak = std::max(std::fabs(e.lo), std::fabs(e.hi));
  const double alive = std::ceil(efc_rt::droplet_rate(p, peak) * kDropletLifetime);
  return static_cast<int>(std::clamp(alive, double(kMinDroplets), double(kMaxDroplets)));
}

std::vector<int> droplet_pool_sizes(const Object& obj) {
  std::vector<int> sizes(obj.functions.size(), 0);
  int object_nq = 0, wanted = 0;
  for (const Part& p : obj.parts) object_nq += p.joint && p.joint->movable() ? 1 : 0;
  for (size_t i = 0; i < obj.functions.size(); ++i)
    if (obj.functions[i].effect.type == EffectType::Fluid)
      wanted += sizes[i] = droplet_pool_size(obj.functions[i].effect);
  // The "initial" key must list every qpos (7 per droplet): share what is
  // left after the object's joints among the pools, in proportion.
  const int budget = (kMaxKeyframeQpos - object_nq) / 7;
  if (wanted > budget)
    for (int& n : sizes)
      if (n > 0) n = std::max(1, n * budget / wanted);
  return sizes;
}

}  // namespace lowering
}  // namespace efc
