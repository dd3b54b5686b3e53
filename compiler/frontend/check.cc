// check_structure(): the spec's type rules that span fields, before defaults.
// Each rule is its own function; all of them run, so one run reports every
// violation. Rules that need a valid reference skip parts/functions whose
// reference is already reported broken (no follow-up noise).
#include "compiler/frontend/check.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "compiler/frontend/suggest.h"

namespace efc {
namespace {

std::string num(double v) { return nlohmann::json(v).dump(); }

std::string part_ptr(size_t i) { return "/parts/" + std::to_string(i); }
std::string fn_ptr(size_t i) { return "/functions/" + std::to_string(i); }

std::vector<std::string> part_names(const Object& obj) {
  std::vector<std::string> n;
  for (const auto& p : obj.parts) n.push_back(p.name);
  return n;
}

// Part names unique; function names unique.
void check_names(const Object& obj, Diagnostics& d) {
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    auto [it, fresh] = seen.emplace(obj.parts[i].name, i);
    if (!fresh)
      report(d, obj, "E0207", part_ptr(i) + "/name",
             "part name '" + obj.parts[i].name + "' is already used by part " +
                 std::to_string(it->second),
             "part names must be unique");
  }
  seen.clear();
  for (size_t i = 0; i < obj.functions.size(); ++i) {
    auto [it, fresh] = seen.emplace(obj.functions[i].name, i);
    if (!fresh)
      report(d, obj, "E0301", fn_ptr(i) + "/name",
             "function name '" + obj.functions[i].name + "' is already used by function " +
                 std::to_string(it->second),
             "function names must be unique");
  }
}

// Exactly one root (a part without a joint).
void check_root(const Object& obj, Diagnostics& d) {
  int first = -1;
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    if (obj.parts[i].joint) continue;
    if (first < 0) {
      first = static_cast<int>(i);
      continue;
    }
    report(d, obj, "E0202", part_ptr(i),
           "part '" + obj.parts[i].name + "' has no joint, but '" + obj.parts[first].name +
               "' is already the root",
           "exactly one part is fixed to the world; give '" + obj.parts[i].name +
               "' a joint (\"type\": \"fixed\" to attach it rigidly)");
  }
  if (first < 0 && !obj.parts.empty())
    report(d, obj, "E0201", "/parts", "no root part: every part has a joint",
           "remove the joint of the part fixed to the world (usually the base)");
}

// Parents exist, are not the part itself; fills parent_index.
void check_parents(Object& obj, Diagnostics& d) {
  auto names = part_names(obj);
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    auto& j = obj.parts[i].joint;
    if (!j) continue;
    j->parent_index = -1;
    const std::string ptr = part_ptr(i) + "/joint/parent";
    int p = obj.find_part(j->parent);
    if (p < 0) {
      std::string hint = frontend::did_you_mean(j->parent, names);
      report(d, obj, "E0204", ptr, "parent '" + j->parent + "' of part '" + obj.parts[i].name +
                                       "' is not a part",
             hint);
    } else if (p == static_cast<int>(i)) {
      report(d, obj, "E0205", ptr, "part '" + obj.parts[i].name + "' is its own parent",
             "name the part it is mounted on");
    } else {
      j->parent_index = p;
    }
  }
}

// Parent links form a tree: following parents never loops. One error per loop.
void check_tree(const Object& obj, Diagnostics& d) {
  const size_t n = obj.parts.size();
  std::vector<int> state(n, 0);  // 0 new, 1 on the current walk, 2 done
  for (size_t start = 0; start < n; ++start) {
    std::vector<int> walk;
    int k = static_cast<int>(start);
    while (k >= 0 && state[k] == 0) {
      state[k] = 1;
      walk.push_back(k);
      k = obj.parts[k].joint ? obj.parts[k].joint->parent_index : -1;
    }
    if (k >= 0 && state[k] == 1) {  // back on this walk: a loop from k
      size_t from = 0;
      while (walk[from] != k) ++from;
      int lowest = k;
      for (size_t w = from; w < walk.size(); ++w) lowest = std::min(lowest, walk[w]);
      std::string chain;
      int c = lowest;
      do {
        chain += "'" + obj.parts[c].name + "' -> ";
        c = obj.parts[c].joint->parent_index;
      } while (c != lowest);
      chain += "'" + obj.parts[lowest].name + "'";
      report(d, obj, "E0206", part_ptr(lowest) + "/joint/parent",
             "parents form a cycle: " + chain,
             "parts hang from their parent down to the root; break the loop");
    }
    for (int w : walk) state[w] = 2;
  }
}

