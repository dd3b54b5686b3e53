// Fills the spec's defaults so backends, the harness and `--dump-ir` see one
// explicit value for every parameter. Each rule cites the spec (efc-spec-v1.md).
#include "compiler/core/resolve.h"

#include <algorithm>
#include <cmath>

#include "compiler/frontend/check.h"
#include "compiler/geometry/geometry.h"

namespace efc {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDefaultDensity = 500.0;  // kg/m^3 (spec: PART.mass)

double norm(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 scaled(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 bbox_center(const Part& p) {
  return {(p.bbox_min[0] + p.bbox_max[0]) / 2, (p.bbox_min[1] + p.bbox_max[1]) / 2,
          (p.bbox_min[2] + p.bbox_max[2]) / 2};
}

void load_meshes(Object& obj, Geometry& g, Diagnostics& diags) {
  if (g.kind == GeomKind::Compound) {
    for (Geometry& c : g.children) load_meshes(obj, c, diags);
    return;
  }
  if (g.kind != GeomKind::Mesh || g.mesh) return;
  MeshData mesh;
  std::string error;
  if (!load_mesh(g.mesh_resolved, g.scale, &mesh, &error)) {
    report(diags, obj, "E0111", g.loc.pointer + "/mesh",
           "cannot load mesh '" + g.mesh_path + "': " + error,
           "the file must be a readable OBJ, STL or PLY triangle mesh");
    return;
  }
  if (!mesh.closed)
    report_warning(diags, obj, "W0103", g.loc.pointer + "/mesh",
                   "mesh '" + g.mesh_path + "' is not closed; its convex hull gives the inertia",
                   "close the mesh (every edge shared by two triangles) for exact inertia");
  g.mesh = std::move(mesh);
}

bool has_unloaded_mesh(const Geometry& g) {
  if (g.kind == GeomKind::Compound)
    return std::any_of(g.children.begin(), g.children.end(), has_unloaded_mesh);
  return g.kind == GeomKind::Mesh && !g.mesh;
}

void resolve_part(Object& obj, Part& p, Diagnostics& diags) {
  load_meshes(obj, p.geometry, diags);
  if (has_unloaded_mesh(p.geometry)) return;
  bounding_box(p.geometry, &p.bbox_min, &p.bbox_max);
  const MassProperties unit = unit_density_mass_properties(p.geometry);
  if (!(unit.volume > 0)) {  // a flat mesh with no hull: no inertia to give a simulator
    report(diags, obj, "E0120", p.geometry.loc.pointer,
           "geometry of part '" + p.name + "' encloses no volume",
           "a part needs a solid shape (a flat mesh has no inertia)");
    return;
  }
  const double mass = p.mass ? *p.mass : unit.volume * kDefaultDensity;
  p.mass_props = with_mass(unit, mass);
  p.mass_props.volume = unit.volume;
}

void resolve_joint(Object& obj, Part& p, Diagnostics& diags) {
  if (!p.joint) return;
  Joint& j = *p.joint;
  if (!j.movable()) return;
  // Spec: movable joints need a direction; +z (the object's up) when omitted.
  const double n = norm(j.axis);
  if (n > 0) j.axis = scaled(j.axis, 1.0 / n);
  double initial = j.initial.value_or(0.0);
  if (j.has_range) {
    const double clamped = std::clamp(initial, j.lo, j.hi);
    if (j.initial && clamped != initial)
      report_warning(diags, obj, "W0210", j.loc.pointer + "/initial",
                     "initial position " + std::to_string(initial) + " of joint '" + p.name +
                         "' is outside its range; clamped to " + std::to_string(clamped));
    initial = clamped;
  }
  j.initial = initial;
}



void receptor_defaults(const Object& obj, Function& f) {
  double r_lo, r_hi;
  receptor_range(obj, f, &r_lo, &r_hi);
  Mapping& m = f.mapping;
  const double span = r_hi - r_lo;
  auto fill = [&m](std::optional<double>& field, double value, const char* name) {
    if (!field) {
      field = value;
      m.defaulted.push_back(name);
    }
  };
  const double e_lo = f.effect.lo, e_hi = f.effect.hi;
  switch (m.type) {
    case MappingType::Binary:
      fill(m.threshold, (r_lo + r_hi) / 2, "threshold");
      if (!m.latching) {
        m.latching = false;
        m.defaulted.push_back("latching");
      }
      break;
    case MappingType::Step:
      fill(m.threshold, r_lo + 0.7 * span, "threshold");  // the paper's rule
      fill(m.hysteresis, 0.02 * span, "hysteresis");
      break;
    case MappingType::Linear:
      fill(m.gain, (e_hi - e_lo) / span, "gain");  // the paper's rule
      fill(m.offset, e_lo, "offset");
      break;
    case MappingType::Cumulative:
      fill(m.threshold, (r_lo + r_hi) / 2, "threshold");
      fill(m.initial, e_lo, "initial");
      break;
  }
}

// Spec: the effector's OBB, its two lowest corners farthest from the
// receptor's centre, their mean; direction straight down (EgoFun3D's rule).
Vec3 egofun3d_emitter(const Part& effector, const Part& receptor) {
  OrientedBox box = oriented_bounding_box(effector.geometry);
  std::vector<Vec3> corners = box.corners();
  std::sort(corners.begin(), corners.end(),
            [](const Vec3& a, const Vec3& b) { return a[2] < b[2]; });
  corners.resize(4);  // the lowest face
  const Vec3 rc = bbox_center(receptor);
  std::sort(corners.begin(), corners.end(), [&rc](const Vec3& a, const Vec3& b) {
    return norm(sub(a, rc)) > norm(sub(b, rc));
  });
  return {(corners[0][0] + corners[1][0]) / 2, (corners[0][1] + corners[1][1]) / 2,
          (corners[0][2] + corners[1][2]) / 2};
}

// Airflow outlet default (the spec is silent): the centre of the effector
// OBB's end face along its longest axis, on the side away from the receptor;
// blowing outwards along that axis (a hair dryer's barrel, a fan's nose).
void default_outlet(const Part& effector, const Part& receptor, Vec3* pos, Vec3* dir) {
  OrientedBox box = oriented_bounding_box(effector.geometry);
  int longest = 0;
  for (int k = 1; k < 3; ++k)
    if (box.half[k] > box.half[longest]) longest = k;
  Vec3 axis{box.axes[0][longest], box.axes[1][longest], box.axes[2][longest]};
  const Vec3 away = sub(box.center, bbox_center(receptor));
  if (dot(axis, away) < 0) axis = scaled(axis, -1);
  *dir = axis;
  *pos = {box.center[0] + axis[0] * box.half[longest], box.center[1] + axis[1] * box.half[longest],
          box.center[2] + axis[2] * box.half[longest]};
}

void effect_defaults(Object& obj, Function& f, Diagnostics& diags) {
  Effect& e = f.effect;
  const Part& effector = obj.parts[f.effector_index];
  const Part& receptor = obj.parts[f.receptor_index];
  auto mark = [&e](const char* name) { e.defaulted.push_back(name); };
  if (!e.has_range) {
    e.has_range = true;
    mark("range");
    switch (e.type) {
      case EffectType::Geometry: {
        const Joint& j = *effector.joint;
        if (!j.has_range) {  // continuous effector: no range to borrow
          e.has_range = false;
          report(diags, obj, "E0330", e.loc.pointer,
                 "geometry effect of function '" + f.name + "' needs a 'range': effector '" +
                     effector.name + "' has a continuous joint with no range",
                 "add \"range\": [off, on] in radians");
          return;
        }
        e.lo = j.lo;
        e.hi = j.hi;
        break;
      }
      case EffectType::Illumination: e.lo = 0; e.hi = 800; break;
      case EffectType::Temperature: e.lo = 20; e.hi = 200; break;
      case EffectType::Fluid: e.lo = 0; e.hi = 6; break;
      case EffectType::Airflow: e.lo = 0; e.hi = 10; break;
    }
  }
  switch (e.type) {
    case EffectType::Geometry:
      // Drive stiffness and damping, when not given, are the backend's: they
      // depend on the whole subtree the drive carries and on the timestep
      // (backends/common/lowering.cc has the rule every target shares).
      break;
    case EffectType::Illumination:
      if (!e.color) { e.color = Vec3{1, 1, 1}; mark("color"); }
      if (!e.position) { e.position = bbox_center(effector); mark("position"); }
      break;
    case EffectType::Temperature:
      if (!e.time_constant) { e.time_constant = 30; mark("time_constant"); }
      if (!e.position) { e.position = bbox_center(effector); mark("position"); }
      break;
    case EffectType::Fluid:
      if (!e.position) {
        e.position = egofun3d_emitter(effector, receptor);
        mark("emitter.position");
      }
      if (!e.direction) { e.direction = Vec3{0, 0, -1}; mark("emitter.direction"); }
      if (!e.speed) { e.speed = 1.0; mark("speed"); }
      if (!e.droplet_radius) { e.droplet_radius = 0.004; mark("droplet_radius"); }
      break;
    case EffectType::Airflow: {
      if (!e.position || !e.direction) {  // the OBB is the costly part of resolve
        Vec3 pos, dir;
        default_outlet(effector, receptor, &pos, &dir);
        if (!e.position) { e.position = pos; mark("outlet.position"); }
        if (!e.direction) { e.direction = dir; mark("outlet.direction"); }
      }
      if (!e.cone_angle) { e.cone_angle = 0.35; mark("cone_angle"); }
      if (!e.reach) { e.reach = 0.6; mark("reach"); }
      break;
    }
  }
  if (e.direction) {  // check_structure rejected zero directions (E0322)
    const double n = norm(*e.direction);
    if (n > 0) e.direction = scaled(*e.direction, 1.0 / n);
  }
}

}  // namespace

void receptor_range(const Object& obj, const Function& f, double* lo, double* hi) {
  const Joint& j = *obj.parts[f.receptor_index].joint;
  if (j.has_range) {
    *lo = j.lo;
    *hi = j.hi;
  } else {  // continuous: playback sweeps [0, 2 pi]
    *lo = 0;
    *hi = 2 * kPi;
  }
}

void resolve(Object& obj, Diagnostics& diags) {
  for (Part& p : obj.parts) {
    resolve_part(obj, p, diags);
    resolve_joint(obj, p, diags);
  }
  if (diags.has_errors()) return;  // mass properties are needed below
  for (Function& f : obj.functions) {
    effect_defaults(obj, f, diags);
    if (f.effect.has_range) receptor_defaults(obj, f);
  }
}

}  // namespace efc
