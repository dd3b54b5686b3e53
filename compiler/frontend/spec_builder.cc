#include "compiler/frontend/spec_builder.h"

#include <cmath>

#include "compiler/frontend/mesh_path.h"
#include "compiler/frontend/suggest.h"

namespace efc::frontend {
namespace {

using nlohmann::json;
using Keys = std::vector<std::string>;

const Keys kRoles = {"base", "receptor", "effector", "other"};
const Keys kJointTypes = {"fixed", "revolute", "continuous", "prismatic"};
const Keys kMappingTypes = {"binary", "step", "linear", "cumulative"};
const Keys kEffectTypes = {"geometry", "illumination", "temperature", "fluid", "airflow"};
const Keys kGeomKinds = {"mesh", "box", "cylinder", "sphere", "compound"};

std::string join(const Keys& k) {
  std::string s;
  for (const auto& x : k) s += (s.empty() ? "" : ", ") + x;
  return s;
}

int index_of(const Keys& k, const std::string& v) {
  for (size_t i = 0; i < k.size(); ++i)
    if (k[i] == v) return static_cast<int>(i);
  return -1;
}

// The last token of a pointer, unescaped enough for messages.
std::string last_token(const std::string& ptr) {
  auto at = ptr.rfind('/');
  return at == std::string::npos ? ptr : ptr.substr(at + 1);
}

class Builder {
 public:
  Builder(Object& obj, const ReadOptions& opts, Diagnostics& d)
      : obj_(obj), opts_(opts), diags_(d) {}

  void top(const json& doc) {
    obj_.loc = loc("");
    if (!doc.is_object()) {
      err("E0101", "", "the document must be a JSON object, got " + json_kind_phrase(doc),
          "a spec looks like {\"efc\": 1, \"name\": ..., \"parts\": [...]}");
      return;
    }
    keys(doc, "", {"efc", "name", "description", "parts", "functions"}, &obj_.extensions,
         "the top level");
    if (const json* v = get(doc, "", "efc", true)) {
      if (v->is_number_integer() && v->get<long long>() == 1) {
        obj_.version = 1;
      } else {
        err("E0104", "/efc", "unsupported format version " + v->dump() + " (this compiler reads 1)",
            "write \"efc\": 1");
      }
    }
    name(doc, "", "name", &obj_.name, "object name");
    if (const json* v = get(doc, "", "description", false)) {
      if (v->is_string())
        obj_.description = v->get<std::string>();
      else
        type_err("/description", *v, "a string");
    }
    if (const json* v = get(doc, "", "parts", true)) {
      if (!v->is_array()) {
        type_err("/parts", *v, "an array");
      } else if (v->empty()) {
        err("E0116", "/parts", "'parts' is empty; an object needs at least one part",
            "add the root part (the one without a joint)");
      } else {
        obj_.parts.resize(v->size());
        for (size_t i = 0; i < v->size(); ++i)
          part((*v)[i], "/parts/" + std::to_string(i), obj_.parts[i]);
      }
    }
    if (const json* v = get(doc, "", "functions", false)) {
      if (!v->is_array()) {
        type_err("/functions", *v, "an array");
      } else {
        obj_.functions.resize(v->size());
        for (size_t i = 0; i < v->size(); ++i)
          function((*v)[i], "/functions/" + std::to_string(i), obj_.functions[i]);
      }
    }
  }

 private:
  // ------------------------------------------------------------ reporting
  std::pair<int, int> pos_of(std::string ptr) const {
    for (;;) {
      auto it = obj_.positions.find(ptr);
      if (it != obj_.positions.end()) return it->second;
      if (ptr.empty()) return {0, 0};
      ptr = ptr.substr(0, ptr.rfind('/'));
    }
  }
  SourceLoc loc(const std::string& ptr) const {
    auto p = pos_of(ptr);
    return {ptr, p.first, p.second};
  }
  void err(const char* code, const std::string& ptr, std::string msg, std::string hint = {}) {
    auto p = pos_of(ptr);
    diags_.error(code, obj_.file, p.first, p.second, ptr, std::move(msg), std::move(hint));
  }
  void type_err(const std::string& ptr, const json& v, const std::string& want) {
    err("E0101", ptr, "'" + last_token(ptr) + "' must be " + want + ", got " + json_kind_phrase(v));
  }

