#include "synth/suite/effector_parts.h"

#include <algorithm>

namespace efc::synth::suite {
namespace {

// x kept inside [lo, hi]; lo wins when the interval is empty (a part wider
// than its room then sits at the inner edge rather than off the face).
double within(double x, double lo, double hi) { return std::max(lo, std::min(x, hi)); }

// A centre along u for something of half-width `half` in the left half of the
// front face (the receptor's half is the right one).
double left_half_a(const Face& f, double half, SuiteRng& rng) {
  return mm(-within(rng.uniform(0.25, 0.75) * f.half_u, half + 0.01, f.half_u - half - 0.01));
}

// A centre along v for something of half-height `half`, inside the face.
double face_b(const Face& f, double half, double lo, double hi, SuiteRng& rng) {
  const double room = f.half_v - half - 0.01;
  return mm(within(rng.uniform(lo, hi) * f.half_v, -room, room));
}

void set_range(EffectorBuild& e, double off, double on) {
  e.off = off;
  e.on = on;
  e.effect["range"] = SpecJson::array({off, on});
}

// ------------------------------------------------------------ temperature
void temperature(EffectorBuild& e, const Body& body, SuiteRng& rng) {
  const Face top = body.top();
  const double room = 0.4 * std::min(top.half_u, top.half_v);
  const bool burner = rng.chance(0.6);
  e.kind = burner ? "burner" : "pot";
  const double radius =
      mm(std::min(burner ? rng.uniform(0.05, 0.12) : rng.uniform(0.05, 0.1), room));
  const double height = mm(burner ? 0.01 : rng.uniform(0.06, 0.15));
  const double a = mm(-rng.uniform(0, 0.5) * (top.half_u - radius));
  const double b = mm(rng.uniform(-0.5, 0.5) * (top.half_v - radius));
  e.part["geometry"] = cylinder_geometry(radius, height, top.at(a, b, height / 2), {0, 0, 1});
  e.part["rgba"] = burner ? rgba(0.12, 0.12, 0.12) : rgba(0.7, 0.71, 0.73);
  e.effect = {{"type", "temperature"}};
  if (rng.chance(0.85)) {  // heats from room temperature
    set_range(e, 20, snap(rng.uniform(45, 260), 10));
  } else {  // a cooler: e_hi below e_lo
    const double room = snap(rng.uniform(20, 26), 10);
    set_range(e, room, snap(rng.uniform(4, 16), 10));
  }
  // Time constants that show within a demonstration (a press holds the
  // receptor on for a second or two): 0.5 to 3 s. Longer ones barely redden
  // the part in a 5 to 10 s clip and cannot be told from nothing.
  e.effect["time_constant"] = snap(rng.uniform(0.5, 3), 10);
  if (rng.chance(0.6))
    e.effect["position"] = json_vec(top.at(a, b, burner ? height : height / 2), 1e4);
}

// ------------------------------------------------------------ illumination
void illumination(EffectorBuild& e, const Body& body, SuiteRng& rng) {
  const Face front = body.front(), top = body.top();
  const double kind = rng.unit();
  e.effect = {{"type", "illumination"}};
  double on = 0;
  if (kind < 0.4) {
    e.kind = "lamp";
    const double bulb = mm(rng.uniform(0.025, 0.06));
    const double stem = mm(std::min(rng.uniform(0.05, 0.25), 1.18 - body.h - 2 * bulb));
    const double a = mm(-rng.uniform(0.2, 0.6) * top.half_u),
                 b = mm(rng.uniform(-0.3, 0.3) * top.half_v);
    e.part["geometry"] = compound_geometry(
        {cylinder_geometry(mm(rng.uniform(0.008, 0.015)), stem, top.at(a, b, stem / 2), {0, 0, 1}),
         sphere_geometry(bulb, top.at(a, b, stem + bulb))});
    e.effect["position"] =
        json_vec(top.at(a, b, stem + bulb), 1e4);  // the bulb, not the stem's middle
    on = rng.uniform(150, 1600);
  } else if (kind < 0.75) {
    e.kind = "led";
    const double radius = mm(rng.uniform(0.004, 0.012));
    const double a = left_half_a(front, radius, rng), b = face_b(front, radius, 0.2, 0.8, rng);
    e.part["geometry"] = sphere_geometry(radius, front.at(a, b, 0));  // half sunk in the face
    on = rng.uniform(2, 60);
  } else {
    e.kind = "panel";
    const double su = mm(std::min(rng.uniform(0.08, 0.3), 0.8 * front.half_u));
    const double sv = mm(std::min(rng.uniform(0.04, 0.12), 0.5 * front.half_v));
    const double a = left_half_a(front, su / 2, rng), b = face_b(front, sv / 2, 0.1, 0.7, rng);
    e.part["geometry"] = box_geometry(front.box_size(su, sv, 0.006), front.at(a, b, 0.003));
    on = rng.uniform(20, 300);
  }
  on = snap(on, 1);
  if (rng.chance(0.1))
    set_range(e, on, 0);  // actuating it switches the light off
  else
    set_range(e, 0, on);
  const SpecJson colour = light_colour(rng);
  e.effect["color"] = colour;
  e.part["rgba"] = rgba(0.6 + 0.4 * colour[0].get<double>(), 0.6 + 0.4 * colour[1].get<double>(),
                        0.6 + 0.4 * colour[2].get<double>());
}

// ------------------------------------------------------------ fluid
void fluid(EffectorBuild& e, const Body& body, SuiteRng& rng) {
  const Face front = body.front(), top = body.top();
  e.effect = {{"type", "fluid"}};
  V3 emitter, direction{0, 0, -1};
  if (rng.chance(0.6)) {  // a faucet: column on top, arm out over the front edge, nozzle down
    e.kind = "spout";
    const double column = mm(rng.uniform(0.08, 0.2)), rc = mm(rng.uniform(0.012, 0.02));
    const double arm = mm(rng.uniform(0.01, 0.014)), overhang = mm(rng.uniform(0.03, 0.1));
    const double a = mm(-rng.uniform(0.1, 0.5) * top.half_u),
                 b = mm(-rng.uniform(0.2, 0.5) * top.half_v);
    const V3 base = top.at(a, b, 0);
    const double y_end = -body.d / 2 - overhang, z_arm = body.h + column - arm;
    e.part["geometry"] = compound_geometry(
        {cylinder_geometry(rc, column, add(base, {0, 0, column / 2}), {0, 0, 1}),
         cylinder_geometry(arm, base[1] - y_end, {base[0], (base[1] + y_end) / 2, z_arm},
                           {0, 1, 0}),
         cylinder_geometry(mm(0.9 * arm), 0.03, {base[0], y_end, z_arm - 0.015}, {0, 0, 1})});
    emitter = {base[0], y_end, z_arm - 0.03};
  } else {  // a dispenser nozzle sticking out of the front
    e.kind = "nozzle";
    const double radius = mm(rng.uniform(0.006, 0.015)), length = mm(rng.uniform(0.02, 0.05));
    const double a = left_half_a(front, radius, rng), b = face_b(front, radius, 0, 0.6, rng);
    e.part["geometry"] = cylinder_geometry(radius, length, front.at(a, b, length / 2), front.n);
    emitter = front.at(a, b - radius, length);
    if (rng.chance(0.3)) direction = unit(add(scale(front.n, 0.35), {0, 0, -1}));
  }
  e.part["rgba"] = rgba(0.75, 0.76, 0.78);
  set_range(e, 0, snap(rng.uniform(0.5, 12), 100));
  e.effect["emitter"] = {{"position", json_vec(emitter, 1e4)}, {"direction", json_vec(direction)}};
  e.effect["speed"] = snap(rng.uniform(0.5, 2.5), 100);
  e.effect["droplet_radius"] = snap(rng.uniform(0.0015, 0.005), 1e4);
}

// ------------------------------------------------------------ airflow
void airflow(EffectorBuild& e, const Body& body, SuiteRng& rng) {
  const Face front = body.front(), top = body.top();
  e.effect = {{"type", "airflow"}};
  V3 outlet, direction;
  if (rng.chance(0.6)) {  // a round fan grille in front, blowing out (tilted up or down)
    e.kind = "grille";
    const double radius =
        mm(std::min({rng.uniform(0.04, 0.12), 0.45 * front.half_u - 0.01, 0.8 * front.half_v}));
    const double thickness = mm(rng.uniform(0.01, 0.02));
    const double a = left_half_a(front, radius, rng), b = face_b(front, radius, -0.3, 0.4, rng);
    e.part["geometry"] =
        cylinder_geometry(radius, thickness, front.at(a, b, thickness / 2), front.n);
    outlet = front.at(a, b, thickness);
    direction = unit(add(front.n, scale(front.v, rng.uniform(-0.5, 0.5))));
  } else {  // a vent on top, blowing up
    e.kind = "vent";
    const double su = mm(std::min(rng.uniform(0.1, 0.5), 1.6 * top.half_u - 0.02));
    const double sv = mm(std::min(rng.uniform(0.05, 0.3), 1.6 * top.half_v - 0.02));
    const double a =
        mm(-within(rng.uniform(0.05, 0.5) * top.half_u, 0, top.half_u - su / 2 - 0.01));
    e.part["geometry"] = box_geometry({su, sv, 0.01}, top.at(a, 0, 0.005));
    outlet = top.at(a, 0, 0.01);
    direction = unit({rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), 1});
  }
  e.part["rgba"] = rgba(0.3, 0.3, 0.32);
  const double speed = snap(rng.uniform(2, 12), 100);
  if (rng.chance(0.1))
    set_range(e, speed, 0);  // actuating it stops the air (a fridge door)
  else
    set_range(e, 0, speed);
  e.effect["outlet"] = {{"position", json_vec(outlet, 1e4)}, {"direction", json_vec(direction)}};
  e.effect["cone_angle"] = snap(rng.uniform(0.15, 0.6), 1e3);
  e.effect["reach"] = snap(rng.uniform(0.3, 2.5), 100);
}

// ------------------------------------------------------------ geometry
SpecJson hinge(const V3& axis, const V3& origin, double hi, SuiteRng& rng) {
  return {{"type", "revolute"},
          {"parent", "body"},
          {"axis", json_vec(axis)},
          {"origin", json_vec(origin, 1e4)},
          {"range", SpecJson::array({0, hi})},
          {"damping", snap(rng.uniform(0.02, 0.2), 1e3)}};
}

SpecJson slide(const V3& axis, double hi, SuiteRng& rng) {
  return {{"type", "prismatic"},
          {"parent", "body"},
          {"axis", json_vec(axis)},
          {"range", SpecJson::array({0, hi})},
          {"damping", snap(rng.uniform(1, 8), 100)}};
}

void geometry(EffectorBuild& e, const Body& body, SuiteRng& rng) {
  const Face front = body.front(), top = body.top();
  static const std::vector<std::string> kKinds = {"lid", "door", "tray", "ram", "flap"};
  e.kind = rng.pick(kKinds);
  double hi = 0;
  if (e.kind == "lid") {  // the whole top, hinged at the back, opening upwards
    const double t = mm(rng.uniform(0.012, 0.02));
    hi = snap(rng.uniform(1.0, 1.7), 1e4);
    e.part["geometry"] =
        box_geometry({mm(0.92 * body.w), mm(0.92 * body.d), t}, {0, 0, body.h + t / 2});
    e.part["mass"] = snap(rng.uniform(0.3, 1.5), 100);
    e.part["joint"] = hinge({-1, 0, 0}, {0, mm(0.46 * body.d), body.h + t / 2}, hi, rng);
  } else if (e.kind == "door") {  // the left of the front, hinged on its left edge
    const double width = mm(rng.uniform(0.35, 0.48) * body.w), t = mm(rng.uniform(0.015, 0.025));
    const double height = mm(rng.uniform(0.5, 0.85) * 2 * front.half_v);
    const double b = face_b(front, height / 2, -0.1, 0.1, rng);
    hi = snap(rng.uniform(1.2, 1.9), 1e4);
    e.part["geometry"] = box_geometry(front.box_size(width, height, t),
                                      front.at(-front.half_u + width / 2, b, t / 2));
    e.part["mass"] = snap(rng.uniform(0.5, 3), 100);
    e.part["joint"] = hinge({0, 0, -1}, front.at(-front.half_u, b, t / 2), hi, rng);
  } else if (e.kind == "tray") {  // pulls out of the lower left of the front
    const double width = mm(rng.uniform(0.5, 0.8) * front.half_u);
    const double height = mm(rng.uniform(0.5, 0.9) * front.half_v),
                 depth = mm(rng.uniform(0.5, 0.8) * body.d);
    const double a = mm(-0.5 * front.half_u), b = mm(-0.95 * front.half_v + height / 2);
    hi = snap(rng.uniform(0.4, 0.75) * depth, 1e4);
    e.part["geometry"] =
        compound_geometry({box_geometry(front.box_size(width, height, 0.02), front.at(a, b, 0.01)),
                           box_geometry(front.box_size(0.9 * width, 0.75 * height, depth),
                                        front.at(a, b, -depth / 2))});
    e.part["mass"] = snap(rng.uniform(0.5, 2.5), 100);
    e.part["joint"] = slide(front.n, hi, rng);
  } else if (e.kind == "ram") {  // rises out of the top
    const double radius =
        mm(std::min(rng.uniform(0.02, 0.06), 0.4 * std::min(top.half_u, top.half_v)));
    const double height = mm(rng.uniform(0.05, 0.15));
    const double a = mm(-rng.uniform(0.1, 0.5) * (top.half_u - radius));
    hi = snap(rng.uniform(0.04, 0.15), 1e4);
    e.part["geometry"] = compound_geometry(
        {cylinder_geometry(radius, height, top.at(a, 0, height / 2 - 0.01), {0, 0, 1}),
         cylinder_geometry(mm(1.2 * radius), 0.01, top.at(a, 0, height - 0.005), {0, 0, 1})});
    e.part["joint"] = slide({0, 0, 1}, hi, rng);
  } else {  // a louvre flap on the front, hinged at its top edge, swinging out
    const double su = mm(std::min(rng.uniform(0.15, 0.4) * body.w, 0.8 * front.half_u));
    const double sv = mm(std::min(rng.uniform(0.04, 0.1), front.half_v));
    const double a = left_half_a(front, su / 2, rng), b = face_b(front, sv / 2, 0, 0.6, rng);
    hi = snap(rng.uniform(0.5, 1.2), 1e4);
    e.part["geometry"] = box_geometry(front.box_size(su, sv, 0.006), front.at(a, b, 0.003));
    e.part["joint"] = hinge(scale(front.u, -1), front.at(a, b + sv / 2, 0.003), hi, rng);
  }
  e.part["rgba"] = appliance_colour(rng);
  e.effect = {{"type", "geometry"}};
  // Inside the joint's range: mostly [0, part of it]; sometimes from a
  // partly open rest; sometimes actuating it closes the part.
  double off = 0, on = snap(rng.uniform(0.6, 1.0) * hi, 1e4);
  if (rng.chance(0.2)) off = snap(rng.uniform(0.1, 0.3) * hi, 1e4);
  if (rng.chance(0.1)) std::swap(off, on);
  set_range(e, off, on);
}

}  // namespace

