// vary_example() of example_variation.h.
#include <algorithm>
#include <map>
#include <set>

#include "synth/suite/example_variation.h"
#include "synth/suite/geometry_bounds.h"

namespace efc::synth::suite {
namespace {

// Values written back are snapped to 1e-6 (see spec_json.h): the product of
// two decimals would otherwise print with 17 digits.
void multiply(SpecJson& o, const char* key, double k) {
  if (o.contains(key) && o[key].is_number()) o[key] = snap(o[key].get<double>() * k);
}

void multiply_vec(SpecJson& o, const char* key, double k) {
  V3 v;
  if (o.contains(key) && read_vec(o[key], &v)) o[key] = json_vec(scale(v, k));
}

// An affine change of a quantity: q -> a + b q (b > 0, so order is kept).
struct Affine {
  double a = 0, b = 1;
  double operator()(double q) const { return snap(a + b * q); }
};

void map_number(SpecJson& o, const char* key, const Affine& f) {
  if (o.contains(key) && o[key].is_number()) o[key] = f(o[key].get<double>());
}

void map_range(SpecJson& o, const Affine& f) {
  if (!o.contains("range") || !o["range"].is_array() || o["range"].size() != 2) return;
  for (auto& end : o["range"])
    if (end.is_number()) end = f(end.get<double>());
}

bool read_range(const SpecJson& o, double* lo, double* hi) {
  if (!o.contains("range") || !o["range"].is_array() || o["range"].size() != 2 ||
      !o["range"][0].is_number() || !o["range"][1].is_number())
    return false;
  *lo = o["range"][0].get<double>();
  *hi = o["range"][1].get<double>();
  return true;
}

void scale_geometry(SpecJson& g, double s) {
  if (!g.is_object()) return;
  if (g.contains("compound") && g["compound"].is_array()) {
    for (auto& child : g["compound"]) scale_geometry(child, s);
    return;
  }
  if (g.contains("mesh")) {
    if (!g.contains("scale")) g["scale"] = SpecJson::array({1, 1, 1});
    multiply_vec(g, "scale", s);
    return;
  }
  for (const char* kind : {"box", "cylinder", "sphere"}) {
    if (!g.contains(kind) || !g[kind].is_object()) continue;
    SpecJson& p = g[kind];
    multiply_vec(p, "size", s);
    multiply_vec(p, "center", s);
    multiply(p, "radius", s);
    multiply(p, "length", s);
  }
}

void collect_meshes(const SpecJson& g, std::vector<std::string>* paths) {
  if (!g.is_object()) return;
  if (g.contains("compound") && g["compound"].is_array())
    for (const auto& child : g["compound"]) collect_meshes(child, paths);
  if (g.contains("mesh") && g["mesh"].is_string()) paths->push_back(g["mesh"].get<std::string>());
}

// A path the spec may name and the caller may copy: relative, no `..`.
bool stays_inside(const std::string& path) {
  if (path.empty() || path[0] == '/' || path[0] == '\\') return false;
  size_t start = 0;
  while (start <= path.size()) {
    size_t end = path.find_first_of("/\\", start);
    if (end == std::string::npos) end = path.size();
    if (path.compare(start, end - start, "..") == 0) return false;
    start = end + 1;
  }
  return true;
}

// Mostly lighter or darker, a little tinted: steel stays steel-like.
void jitter_colour(SpecJson& o, const char* key, SuiteRng& rng) {
  if (!o.contains(key) || !o[key].is_array() || o[key].size() < 3) return;
  const double shade = rng.uniform(-0.1, 0.1);
  for (size_t k = 0; k < 3; ++k) {
    const double tint = rng.uniform(-0.04, 0.04);
    if (o[key][k].is_number())
      o[key][k] = snap(std::clamp(o[key][k].get<double>() + shade + tint, 0.0, 1.0), 1e3);
  }
}

// Per part: how its joint positions change (position -> factor * position).
struct JointChange {
  std::string type;
  double factor = 1;
  bool bounded = false;
  double lo = 0, hi = 0;  // the new range
};

std::map<std::string, JointChange> vary_joints(SpecJson& parts, double s, SuiteRng& rng) {
  std::map<std::string, JointChange> out;
  for (auto& p : parts) {
    JointChange c;
    if (p.contains("joint")) {
      SpecJson& j = p["joint"];
      c.type = j["type"].get<std::string>();
      if (c.type == "revolute") c.factor = snap(rng.uniform(0.7, 1.1), 1e3);
      if (c.type == "prismatic") c.factor = s * snap(rng.uniform(0.75, 1.15), 1e3);
      multiply_vec(j, "origin", s);
      map_range(j, Affine{0, c.factor});
      multiply(j, "initial", c.factor);
      if (j.contains("spring") && j["spring"].is_object()) multiply(j["spring"], "rest", c.factor);
      c.bounded = read_range(j, &c.lo, &c.hi);
    }
    out[p["name"].get<std::string>()] = c;
  }
  return out;
}

// How the effect's quantity changes; geometry targets follow their joint.
Affine effect_change(const std::string& type, const JointChange& effector, SuiteRng& rng) {
  if (type == "geometry") return {0, effector.factor};
  if (type == "temperature") {
    const double g = snap(rng.uniform(0.6, 1.25), 1e3);
    return {20 * (1 - g), g};  // about room temperature: 20 C stays 20 C
  }
  const double g =
      snap(type == "illumination" ? rng.uniform(0.5, 1.8) : rng.uniform(0.6, 1.5), 1e3);
  return {0, g};
}

// The spec's default range of an effect type (efc-spec-v1.md, EFFECT).
SpecJson default_range(const std::string& type) {
  if (type == "illumination") return SpecJson::array({0, 800});
  if (type == "temperature") return SpecJson::array({20, 200});
  if (type == "fluid") return SpecJson::array({0, 6});
  return SpecJson::array({0, 10});
}

void vary_effect(SpecJson& e, const Affine& q, double s, SuiteRng& rng) {
  const std::string type = e["type"].get<std::string>();
  // Written out before it changes: the default would not follow.
  if (!e.contains("range") && type != "geometry") e["range"] = default_range(type);
  map_range(e, q);
  multiply_vec(e, "position", s);
  for (const char* point : {"emitter", "outlet"})
    if (e.contains(point) && e[point].is_object()) multiply_vec(e[point], "position", s);
  multiply(e, "reach", s);
  jitter_colour(e, "color", rng);
  // A real heater takes minutes; a suite clip lasts seconds. The time
  // constant is drawn as for a generated heater (0.5 to 3 s,
  // effector_parts.cc) so that the effect shows within the recording.
  if (e.contains("time_constant")) e["time_constant"] = snap(rng.uniform(0.5, 3), 10);
}

// The receptor's switching point, explicit or the spec's default.
double effective_threshold(const SpecJson& m, const JointChange& r) {
  if (m.contains("threshold") && m["threshold"].is_number()) return m["threshold"].get<double>();
  const double f = m["type"] == "step" ? 0.7 : 0.5;
  return r.lo + f * (r.hi - r.lo);
}

// How a hand-driven receptor's switching points move, as a fraction of its
// range: one shift per receptor, so functions sharing a mechanism (the
// toaster's latch) still switch together. Chained receptors keep theirs.
std::map<std::string, double> threshold_shifts(const SpecJson& functions,
                                               const std::set<std::string>& chained,
                                               SuiteRng& rng) {
  std::map<std::string, double> shifts;
  for (const auto& f : functions) {
    const std::string receptor = f["receptor"].get<std::string>();
    if (chained.count(receptor) || shifts.count(receptor)) continue;
    shifts[receptor] = rng.chance(0.6) ? rng.uniform(-0.2, 0.2) : 0.0;
  }
  return shifts;
}

void vary_mapping(SpecJson& m, const JointChange& r, const Affine& q, double threshold_shift,
                  SuiteRng& rng) {
  const std::string type = m["type"].get<std::string>();
  multiply(m, "threshold", r.factor);
  multiply(m, "hysteresis", r.factor);
  if (type == "linear") {
    // s_E = offset + gain (s_R - r_lo): per new receptor unit and new quantity.
    const double jitter = rng.chance(0.5) ? rng.uniform(0.8, 1.25) : 1.0;
    multiply(m, "gain", q.b / r.factor * jitter);
    map_number(m, "offset", q);
    return;
  }
  if (type == "cumulative") {
    multiply(m, "delta", q.b * (rng.chance(0.5) ? rng.uniform(0.75, 1.3) : 1.0));
    map_number(m, "initial", q);
  }
  if (!r.bounded) return;
  if (threshold_shift != 0) {
    const double span = r.hi - r.lo;
    const double f = (effective_threshold(m, r) - r.lo) / span;
    m["threshold"] = snap(r.lo + span * std::clamp(f + threshold_shift, 0.15, 0.85));
  }
  // Returning to the start of the travel must still switch it off.
  if (type == "step" && m.contains("hysteresis") && m["hysteresis"].is_number())
    m["hysteresis"] =
        snap(std::min(m["hysteresis"].get<double>(), 0.8 * (effective_threshold(m, r) - r.lo)));
}

}  // namespace

bool vary_example(const ExampleSpec& example, SuiteRng& rng, VariedExample* out,
                  std::string* error) {
  out->spec = example.doc;
  out->files.clear();
  SpecJson& parts = out->spec["parts"];

  Bounds bounds;
  std::vector<std::string> meshes;
  for (const auto& p : parts) {
    if (!add_geometry_bounds(p["geometry"], example.dir, &bounds, error)) return false;
    collect_meshes(p["geometry"], &meshes);
  }
  std::set<std::string> seen;
  for (const std::string& m : meshes) {
    if (!stays_inside(m)) {
      *error = "mesh path '" + m + "' leaves the examples folder";
      return false;
    }
    if (seen.insert(m).second) out->files.push_back({example.dir + "/" + m, m});
  }

  const double size = std::max(bounds.max_extent(), 1e-3);
  const double s_hi = std::min(1.3, std::max(1.0, 1.2 / size));
  const double s_lo = std::min(std::max(0.75, 0.1 / size), s_hi);
  const double s = snap(rng.uniform(s_lo, s_hi), 1e3);
  out->scale = s;
  // The example's text names its numbers; they change below.
  const SpecJson& text =
      example.doc.contains("description") ? example.doc["description"] : SpecJson();
  out->spec["description"] = "Suite variation of examples/" + example.name + ".json (scale " +
                             SpecJson(s).dump() + "; ranges and template parameters changed). " +
                             (text.is_string() ? text.get<std::string>() : "");

  for (auto& p : parts) {
    scale_geometry(p["geometry"], s);
    multiply(p, "mass", s * s * s);
    jitter_colour(p, "rgba", rng);
  }
  const std::map<std::string, JointChange> joints = vary_joints(parts, s, rng);

  if (!out->spec.contains("functions")) return true;
  std::set<std::string> moved_by_functions;
  for (const auto& f : out->spec["functions"])
    if (f["effect"]["type"] == "geometry")
      moved_by_functions.insert(f["effector"].get<std::string>());
  const std::map<std::string, double> shifts =
      threshold_shifts(out->spec["functions"], moved_by_functions, rng);
  for (auto& f : out->spec["functions"]) {
    const std::string receptor = f["receptor"].get<std::string>(),
                      effector = f["effector"].get<std::string>();
    const auto r = joints.find(receptor), e = joints.find(effector);
    if (r == joints.end() || e == joints.end()) continue;  // the loader reports it
    const Affine q = effect_change(f["effect"]["type"].get<std::string>(), e->second, rng);
    vary_effect(f["effect"], q, s, rng);
    const auto shift = shifts.find(receptor);
    vary_mapping(f["mapping"], r->second, q, shift == shifts.end() ? 0.0 : shift->second, rng);
  }
  return true;
}

}  // namespace efc::synth::suite