  // ------------------------------------------------------------ fields
  // Unknown keys are errors (at the key); `x-` keys go to ext (or are accepted
  // and dropped where the IR has no node to keep them on: ext == nullptr).
  void keys(const json& o, const std::string& ptr, const Keys& allowed, Extensions* ext,
            const std::string& where) {
    for (auto it = o.begin(); it != o.end(); ++it) {
      const std::string& k = it.key();
      if (k.rfind("x-", 0) == 0) {
        if (ext) (*ext)[k] = it.value();
        continue;
      }
      if (index_of(allowed, k) >= 0) continue;
      std::string kp = pointer_append(ptr, k);
      auto kpos = obj_.positions.find(key_position(kp));
      auto p = kpos != obj_.positions.end() ? kpos->second : pos_of(kp);
      std::string hint = did_you_mean(k, allowed);
      if (hint.empty()) hint = "allowed here: " + join(allowed) + " (and x-... extension keys)";
      diags_.error("E0103", obj_.file, p.first, p.second, kp,
                   "unknown key '" + k + "' in " + where, hint);
    }
  }

  const json* get(const json& o, const std::string& ptr, const char* key, bool required) {
    auto it = o.find(key);
    if (it != o.end()) return &*it;
    if (required)
      err("E0102", pointer_append(ptr, key), std::string("missing required field '") + key + "'");
    return nullptr;
  }

  bool number(const json& v, const std::string& ptr, double* out) {
    if (!v.is_number()) {
      type_err(ptr, v, "a number");
      return false;
    }
    double d = v.get<double>();
    if (!std::isfinite(d)) {  // cannot come from JSON text; other producers may
      err("E0006", ptr, "number is not finite");
      return false;
    }
    *out = d;
    return true;
  }
  std::optional<double> opt_number(const json& o, const std::string& ptr, const char* key,
                                   bool required = false) {
    const json* v = get(o, ptr, key, required);
    double d;
    if (v && number(*v, pointer_append(ptr, key), &d)) return d;
    return std::nullopt;
  }
  bool vec(const json& v, const std::string& ptr, size_t n, double* out) {
    if (!v.is_array()) {
      type_err(ptr, v, "an array of " + std::to_string(n) + " numbers");
      return false;
    }
    if (v.size() != n) {
      err("E0109", ptr,
          "'" + last_token(ptr) + "' must have " + std::to_string(n) + " numbers, got " +
              std::to_string(v.size()));
      return false;
    }
    bool ok = true;
    for (size_t i = 0; i < n; ++i) ok &= number(v[i], ptr + "/" + std::to_string(i), &out[i]);
    return ok;
  }
  std::optional<Vec3> opt_vec3(const json& o, const std::string& ptr, const char* key) {
    const json* v = get(o, ptr, key, false);
    Vec3 r;
    if (v && vec(*v, pointer_append(ptr, key), 3, r.data())) return r;
    return std::nullopt;
  }
  // Colour components in [0, 1].
  bool colour(const json& v, const std::string& ptr, size_t n, double* out) {
    if (!vec(v, ptr, n, out)) return false;
    bool ok = true;
    for (size_t i = 0; i < n; ++i) {
      if (out[i] < 0 || out[i] > 1) {
        err("E0110", ptr + "/" + std::to_string(i),
            "colour component " + json(out[i]).dump() + " is outside [0, 1]",
            "colours are fractions: 255 is 1.0");
        ok = false;
      }
    }
    return ok;
  }
  std::optional<std::string> str(const json& o, const std::string& ptr, const char* key,
                                 bool required) {
    const json* v = get(o, ptr, key, required);
    if (!v) return std::nullopt;
    if (!v->is_string()) {
      type_err(pointer_append(ptr, key), *v, "a string");
      return std::nullopt;
    }
    return v->get<std::string>();
  }
  // A required name: a string matching the name pattern, not reserved.
  void name(const json& o, const std::string& ptr, const char* key, std::string* out,
            const char* what) {
    auto s = str(o, ptr, key, true);
    if (!s) return;
    std::string kp = pointer_append(ptr, key);
    if (!is_valid_name(*s)) {
      err("E0105", kp,
          std::string(what) + " " + json(*s).dump(-1, ' ', false, json::error_handler_t::replace) +
              " is not a valid name",
          "names match [A-Za-z_][A-Za-z0-9_]{0,63}: letters, digits and '_', not starting "
          "with a digit, at most 64 characters (they become XML, C++ and Python identifiers)");
      return;
    }
    if (s->rfind("efc_", 0) == 0) {
      err("E0106", kp, std::string(what) + " '" + *s + "' starts with the reserved prefix 'efc_'",
          "the compiler names the elements it generates efc_...; choose another name");
      return;
    }
    *out = *s;
  }
  // An enum value; returns its index in `values` or -1.
  int enum_value(const json& o, const std::string& ptr, const char* key, const Keys& values,
                 bool required, const char* what) {
    auto s = str(o, ptr, key, required);
    if (!s) return -1;
    int i = index_of(values, *s);
    if (i < 0) {
      std::string hint = did_you_mean(*s, values);
      err("E0107", pointer_append(ptr, key),
          std::string("unknown ") + what + " '" + *s + "'",
          hint.empty() ? "one of: " + join(values) : hint);
    }
    return i;
  }
  bool is_obj(const json& v, const std::string& ptr) {
    if (v.is_object()) return true;
    type_err(ptr, v, "an object");
    return false;
  }