// One joint's own values: range, axis, origin, damping.
void check_joint(const Object& obj, size_t i, Diagnostics& d) {
  const Part& part = obj.parts[i];
  const Joint& j = *part.joint;
  const std::string ptr = part_ptr(i) + "/joint";
  const bool needs_range = j.type == JointType::Revolute || j.type == JointType::Prismatic;
  if (needs_range && !j.has_range)
    report(d, obj, "E0208", ptr + "/range",
           std::string("joint '") + part.name + "' is " + to_string(j.type) + " but has no range",
           j.type == JointType::Revolute
               ? "add \"range\": [lo, hi] in radians, or use \"type\": \"continuous\""
               : "add \"range\": [lo, hi] in metres");
  if (!needs_range && j.has_range)
    report(d, obj, "E0209", ptr + "/range",
           std::string("joint '") + part.name + "' is " + to_string(j.type) +
               " and cannot have a range",
           j.type == JointType::Continuous ? "remove the range, or use \"type\": \"revolute\""
                                           : "remove the range");
  if (needs_range && j.has_range && !(j.lo < j.hi))
    report(d, obj, "E0203", ptr + "/range",
           "joint '" + part.name + "' range [" + num(j.lo) + ", " + num(j.hi) +
               "] is not ordered (lo < hi)",
           j.lo > j.hi ? "swap the two numbers" : "the two ends must differ");
  if (j.has_axis) {
    double n = std::sqrt(j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2]);
    if (j.type == JointType::Fixed)
      report(d, obj, "E0211", ptr + "/axis",
             "joint '" + part.name + "' is fixed and cannot have an axis", "remove the axis");
    else if (n == 0)
      report(d, obj, "E0210", ptr + "/axis", "joint '" + part.name + "' axis is the zero vector",
             "give the direction it turns about or slides along, e.g. [0, 0, 1]");
    else if (std::fabs(n - 1) > 1e-3)
      report_warning(d, obj, "W0201", ptr + "/axis",
                     "joint '" + part.name + "' axis has length " + num(n) +
                         "; it is normalised",
                     "write a unit vector to silence this");
  }
  if (j.has_origin && j.type == JointType::Prismatic)
    report_warning(d, obj, "W0202", ptr + "/origin",
                   "joint '" + part.name + "' is prismatic; its origin is ignored",
                   "remove the origin (a slide has no pivot)");
  if (j.damping < 0)
    report(d, obj, "E0214", ptr + "/damping", "joint damping " + num(j.damping) + " is negative");
  if (j.friction < 0)
    report(d, obj, "E0214", ptr + "/friction",
           "joint friction " + num(j.friction) + " is negative");
  if (j.spring && !(j.spring->stiffness > 0))
    report(d, obj, "E0214", ptr + "/spring/stiffness",
           "spring stiffness " + num(j.spring->stiffness) + " must be positive",
           "a spring without stiffness does nothing: remove it or give N m/rad (N/m)");
}

// Sizes of a geometry (recursively for compounds) are positive.
void check_geometry(const Object& obj, const Geometry& g, Diagnostics& d) {
  const std::string& p = g.loc.pointer;
  auto positive = [&](double v, const std::string& field, const char* what) {
    if (!(v > 0))
      report(d, obj, "E0213", p + field, std::string(what) + " " + num(v) + " must be positive");
  };
  switch (g.kind) {
    case GeomKind::Mesh:
      for (int k = 0; k < 3; ++k) positive(g.scale[k], "/scale/" + std::to_string(k), "mesh scale");
      break;
    case GeomKind::Box:
      for (int k = 0; k < 3; ++k) positive(g.size[k], "/box/size/" + std::to_string(k), "box size");
      break;
    case GeomKind::Cylinder:
      positive(g.radius, "/cylinder/radius", "cylinder radius");
      positive(g.length, "/cylinder/length", "cylinder length");
      if (g.axis[0] == 0 && g.axis[1] == 0 && g.axis[2] == 0)
        report(d, obj, "E0210", p + "/cylinder/axis", "cylinder axis is the zero vector",
               "give the cylinder's direction, e.g. [0, 0, 1]");
      break;
    case GeomKind::Sphere:
      positive(g.radius, "/sphere/radius", "sphere radius");
      break;
    case GeomKind::Compound:
      for (const auto& c : g.children) check_geometry(obj, c, d);
      break;
  }
}