SpecJson light_colour(SuiteRng& rng) {
  static const std::vector<V3> kLeds = {{1, 0.2, 0.1}, {0.2, 1, 0.3}, {0.3, 0.5, 1}, {1, 0.6, 0.1}};
  const double kind = rng.unit();
  V3 c;
  if (kind < 0.45)
    c = {1, rng.uniform(0.8, 0.95), rng.uniform(0.55, 0.8)};  // warm white
  else if (kind < 0.75)
    c = {rng.uniform(0.85, 0.95), rng.uniform(0.92, 1), 1};  // cool white
  else
    c = rng.pick(kLeds);
  return json_vec(c, 1e3);
}

EffectorBuild build_effector(const std::string& effect, const Body& body, SuiteRng& rng) {
  EffectorBuild e;
  e.part = {{"name", ""}, {"role", "effector"}};
  if (effect == "temperature")
    temperature(e, body, rng);
  else if (effect == "illumination")
    illumination(e, body, rng);
  else if (effect == "fluid")
    fluid(e, body, rng);
  else if (effect == "airflow")
    airflow(e, body, rng);
  else
    geometry(e, body, rng);
  e.part["name"] = e.kind;
  if (!e.part.contains("joint")) e.part["joint"] = fixed_to_body();
  e.part = in_spec_order(e.part);
  return e;
}

}  // namespace efc::synth::suite