  // ------------------------------------------------------------ nodes
  void part(const json& v, const std::string& ptr, Part& p) {
    p.loc = loc(ptr);
    if (!is_obj(v, ptr)) return;
    keys(v, ptr, {"name", "role", "geometry", "mass", "rgba", "joint"}, &p.extensions, "a part");
    name(v, ptr, "name", &p.name, "part name");
    int role = enum_value(v, ptr, "role", kRoles, false, "role");
    if (role >= 0) p.role = static_cast<PartRole>(role);
    if (const json* g = get(v, ptr, "geometry", true)) geometry(*g, ptr + "/geometry", p.geometry);
    p.mass = opt_number(v, ptr, "mass");
    if (const json* c = get(v, ptr, "rgba", false)) {
      std::array<double, 4> rgba;
      if (colour(*c, ptr + "/rgba", 4, rgba.data())) p.rgba = rgba;
    }
    if (const json* j = get(v, ptr, "joint", false)) {
      p.joint.emplace();
      joint(*j, ptr + "/joint", *p.joint);
    }
  }

  void geometry(const json& v, const std::string& ptr, Geometry& g) {
    g.loc = loc(ptr);
    if (!is_obj(v, ptr)) return;
    keys(v, ptr, {"mesh", "scale", "box", "cylinder", "sphere", "compound"}, &g.extensions,
         "a geometry");
    Keys present;
    for (const auto& k : kGeomKinds)
      if (v.contains(k)) present.push_back(k);
    if (present.size() != 1) {
      err("E0108", ptr,
          present.empty() ? "geometry has none of mesh, box, cylinder, sphere, compound"
                          : "geometry has several kinds (" + join(present) + "); it needs one",
          "use one; several pieces of one part go in \"compound\": [...]");
      return;
    }
    const std::string kind = present[0];
    g.kind = static_cast<GeomKind>(index_of(kGeomKinds, kind));
    const std::string kp = ptr + "/" + kind;
    const json& body = v[kind];
    if (v.contains("scale") && kind != "mesh") {
      auto p = obj_.positions.count(key_position(ptr + "/scale"))
                   ? obj_.positions.at(key_position(ptr + "/scale"))
                   : pos_of(ptr + "/scale");
      diags_.error("E0103", obj_.file, p.first, p.second, ptr + "/scale",
                   "'scale' applies only to a mesh, not to a " + kind,
                   "give the " + kind + "'s sizes directly");
    }
    // x- keys inside a primitive's object are accepted but not kept: the IR
    // has no node for it (the geometry's own x- keys are kept).
    switch (g.kind) {
      case GeomKind::Mesh: {
        if (!body.is_string()) {
          type_err(kp, body, "a string (a file path)");
          break;
        }
        g.mesh_path = body.get<std::string>();
        auto r = check_mesh_path(g.mesh_path, obj_.base_dir, opts_.allow_absolute_paths);
        if (*r.code)
          err(r.code, kp, r.message, r.hint);
        else
          g.mesh_resolved = r.resolved;
        if (auto s = opt_vec3(v, ptr, "scale")) g.scale = *s;
        break;
      }
      case GeomKind::Box:
        if (!is_obj(body, kp)) break;
        keys(body, kp, {"size", "center", "rpy"}, nullptr, "a box");
        if (const json* s = get(body, kp, "size", true)) vec(*s, kp + "/size", 3, g.size.data());
        if (auto c = opt_vec3(body, kp, "center")) g.center = *c;
        if (auto r = opt_vec3(body, kp, "rpy")) g.rpy = *r;
        break;
      case GeomKind::Cylinder:
        if (!is_obj(body, kp)) break;
        keys(body, kp, {"radius", "length", "center", "axis"}, nullptr, "a cylinder");
        if (auto r = opt_number(body, kp, "radius", true)) g.radius = *r;
        if (auto l = opt_number(body, kp, "length", true)) g.length = *l;
        if (auto c = opt_vec3(body, kp, "center")) g.center = *c;
        if (auto a = opt_vec3(body, kp, "axis")) g.axis = *a;
        break;
      case GeomKind::Sphere:
        if (!is_obj(body, kp)) break;
        keys(body, kp, {"radius", "center"}, nullptr, "a sphere");
        if (auto r = opt_number(body, kp, "radius", true)) g.radius = *r;
        if (auto c = opt_vec3(body, kp, "center")) g.center = *c;
        break;
      case GeomKind::Compound:
        if (!body.is_array()) {
          type_err(kp, body, "an array of geometries");
          break;
        }
        if (body.empty()) {
          err("E0116", kp, "'compound' is empty; it needs at least one geometry");
          break;
        }
        g.children.resize(body.size());
        for (size_t i = 0; i < body.size(); ++i)
          geometry(body[i], kp + "/" + std::to_string(i), g.children[i]);
        break;
    }
  }

