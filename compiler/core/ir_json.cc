// The resolved IR as JSON. Field names follow the spec; values are the ones
// the backends use (every default filled), and "defaulted" lists which came
// from a rule rather than from the file.
#include "compiler/core/ir_json.h"

namespace efc {
namespace {

using nlohmann::json;

json vec(const Vec3& v) { return json::array({v[0], v[1], v[2]}); }

json mat(const Mat3& m) {
  json rows = json::array();
  for (const auto& r : m) rows.push_back(json::array({r[0], r[1], r[2]}));
  return rows;
}

json loc(const SourceLoc& l) { return {{"pointer", l.pointer}, {"line", l.line}, {"column", l.col}}; }

void add_extensions(json& j, const Extensions& ext) {
  for (const auto& [k, v] : ext) j[k] = v;
}

json geometry(const Geometry& g) {
  json j;
  switch (g.kind) {
    case GeomKind::Mesh:
      j["mesh"] = g.mesh_path;
      j["scale"] = vec(g.scale);
      if (g.mesh) {
        j["vertices"] = g.mesh->vertices.size();
        j["triangles"] = g.mesh->triangles.size();
        j["closed"] = g.mesh->closed;
      }
      break;
    case GeomKind::Box:
      j["box"] = {{"size", vec(g.size)}, {"center", vec(g.center)}, {"rpy", vec(g.rpy)}};
      break;
    case GeomKind::Cylinder:
      j["cylinder"] = {{"radius", g.radius}, {"length", g.length}, {"center", vec(g.center)},
                       {"axis", vec(g.axis)}};
      break;
    case GeomKind::Sphere:
      j["sphere"] = {{"radius", g.radius}, {"center", vec(g.center)}};
      break;
    case GeomKind::Compound: {
      json pieces = json::array();
      for (const Geometry& c : g.children) pieces.push_back(geometry(c));
      j["compound"] = pieces;
      break;
    }
  }
  add_extensions(j, g.extensions);
  return j;
}

json joint(const Joint& jt) {
  json j = {{"type", to_string(jt.type)}, {"parent", jt.parent}, {"source", loc(jt.loc)}};
  if (jt.movable()) {
    j["axis"] = vec(jt.axis);
    j["origin"] = vec(jt.origin);
    if (jt.has_range) j["range"] = json::array({jt.lo, jt.hi});
    if (jt.initial) j["initial"] = *jt.initial;
    j["damping"] = jt.damping;
    j["friction"] = jt.friction;
    if (jt.spring) j["spring"] = {{"stiffness", jt.spring->stiffness}, {"rest", jt.spring->rest}};
  }
  add_extensions(j, jt.extensions);
  return j;
}

json part(const Part& p) {
  const MassProperties& mp = p.mass_props;
  json j = {{"name", p.name},
            {"role", to_string(p.role)},
            {"geometry", geometry(p.geometry)},
            {"mass", mp.mass},
            {"volume", mp.volume},
            {"com", vec(mp.com)},
            {"inertia", mat(mp.inertia)},
            {"bbox", {{"min", vec(p.bbox_min)}, {"max", vec(p.bbox_max)}}},
            {"mass_defaulted", !p.mass.has_value()},
            {"source", loc(p.loc)}};
  if (p.rgba) j["rgba"] = *p.rgba;
  if (p.joint) j["joint"] = joint(*p.joint);
  add_extensions(j, p.extensions);
  return j;
}

void put(json& j, const char* key, const std::optional<double>& v) {
  if (v) j[key] = *v;
}

json mapping(const Mapping& m) {
  json j = {{"type", to_string(m.type)}};
  put(j, "threshold", m.threshold);
  if (m.latching) j["latching"] = *m.latching;
  put(j, "hysteresis", m.hysteresis);
  put(j, "gain", m.gain);
  put(j, "offset", m.offset);
  put(j, "delta", m.delta);
  put(j, "initial", m.initial);
  j["defaulted"] = m.defaulted;
  j["source"] = loc(m.loc);
  add_extensions(j, m.extensions);
  return j;
}

json effect(const Effect& e) {
  json j = {{"type", to_string(e.type)}, {"range", json::array({e.lo, e.hi})}};
  put(j, "stiffness", e.stiffness);
  put(j, "damping", e.damping);
  if (e.color) j["color"] = vec(*e.color);
  put(j, "time_constant", e.time_constant);
  put(j, "speed", e.speed);
  put(j, "droplet_radius", e.droplet_radius);
  put(j, "cone_angle", e.cone_angle);
  put(j, "reach", e.reach);
  if (e.type == EffectType::Fluid || e.type == EffectType::Airflow) {
    json point;
    if (e.position) point["position"] = vec(*e.position);
    if (e.direction) point["direction"] = vec(*e.direction);
    j[e.type == EffectType::Fluid ? "emitter" : "outlet"] = point;
  } else if (e.position) {
    j["position"] = vec(*e.position);
  }
  j["defaulted"] = e.defaulted;
  j["source"] = loc(e.loc);
  add_extensions(j, e.extensions);
  return j;
}

}  // namespace

json ir_to_json(const Object& obj) {
  json j = {{"efc", obj.version}, {"name", obj.name}, {"file", obj.file}};
  if (obj.description) j["description"] = *obj.description;
  j["parts"] = json::array();
  for (const Part& p : obj.parts) j["parts"].push_back(part(p));
  j["functions"] = json::array();
  for (const Function& f : obj.functions)
    j["functions"].push_back({{"name", f.name},
                              {"receptor", f.receptor},
                              {"effector", f.effector},
                              {"mapping", mapping(f.mapping)},
                              {"effect", effect(f.effect)},
                              {"source", loc(f.loc)}});
  add_extensions(j, obj.extensions);
  return j;
}

}  // namespace efc
