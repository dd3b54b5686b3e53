// The MuJoCo binding of the efc runtime (see efc_mujoco.h for the contract).
//
// Template semantics (mapping, lag, droplet counts) live only in
// efc_rt::function_step; this file only reads receptors from the simulation
// and writes the runtime's output back into it.
#include "efc_mujoco.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace efc_mj {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Colour of a fully glowing part (red-hot).
constexpr float kHotRgb[3] = {1.0f, 0.22f, 0.04f};

std::string prefixed(const char* fn, const char* suffix) {
  return std::string("efc_") + fn + suffix;
}

// Rotates a body-frame vector into the world frame (xmat is row-major).
void rotate(const mjtNum* xmat, const double* v, double* out) {
  for (int r = 0; r < 3; ++r)
    out[r] = xmat[3 * r] * v[0] + xmat[3 * r + 1] * v[1] + xmat[3 * r + 2] * v[2];
}

void normalize(double* v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n > 0)
    for (int k = 0; k < 3; ++k) v[k] /= n;
}

// Area of a geom's silhouette seen along the unit world axis `a` (m^2):
// exact for spheres, boxes, cylinders and capsules, the bounding sphere's
// disc halved for anything else (meshes, ellipsoids), a fair average.
double cross_section(const mjModel* m, const mjData* d, int g, const double* a) {
  const mjtNum* R = d->geom_xmat + 9 * g;
  // The axis in the geom frame: R^T a.
  double l[3];
  for (int c = 0; c < 3; ++c) l[c] = R[c] * a[0] + R[3 + c] * a[1] + R[6 + c] * a[2];
  const mjtNum* s = m->geom_size + 3 * g;
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      return kPi * s[0] * s[0];
    case mjGEOM_BOX:  // half sizes: projected area = 4 (|lx| sy sz + ...)
      return 4 * (std::fabs(l[0]) * s[1] * s[2] + std::fabs(l[1]) * s[0] * s[2] +
                  std::fabs(l[2]) * s[0] * s[1]);
    case mjGEOM_CYLINDER:
    case mjGEOM_CAPSULE: {
      const double side = std::sqrt(std::max(0.0, 1 - l[2] * l[2]));
      const double caps = m->geom_type[g] == mjGEOM_CAPSULE ? kPi * s[0] * s[0] : 0;
      return kPi * s[0] * s[0] * std::fabs(l[2]) + 4 * s[0] * s[1] * side + caps * (1 - std::fabs(l[2]));
    }
    case mjGEOM_PLANE:
    case mjGEOM_HFIELD:
      return 0;
    default:
      return 0.5 * kPi * m->geom_rbound[g] * m->geom_rbound[g];
  }
}

}  // namespace