void check_parts(const Object& obj, Diagnostics& d) {
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    const Part& p = obj.parts[i];
    if (p.mass && !(*p.mass > 0))
      report(d, obj, "E0212", part_ptr(i) + "/mass",
             "part '" + p.name + "' mass " + num(*p.mass) + " must be positive",
             "leave it out to compute it from the geometry");
    check_geometry(obj, p.geometry, d);
    if (p.joint) check_joint(obj, i, d);
  }
}

bool movable(const Part& p) { return p.joint && p.joint->movable(); }

// References of each function; fills receptor_index and effector_index.
void check_references(Object& obj, Diagnostics& d) {
  auto names = part_names(obj);
  for (size_t i = 0; i < obj.functions.size(); ++i) {
    Function& f = obj.functions[i];
    const std::string ptr = fn_ptr(i);
    f.receptor_index = obj.find_part(f.receptor);
    f.effector_index = obj.find_part(f.effector);
    if (f.receptor_index < 0)
      report(d, obj, "E0302", ptr + "/receptor",
             "receptor '" + f.receptor + "' of function '" + f.name + "' is not a part",
             frontend::did_you_mean(f.receptor, names));
    if (f.effector_index < 0)
      report(d, obj, "E0303", ptr + "/effector",
             "effector '" + f.effector + "' of function '" + f.name + "' is not a part",
             frontend::did_you_mean(f.effector, names));
    if (f.receptor_index >= 0 && f.receptor_index == f.effector_index)
      report(d, obj, "E0304", ptr + "/effector",
             "function '" + f.name + "' has '" + f.receptor + "' as both receptor and effector",
             "the effector is the part the function acts on; it must be another part");
    if (f.receptor_index >= 0 && !movable(obj.parts[f.receptor_index]))
      report(d, obj, "E0305", ptr + "/receptor",
             "receptor '" + f.receptor + "' of function '" + f.name + "' cannot move (" +
                 (obj.parts[f.receptor_index].joint ? "fixed joint" : "it is the root") + ")",
             "a receptor is what the user moves: give it a revolute, continuous or prismatic joint");
    if (f.effect.type == EffectType::Geometry && f.effector_index >= 0 &&
        f.effector_index != f.receptor_index && !movable(obj.parts[f.effector_index]))
      report(d, obj, "E0306", ptr + "/effector",
             "function '" + f.name + "' moves '" + f.effector + "', which has no movable joint",
             "a geometry effect drives the effector's joint: make it revolute, continuous or "
             "prismatic");
  }
}

// No two functions write the same (effector, effect type).
void check_writers(const Object& obj, Diagnostics& d) {
  std::map<std::pair<int, int>, size_t> seen;
  for (size_t i = 0; i < obj.functions.size(); ++i) {
    const Function& f = obj.functions[i];
    if (f.effector_index < 0) continue;
    auto key = std::make_pair(f.effector_index, static_cast<int>(f.effect.type));
    auto [it, fresh] = seen.emplace(key, i);
    if (!fresh)
      report(d, obj, "E0307", fn_ptr(i) + "/effect/type",
             "functions '" + obj.functions[it->second].name + "' and '" + f.name +
                 "' both set the " + to_string(f.effect.type) + " of '" + f.effector + "'",
             "merge them into one function, or act on different parts");
  }
}