  void joint(const json& v, const std::string& ptr, Joint& j) {
    j.loc = loc(ptr);
    if (!is_obj(v, ptr)) return;
    int t = enum_value(v, ptr, "type", kJointTypes, true, "joint type");
    // A fixed joint does not move: motion parameters are errors here (axis and
    // range get their own, clearer codes from check_structure()).
    if (t == static_cast<int>(JointType::Fixed))
      keys(v, ptr, {"type", "parent", "axis", "origin", "range"}, &j.extensions, "a fixed joint");
    else
      keys(v, ptr,
           {"type", "parent", "axis", "origin", "range", "initial", "damping", "friction", "spring"},
           &j.extensions, "a joint");
    if (t >= 0) j.type = static_cast<JointType>(t);
    if (auto p = str(v, ptr, "parent", true)) j.parent = *p;
    if (auto a = opt_vec3(v, ptr, "axis")) {
      j.axis = *a;
      j.has_axis = true;
    }
    if (auto o = opt_vec3(v, ptr, "origin")) {
      j.origin = *o;
      j.has_origin = true;
    }
    if (const json* r = get(v, ptr, "range", false)) {
      double lohi[2];
      if (vec(*r, ptr + "/range", 2, lohi)) {
        j.has_range = true;
        j.lo = lohi[0];
        j.hi = lohi[1];
      }
    }
    j.initial = opt_number(v, ptr, "initial");
    if (auto d = opt_number(v, ptr, "damping")) j.damping = *d;
    if (auto f = opt_number(v, ptr, "friction")) j.friction = *f;
    if (const json* s = get(v, ptr, "spring", false)) {
      const std::string sp = ptr + "/spring";
      Spring spring;
      spring.loc = loc(sp);
      if (is_obj(*s, sp)) {
        keys(*s, sp, {"stiffness", "rest"}, nullptr, "a spring");
        if (auto k = opt_number(*s, sp, "stiffness", true)) spring.stiffness = *k;
        if (auto r = opt_number(*s, sp, "rest")) spring.rest = *r;
        j.spring = spring;
      }
    }
  }

  void function(const json& v, const std::string& ptr, Function& f) {
    f.loc = loc(ptr);
    if (!is_obj(v, ptr)) return;
    keys(v, ptr, {"name", "receptor", "effector", "mapping", "effect"}, &f.extensions,
         "a function");
    name(v, ptr, "name", &f.name, "function name");
    if (auto r = str(v, ptr, "receptor", true)) f.receptor = *r;
    if (auto e = str(v, ptr, "effector", true)) f.effector = *e;
    if (const json* m = get(v, ptr, "mapping", true)) mapping(*m, ptr + "/mapping", f.mapping);
    if (const json* e = get(v, ptr, "effect", true)) effect(*e, ptr + "/effect", f.effect);
  }