Controller::Controller(const mjModel* m, const FunctionBinding* table, int count)
    : rows_(table, table + (count > 0 ? count : 0)) {
  for (const FunctionBinding& b : rows_) {
    Hot h;
    h.params = b.params;
    for (int k = 0; k < 3; ++k) h.direction[k] = b.direction[k], h.color[k] = b.color[k];
    h.speed = b.speed;
    h.droplet_count = b.droplet_count;
    h.cone_angle = b.cone_angle;
    h.reach = b.reach;
    h.glow_max = b.glow_max;
    hot_.push_back(h);
  }
  states_.resize(rows_.size());
  resolved_.resize(rows_.size());
  readouts_.resize(rows_.size());
  auto find = [&](mjtObj type, const std::string& name) {
    const int id = mj_name2id(m, type, name.c_str());
    if (id < 0 && error_.empty()) error_ = "efc: the model has no element named '" + name + "'";
    return id;
  };
  for (size_t i = 0; i < rows_.size(); ++i) {
    const FunctionBinding& b = rows_[i];
    Resolved& r = resolved_[i];
    const int rj = find(mjOBJ_JOINT, b.receptor_joint);
    if (rj >= 0) r.receptor_qpos = m->jnt_qposadr[rj];
    r.body = find(mjOBJ_BODY, b.effector_body);
    switch (b.params.effect.kind) {
      case efc_rt::kGeometry: {
        const int ej = find(mjOBJ_JOINT, b.effector_joint);
        if (ej >= 0) r.effector_qpos = m->jnt_qposadr[ej];
        r.actuator = find(mjOBJ_ACTUATOR, prefixed(b.name, "_drive"));
        break;
      }
      case efc_rt::kIllumination:
        r.light = find(mjOBJ_LIGHT, prefixed(b.name, "_light"));
        break;
      case efc_rt::kTemperature:
        if (r.body >= 0)
          for (int g = 0; g < m->ngeom; ++g)
            if (m->geom_bodyid[g] == r.body) {
              r.glow_geoms.push_back(g);
              // The model's colour before any glow: the base we blend from.
              r.base_rgba.insert(r.base_rgba.end(), m->geom_rgba + 4 * g, m->geom_rgba + 4 * g + 4);
            }
        break;
      case efc_rt::kFluid:
        r.site = find(mjOBJ_SITE, prefixed(b.name, "_point"));
        for (int k = 0; k < b.droplet_count; ++k) {
          Droplet drop;
          drop.body = find(mjOBJ_BODY, prefixed(b.name, ("_drop" + std::to_string(k)).c_str()));
          if (drop.body < 0) break;
          const int j = m->body_jntadr[drop.body];
          if (j < 0 || m->jnt_type[j] != mjJNT_FREE) {
            if (error_.empty())
              error_ = "efc: droplet body '" + std::string(mj_id2name(m, mjOBJ_BODY, drop.body)) +
                       "' has no free joint";
            break;
          }
          drop.qpos = m->jnt_qposadr[j];
          drop.qvel = m->jnt_dofadr[j];
          r.droplets.push_back(drop);
        }
        break;
      case efc_rt::kAirflow:
        r.site = find(mjOBJ_SITE, prefixed(b.name, "_point"));
        break;
      default:
        break;
    }
  }
  // Bodies the air can push: every body on a free joint (droplets, props).
  // The object's own parts are never free (the root is welded to the world).
  for (int body = 1; body < m->nbody; ++body) {
    const int j = m->body_jntadr[body];
    if (j >= 0 && m->jnt_type[j] == mjJNT_FREE) free_bodies_.push_back(body);
  }
}

void Controller::park(const mjModel* m, mjData* d, Droplet& drop, int index) {
  // The parking spot is the body's position in the model (the backend puts
  // every droplet on a spaced grid at z = +50 m, far from anything).
  (void)index;
  drop.alive = false;
  mjtNum* q = d->qpos + drop.qpos;
  for (int k = 0; k < 3; ++k) q[k] = m->body_pos[3 * drop.body + k];
  q[3] = 1;
  q[4] = q[5] = q[6] = 0;
  for (int k = 0; k < 6; ++k) d->qvel[drop.qvel + k] = 0;
}

void Controller::reset(const mjModel* m, mjData* d) {
  if (!ok()) return;
  clear_air_forces(d);
  // The object's lowest point: droplets that fall kDropletFall below it are
  // recycled. Only geoms of bodies that are not free (the object's parts).
  floor_z_ = 0;
  bool any = false;
  for (int g = 0; g < m->ngeom; ++g) {
    const int body = m->geom_bodyid[g];
    if (body == 0 || m->geom_type[g] == mjGEOM_PLANE) continue;
    if (std::find(free_bodies_.begin(), free_bodies_.end(), body) != free_bodies_.end()) continue;
    const double z = d->geom_xpos[3 * g + 2] - m->geom_rbound[g];
    if (!any || z < floor_z_) floor_z_ = z;
    any = true;
  }
  for (size_t i = 0; i < rows_.size(); ++i) {
    Resolved& r = resolved_[i];
    const double s_R = d->qpos[r.receptor_qpos];
    efc_rt::function_init(hot_[i].params, s_R, &states_[i]);
    for (size_t k = 0; k < r.droplets.size(); ++k) park(m, d, r.droplets[k], static_cast<int>(k));
    r.emit_times.clear();
    r.next_droplet = 0;
    readouts_[i].s_R = s_R;
    readouts_[i].s_E = states_[i].mapping.s_E;
    apply(m, d, static_cast<int>(i), 0);
  }
}

