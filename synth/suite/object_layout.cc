#include "synth/suite/object_layout.h"

#include <vector>

namespace efc::synth::suite {

Face Body::front() const {
  const double zc = plinth + (h - plinth) / 2;
  return {"front", {0, -d / 2, zc}, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}, w / 2, (h - plinth) / 2, 1};
}

// Seen from the right (+x), right is +y, i.e. towards the back: the receptor
// takes the -u half, nearer the camera.
Face Body::right() const {
  const double zc = plinth + (h - plinth) / 2;
  return {"right", {w / 2, 0, zc}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, d / 2, (h - plinth) / 2, -1};
}

Face Body::top() const {
  return {"top", {0, 0, h}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, w / 2, d / 2, 1};
}

Body draw_body(SuiteRng& rng) {
  // Multiples of 0.2 mm, so half-sizes and face centres lie on the 0.1 mm
  // grid too and the body's bottom is exactly at z = 0.
  auto even_mm = [](double x) { return snap(x, 5e3); };
  Body b;
  b.w = even_mm(rng.uniform(0.3, 0.9));
  b.d = even_mm(rng.uniform(0.22, 0.6));
  b.h = even_mm(rng.uniform(0.25, 0.85));
  if (rng.chance(0.4)) b.plinth = even_mm(rng.uniform(0.015, 0.05));
  return b;
}

SpecJson body_part(const Body& b, const SpecJson& colour, SuiteRng& rng) {
  const SpecJson shell =
      box_geometry({b.w, b.d, b.h - b.plinth}, {0, 0, b.plinth + (b.h - b.plinth) / 2});
  SpecJson geometry = shell;
  if (b.plinth > 0)
    geometry = compound_geometry(
        {shell, box_geometry({b.w - 0.04, b.d - 0.04, b.plinth}, {0, 0, b.plinth / 2})});
  // Appliances are hollow: 80-250 kg/m^3 of their box, not 500.
  const double mass = snap(b.w * b.d * b.h * rng.uniform(80, 250), 1e3);
  return {
      {"name", "body"}, {"role", "base"}, {"geometry", geometry}, {"mass", mass}, {"rgba", colour}};
}

SpecJson box_geometry(const V3& size, const V3& center) {
  return {{"box", {{"size", json_vec(size, 1e4)}, {"center", json_vec(center, 1e4)}}}};
}

SpecJson cylinder_geometry(double radius, double length, const V3& center, const V3& axis) {
  return {{"cylinder",
           {{"radius", mm(radius)},
            {"length", mm(length)},
            {"center", json_vec(center, 1e4)},
            {"axis", json_vec(axis)}}}};
}

SpecJson sphere_geometry(double radius, const V3& center) {
  return {{"sphere", {{"radius", mm(radius)}, {"center", json_vec(center, 1e4)}}}};
}

SpecJson compound_geometry(std::initializer_list<SpecJson> pieces) {
  SpecJson list = SpecJson::array();
  for (const auto& p : pieces) list.push_back(p);
  return {{"compound", list}};
}

SpecJson translated_geometry(const SpecJson& geometry, const V3& offset) {
  SpecJson g = geometry;
  if (g.contains("compound")) {
    for (auto& child : g["compound"]) child = translated_geometry(child, offset);
    return g;
  }
  for (const char* kind : {"box", "cylinder", "sphere"}) {
    if (!g.contains(kind)) continue;
    V3 c{0, 0, 0};
    read_vec(g[kind]["center"], &c);
    g[kind]["center"] = json_vec(add(c, offset), 1e4);
  }
  return g;
}

SpecJson rgba(double r, double g, double b) {
  return SpecJson::array({snap(r, 1e3), snap(g, 1e3), snap(b, 1e3), 1});
}

SpecJson appliance_colour(SuiteRng& rng) {
  static const std::vector<V3> kColours = {
      {0.95, 0.95, 0.95}, {0.75, 0.76, 0.78}, {0.1, 0.1, 0.1},  {0.9, 0.87, 0.78},
      {0.75, 0.12, 0.1},  {0.35, 0.42, 0.5},  {0.7, 0.55, 0.4}, {0.55, 0.7, 0.6}};
  const V3& c = rng.pick(kColours);
  return rgba(c[0], c[1], c[2]);
}

SpecJson control_colour(SuiteRng& rng) {
  static const std::vector<V3> kColours = {{0.1, 0.1, 0.1}, {0.6, 0.6, 0.62}, {0.95, 0.95, 0.95},
                                           {0.8, 0.1, 0.1}, {0.2, 0.4, 0.8},  {0.9, 0.7, 0.1}};
  const V3& c = rng.pick(kColours);
  return rgba(c[0], c[1], c[2]);
}

SpecJson in_spec_order(const SpecJson& part) {
  SpecJson out = SpecJson::object();
  for (const char* key : {"name", "role", "geometry", "mass", "rgba", "joint"})
    if (part.contains(key)) out[key] = part[key];
  return out;
}

SpecJson fixed_to_body() { return {{"type", "fixed"}, {"parent", "body"}}; }

}  // namespace efc::synth::suite