  void mapping(const json& v, const std::string& ptr, Mapping& m) {
    m.loc = loc(ptr);
    if (!is_obj(v, ptr)) return;
    int t = enum_value(v, ptr, "type", kMappingTypes, true, "mapping type");
    static const Keys per_type[] = {{"type", "threshold", "latching"},
                                    {"type", "threshold", "hysteresis"},
                                    {"type", "gain", "offset"},
                                    {"type", "threshold", "delta", "initial"}};
    // With an unknown type, accept every mapping key rather than pile up errors.
    Keys allowed = t >= 0 ? per_type[t]
                          : Keys{"type", "threshold", "latching", "hysteresis", "gain", "offset",
                                 "delta", "initial"};
    keys(v, ptr, allowed, &m.extensions,
         t >= 0 ? "a " + kMappingTypes[t] + " mapping" : std::string("a mapping"));
    if (t >= 0) m.type = static_cast<MappingType>(t);
    m.threshold = opt_number(v, ptr, "threshold");
    if (const json* l = get(v, ptr, "latching", false)) {
      if (l->is_boolean())
        m.latching = l->get<bool>();
      else
        type_err(ptr + "/latching", *l, "true or false");
    }
    m.hysteresis = opt_number(v, ptr, "hysteresis");
    m.gain = opt_number(v, ptr, "gain");
    m.offset = opt_number(v, ptr, "offset");
    m.delta = opt_number(v, ptr, "delta");
    m.initial = opt_number(v, ptr, "initial");
  }

  void effect(const json& v, const std::string& ptr, Effect& e) {
    e.loc = loc(ptr);
    if (!is_obj(v, ptr)) return;
    int t = enum_value(v, ptr, "type", kEffectTypes, true, "effect type");
    static const Keys per_type[] = {
        {"type", "range", "stiffness", "damping"},
        {"type", "range", "color", "position"},
        {"type", "range", "time_constant", "position"},
        {"type", "range", "emitter", "speed", "droplet_radius"},
        {"type", "range", "outlet", "cone_angle", "reach"}};
    Keys allowed = t >= 0 ? per_type[t]
                          : Keys{"type", "range", "stiffness", "damping", "color", "position",
                                 "time_constant", "emitter", "speed", "droplet_radius", "outlet",
                                 "cone_angle", "reach"};
    keys(v, ptr, allowed, &e.extensions,
         t >= 0 ? "a " + kEffectTypes[t] + " effect" : std::string("an effect"));
    if (t >= 0) e.type = static_cast<EffectType>(t);
    if (const json* r = get(v, ptr, "range", false)) {
      double lohi[2];
      if (vec(*r, ptr + "/range", 2, lohi)) {
        e.has_range = true;
        e.lo = lohi[0];
        e.hi = lohi[1];
      }
    }
    e.stiffness = opt_number(v, ptr, "stiffness");
    e.damping = opt_number(v, ptr, "damping");
    if (const json* c = get(v, ptr, "color", false)) {
      Vec3 rgb;
      if (colour(*c, ptr + "/color", 3, rgb.data())) e.color = rgb;
    }
    if (auto p = opt_vec3(v, ptr, "position")) e.position = *p;
    e.time_constant = opt_number(v, ptr, "time_constant");
    e.speed = opt_number(v, ptr, "speed");
    e.droplet_radius = opt_number(v, ptr, "droplet_radius");
    e.cone_angle = opt_number(v, ptr, "cone_angle");
    e.reach = opt_number(v, ptr, "reach");
    for (const char* pk : {"emitter", "outlet"}) {
      const json* p = get(v, ptr, pk, false);
      if (!p) continue;
      const std::string pp = ptr + "/" + pk;
      if (!is_obj(*p, pp)) continue;
      keys(*p, pp, {"position", "direction"}, &e.point_extensions, std::string("an ") + pk);
      if (auto pos = opt_vec3(*p, pp, "position")) e.position = *pos;
      if (auto dir = opt_vec3(*p, pp, "direction")) e.direction = *dir;
    }
  }

  Object& obj_;
  const ReadOptions& opts_;
  Diagnostics& diags_;
};

}  // namespace

void build_object(const json& doc, Object& obj, const ReadOptions& opts, Diagnostics& diags) {
  Builder(obj, opts, diags).top(doc);
}

}  // namespace efc::frontend