void Controller::step(const mjModel* m, mjData* d) {
  if (!ok()) return;
  clear_air_forces(d);
  const double dt = m->opt.timestep;
  for (size_t i = 0; i < rows_.size(); ++i) {
    const double s_R = d->qpos[resolved_[i].receptor_qpos];
    const int emit = efc_rt::function_step(hot_[i].params, s_R, dt, &states_[i]);
    readouts_[i].s_R = s_R;
    readouts_[i].s_E = states_[i].mapping.s_E;
    apply(m, d, static_cast<int>(i), emit);
  }
}

void Controller::clear_air_forces(mjData* d) {
  // Only the forces this controller set: anything else in xfrc_applied
  // belongs to the user.
  for (int body : pushed_bodies_)
    for (int k = 0; k < 3; ++k) d->xfrc_applied[6 * body + k] = 0;
  pushed_bodies_.clear();
}

void Controller::apply(const mjModel* m, mjData* d, int i, int emit) {
  const Hot& b = hot_[i];
  Resolved& r = resolved_[i];
  const efc_rt::EffectParams& ep = b.params.effect;
  const double out = states_[i].effect.output;
  FunctionReadout& ro = readouts_[i];
  // MuJoCo 2.2 keeps light colours and geom colours only in mjModel (there is
  // no per-mjData copy), the renderer reads them from there, and mjcb_control
  // receives a const mjModel*. These two fields are the effect's "actuator",
  // owned by this binding, so writing them through const_cast is the only
  // way to realise light and glow; nothing else in the model is touched.
  mjModel* mm = const_cast<mjModel*>(m);
  switch (ep.kind) {
    case efc_rt::kGeometry:
      d->ctrl[r.actuator] = out;
      ro.measured = d->qpos[r.effector_qpos];
      break;
    case efc_rt::kIllumination: {
      // No cap: MuJoCo accepts diffuse > 1 (OpenGL saturates when shading),
      // so the model keeps the exact output and the read-back is faithful.
      float* diffuse = mm->light_diffuse + 3 * r.light;
      int brightest = 0;
      for (int c = 0; c < 3; ++c) {
        diffuse[c] = static_cast<float>(b.color[c] * out / kLumensPerDiffuse);
        if (b.color[c] > b.color[brightest]) brightest = c;
      }
      // Lumens read back from the model: the model is the source of truth.
      ro.measured = b.color[brightest] > 0
                        ? diffuse[brightest] / b.color[brightest] * kLumensPerDiffuse
                        : 0.0;
      break;
    }
    case efc_rt::kTemperature: {
      const double full = b.glow_max > ep.e_lo ? b.glow_max : ep.e_lo + 1;
      double f = (out - ep.e_lo) / (full - ep.e_lo);
      f = f < 0 ? 0 : (f > 1 ? 1 : f);
      for (size_t k = 0; k < r.glow_geoms.size(); ++k) {
        float* rgba = mm->geom_rgba + 4 * r.glow_geoms[k];
        const float* base = r.base_rgba.data() + 4 * k;
        for (int c = 0; c < 3; ++c)
          rgba[c] = static_cast<float>(base[c] * (1 - f) + kHotRgb[c] * f);
        rgba[3] = base[3];
      }
      ro.measured = out;
      break;
    }
    case efc_rt::kFluid:
      fluid(m, d, i, emit);
      break;
    case efc_rt::kAirflow:
      airflow(m, d, i);
      break;
    default:
      break;
  }
}