// The function graph (receptor -> effector over parts) has no cycle.
// Iterative DFS; each back edge is one cycle, reported at its closing function.
void check_function_graph(const Object& obj, Diagnostics& d) {
  const size_t n = obj.parts.size();
  std::vector<std::vector<size_t>> out(n);  // part -> functions leaving it
  for (size_t i = 0; i < obj.functions.size(); ++i) {
    const Function& f = obj.functions[i];
    if (f.receptor_index >= 0 && f.effector_index >= 0 && f.receptor_index != f.effector_index)
      out[f.receptor_index].push_back(i);
  }
  std::vector<int> color(n, 0);
  std::vector<size_t> via(n, 0);  // function that reached the part on the DFS path
  for (size_t s = 0; s < n; ++s) {
    if (color[s]) continue;
    std::vector<std::pair<size_t, size_t>> stack{{s, 0}};  // part, next edge
    color[s] = 1;
    while (!stack.empty()) {
      auto& [u, e] = stack.back();
      if (e == out[u].size()) {
        color[u] = 2;
        stack.pop_back();
        continue;
      }
      size_t fi = out[u][e++];
      size_t v = static_cast<size_t>(obj.functions[fi].effector_index);
      if (color[v] == 0) {
        color[v] = 1;
        via[v] = fi;
        stack.push_back({v, 0});
      } else if (color[v] == 1) {
        std::string chain = "'" + obj.functions[fi].name + "'", first = chain;
        for (size_t k = stack.size(); k-- > 0 && stack[k].first != v;)
          chain = first = "'" + obj.functions[via[stack[k].first]].name + "' -> " + chain;
        chain += " -> " + first.substr(0, first.find(" -> "));
        report(d, obj, "E0308", fn_ptr(fi) + "/effector",
               "functions form a cycle: " + chain + " (each one's effector drives the next)",
               "a chain of functions must end; remove one link");
      }
    }
  }
}

bool is_continuous_receptor(const Object& obj, const Function& f) {
  return f.receptor_index >= 0 && obj.parts[f.receptor_index].joint &&
         obj.parts[f.receptor_index].joint->type == JointType::Continuous;
}

void check_mapping(const Object& obj, size_t i, Diagnostics& d) {
  const Function& f = obj.functions[i];
  const Mapping& m = f.mapping;
  const std::string ptr = fn_ptr(i) + "/mapping";
  if (m.type == MappingType::Cumulative) {
    if (!m.delta)
      report(d, obj, "E0314", ptr + "/delta",
             "cumulative mapping of '" + f.name + "' needs a 'delta'",
             "add \"delta\": the amount each press adds (negative for a minus button)");
    else if (*m.delta == 0 || !std::isfinite(*m.delta))
      report(d, obj, "E0315", ptr + "/delta",
             "cumulative mapping of '" + f.name + "' has delta " + num(*m.delta),
             "a press must change something: use a non-zero delta");
  }
  if (m.type == MappingType::Linear && m.gain && (*m.gain == 0 || !std::isfinite(*m.gain)))
    report(d, obj, "E0316", ptr + "/gain",
           "linear mapping of '" + f.name + "' has gain " + num(*m.gain),
           "use a finite non-zero gain, or leave it out for the range-to-range default");
  if (m.type == MappingType::Step && m.hysteresis && *m.hysteresis < 0)
    report(d, obj, "E0319", ptr + "/hysteresis",
           "step mapping of '" + f.name + "' has negative hysteresis " + num(*m.hysteresis),
           "hysteresis is a width below the threshold: use 0 or more");
  if (is_continuous_receptor(obj, f)) {
    if (m.type == MappingType::Linear && !m.gain)
      report(d, obj, "E0317", ptr + "/gain",
             "linear mapping of '" + f.name + "' needs a 'gain': receptor '" + f.receptor +
                 "' is continuous and has no range",
             "add \"gain\": output units per radian");
    else if (m.type != MappingType::Linear && !m.threshold)
      report(d, obj, "E0317", ptr + "/threshold",
             std::string(to_string(m.type)) + " mapping of '" + f.name +
                 "' needs a 'threshold': receptor '" + f.receptor +
                 "' is continuous and has no range",
             "add \"threshold\": the angle (radians) where it switches");
  }
}