void Controller::fluid(const mjModel* m, mjData* d, int i, int emit) {
  const Hot& b = hot_[i];
  Resolved& r = resolved_[i];
  const double now = d->time;
  // Recycle droplets that lived long enough or fell well below the object;
  // keep the parked ones pinned (gravity moved them during the last step).
  for (size_t k = 0; k < r.droplets.size(); ++k) {
    Droplet& drop = r.droplets[k];
    if (drop.alive && (now - drop.born > kDropletLifetime ||
                       d->qpos[drop.qpos + 2] < floor_z_ - kDropletFall))
      drop.alive = false;
    if (!drop.alive) park(m, d, drop, static_cast<int>(k));
  }
  if (emit > 0 && !r.droplets.empty() && r.site >= 0) {
    const double* p = d->site_xpos + 3 * r.site;
    double dir[3];
    rotate(d->xmat + 9 * r.body, b.direction, dir);
    normalize(dir);
    const double dt = m->opt.timestep;
    for (int e = 0; e < emit; ++e) {
      // Round robin: the next droplet is the one spawned longest ago, so an
      // exhausted pool recycles its oldest droplet.
      Droplet& drop = r.droplets[r.next_droplet];
      r.next_droplet = (r.next_droplet + 1) % r.droplets.size();
      // Spread this step's droplets along the stream as if emitted evenly
      // during the step, so a fast flow is a stream, not a clump.
      const double lead = b.speed * dt * (static_cast<double>(e) / emit);
      mjtNum* q = d->qpos + drop.qpos;
      for (int k = 0; k < 3; ++k) q[k] = p[k] + dir[k] * lead;
      q[3] = 1;
      q[4] = q[5] = q[6] = 0;
      for (int k = 0; k < 3; ++k) {
        d->qvel[drop.qvel + k] = b.speed * dir[k];
        d->qvel[drop.qvel + 3 + k] = 0;
      }
      drop.alive = true;
      drop.born = now;
    }
  }
  for (int e = 0; e < emit; ++e) r.emit_times.push_back(now);
  // Flow measured from droplets actually spawned in the last kFlowWindow s.
  // The window covers exactly kFlowWindow / timestep steps: half a step of
  // slack keeps d->time's rounding from counting one step too many.
  const double edge = now - kFlowWindow + 0.5 * m->opt.timestep;
  auto stale = std::find_if(r.emit_times.begin(), r.emit_times.end(),
                            [&](double t) { return t > edge; });
  r.emit_times.erase(r.emit_times.begin(), stale);
  const double spawned = r.droplets.empty() ? 0.0 : static_cast<double>(r.emit_times.size());
  readouts_[i].measured = spawned * b.params.effect.droplet_volume_l / kFlowWindow * 60.0;
}

void Controller::airflow(const mjModel* m, mjData* d, int i) {
  const Hot& b = hot_[i];
  const Resolved& r = resolved_[i];
  const double out = states_[i].effect.output;
  readouts_[i].measured = efc_rt::air_speed_at(out, 0, 0, b.cone_angle, b.reach);
  if (r.site < 0 || out == 0) return;
  const double* o = d->site_xpos + 3 * r.site;
  double axis[3];
  rotate(d->xmat + 9 * r.body, b.direction, axis);
  normalize(axis);
  for (int body : free_bodies_) {
    const double* c = d->xipos + 3 * body;
    const double v[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    const double along = v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2];
    const double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const double off = std::sqrt(std::max(0.0, vv - along * along));
    const double angle = std::atan2(off, along);
    const double speed = efc_rt::air_speed_at(out, along, angle, b.cone_angle, b.reach);
    if (speed == 0) continue;
    double area = 0;
    for (int g = m->body_geomadr[body]; g >= 0 && g < m->body_geomadr[body] + m->body_geomnum[body]; ++g)
      area += cross_section(m, d, g, axis);
    const double f = efc_rt::air_drag(speed, area);
    for (int k = 0; k < 3; ++k) d->xfrc_applied[6 * body + k] += f * axis[k];
    pushed_bodies_.push_back(body);
  }
}

}  // namespace efc_mj