void check_effect(const Object& obj, size_t i, Diagnostics& d) {
  const Function& f = obj.functions[i];
  const Effect& e = f.effect;
  const std::string ptr = fn_ptr(i) + "/effect";
  if (e.has_range) {
    if (e.lo == e.hi)
      report(d, obj, "E0309", ptr + "/range",
             "effect range of '" + f.name + "' has two equal ends [" + num(e.lo) + ", " +
                 num(e.hi) + "]",
             "the ends are [off, on]: they must differ");
    const char* unit = nullptr;
    double floor = 0;
    switch (e.type) {
      case EffectType::Illumination: unit = "light output (lumens)"; break;
      case EffectType::Fluid: unit = "flow (L/min)"; break;
      case EffectType::Airflow: unit = "air speed (m/s)"; break;
      case EffectType::Temperature: unit = "temperature (C)"; floor = -273.15; break;
      case EffectType::Geometry: break;
    }
    if (unit) {
      for (int k = 0; k < 2; ++k) {
        double v = k ? e.hi : e.lo;
        if (v < floor)
          report(d, obj, "E0310", ptr + "/range/" + std::to_string(k),
                 std::string(unit) + " " + num(v) + " of '" + f.name + "' is below " + num(floor),
                 e.type == EffectType::Temperature ? "temperatures are in degrees Celsius"
                                                   : "the quantity cannot be negative");
      }
    }
  }
  auto positive = [&](const std::optional<double>& v, const char* field) {
    if (v && !(*v > 0))
      report(d, obj, "E0311", ptr + "/" + field,
             std::string(field) + " " + num(*v) + " of '" + f.name + "' must be positive");
  };
  positive(e.time_constant, "time_constant");
  positive(e.speed, "speed");
  positive(e.droplet_radius, "droplet_radius");
  positive(e.reach, "reach");
  if (e.cone_angle && !(*e.cone_angle > 0 && *e.cone_angle < M_PI / 2))
    report(d, obj, "E0312", ptr + "/cone_angle",
           "cone_angle " + num(*e.cone_angle) + " of '" + f.name + "' is not in (0, pi/2)",
           "it is the half-angle of the air cone, in radians (0.35 is about 20 degrees)");
  for (auto [v, field] : {std::make_pair(&e.stiffness, "stiffness"),
                          std::make_pair(&e.damping, "damping")})
    if (*v && **v < 0)
      report(d, obj, "E0313", ptr + "/" + field,
             std::string("drive ") + field + " " + num(**v) + " of '" + f.name + "' is negative");
  if (e.direction && (*e.direction)[0] == 0 && (*e.direction)[1] == 0 && (*e.direction)[2] == 0)
    report(d, obj, "E0322", ptr + (e.type == EffectType::Airflow ? "/outlet" : "/emitter") +
                                "/direction",
           "direction of '" + f.name + "' is the zero vector", "e.g. [0, 0, -1] for straight down");
}

}  // namespace

void append_in_file_order(const Diagnostics& from, Diagnostics& to) {
  std::vector<Diagnostic> items = from.items();
  std::stable_sort(items.begin(), items.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::make_pair(a.line, a.col) < std::make_pair(b.line, b.col);
  });
  for (auto& d : items) to.add(std::move(d));
}

SourceLoc locate(const Object& obj, const std::string& pointer) {
  std::string p = pointer;
  for (;;) {
    auto it = obj.positions.find(p);
    if (it != obj.positions.end()) return {pointer, it->second.first, it->second.second};
    if (p.empty()) return {pointer, 0, 0};
    p = p.substr(0, p.rfind('/'));
  }
}

void report(Diagnostics& diags, const Object& obj, const char* code, const std::string& pointer,
            std::string message, std::string hint) {
  SourceLoc l = locate(obj, pointer);
  diags.error(code, obj.file, l.line, l.col, pointer, std::move(message), std::move(hint));
}

void report_warning(Diagnostics& diags, const Object& obj, const char* code,
                    const std::string& pointer, std::string message, std::string hint) {
  SourceLoc l = locate(obj, pointer);
  diags.warning(code, obj.file, l.line, l.col, pointer, std::move(message), std::move(hint));
}

void check_structure(Object& obj, Diagnostics& out) {
  Diagnostics diags;  // collected, then put in file order
  check_names(obj, diags);
  check_root(obj, diags);
  check_parents(obj, diags);
  check_tree(obj, diags);
  check_parts(obj, diags);
  check_references(obj, diags);
  check_writers(obj, diags);
  check_function_graph(obj, diags);
  for (size_t i = 0; i < obj.functions.size(); ++i) {
    check_mapping(obj, i, diags);
    check_effect(obj, i, diags);
  }
  append_in_file_order(diags, out);
}

}  // namespace efc
