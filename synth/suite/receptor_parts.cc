#include "synth/suite/receptor_parts.h"

#include <algorithm>

namespace efc::synth::suite {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Centre of a receptor of size `reach` on the receptor's half of the face,
// in its upper half, clear of the face's edges and of the other half.
void place(ReceptorBuild& r, SuiteRng& rng) {
  const Face& f = r.face;
  const double margin = r.reach / 2 + 0.01;
  const double a = std::clamp(rng.uniform(0.45, 0.7) * f.half_u, margin, f.half_u - margin);
  r.a = mm(f.receptor_side * a);
  r.b = mm(std::min(rng.uniform(0.05, 0.5) * f.half_v, f.half_v - margin));
}

SpecJson revolute_joint(const V3& axis, const V3& origin, double lo, double hi) {
  return {{"type", "revolute"},
          {"parent", "body"},
          {"axis", json_vec(axis)},
          {"origin", json_vec(origin, 1e4)},
          {"range", SpecJson::array({lo, hi})}};
}

// A cylinder with a pointer ridge on its outer face (knob, dial).
SpecJson pointer_knob(const ReceptorBuild& r, double radius, double length) {
  const Face& f = r.face;
  return compound_geometry({cylinder_geometry(radius, length, f.at(r.a, r.b, length / 2), f.n),
                            box_geometry(f.box_size(0.22 * radius, 0.85 * radius, 0.004),
                                         f.at(r.a, r.b + 0.45 * radius, length + 0.002))});
}

// Turned about the face normal, either way round.
V3 turn_axis(const Face& f, SuiteRng& rng) { return rng.chance(0.3) ? scale(f.n, -1) : f.n; }

void knob(ReceptorBuild& r, bool small, SuiteRng& rng) {
  const Face& f = r.face;
  const double radius =
      mm(small ? rng.uniform(0.01, 0.025)
               : std::min(rng.uniform(0.028, 0.05), 0.3 * std::min(f.half_u, f.half_v)));
  const double length = mm(rng.uniform(0.015, 0.03));
  r.reach = 2 * radius;
  place(r, rng);
  // Mostly off at 0 and turned one way; sometimes a short range, sometimes a
  // stop below 0 (the drawn pose is then not the lower limit).
  double lo = 0, hi = snap(rng.uniform(2.5, 5.2), 1e4);
  const double kind = rng.unit();
  if (kind < 0.2)
    hi = snap(rng.uniform(1.2, 2.4), 1e4);
  else if (kind < 0.35)
    lo = -snap(rng.uniform(0.3, 0.8), 1e4);
  r.part["geometry"] = pointer_knob(r, radius, length);
  SpecJson joint = revolute_joint(turn_axis(f, rng), f.at(r.a, r.b, 0), lo, hi);
  joint["damping"] = snap(rng.uniform(0.005, 0.02), 1e4);
  joint["friction"] = snap(rng.uniform(0.005, 0.03), 1e4);
  r.part["joint"] = joint;
  r.travel = {false, lo, hi, false};
}

// A small rocker switch pivoting about its middle: the top swings out.
void rocker(ReceptorBuild& r, SuiteRng& rng) {
  const Face& f = r.face;
  const double su = mm(rng.uniform(0.012, 0.02)), sv = mm(rng.uniform(0.02, 0.035)),
               sn = mm(rng.uniform(0.008, 0.014));
  r.reach = sv;
  place(r, rng);
  const double hi = snap(rng.uniform(0.25, 0.4), 1e4);
  r.part["geometry"] = box_geometry(f.box_size(su, sv, sn), f.at(r.a, r.b, sn / 2));
  SpecJson joint = revolute_joint(f.u, f.at(r.a, r.b, 0), 0, hi);
  joint["friction"] = snap(rng.uniform(0.01, 0.05), 1e4);
  r.part["joint"] = joint;
  r.travel = {false, 0, hi, false};
}

// A lever sticking out of the face, pulled down (or pushed up) about a
// horizontal hinge at its hub.
void lever(ReceptorBuild& r, SuiteRng& rng) {
  const Face& f = r.face;
  const double hub = mm(rng.uniform(0.01, 0.016)), length = mm(rng.uniform(0.07, 0.14));
  const double su = mm(rng.uniform(0.015, 0.025)), sv = mm(rng.uniform(0.012, 0.02));
  r.reach = 2 * hub;
  r.sweeps = true;
  place(r, rng);
  const double hi = snap(rng.uniform(0.5, 1.1), 1e4);
  r.part["geometry"] = compound_geometry(
      {cylinder_geometry(hub, 0.02, f.at(r.a, r.b, 0.01), f.n),
       box_geometry(f.box_size(su, sv, length), f.at(r.a, r.b, 0.02 + length / 2))});
  // Turning about +u takes the outward bar towards -v (down).
  const V3 axis = rng.chance(0.7) ? f.u : scale(f.u, -1);
  SpecJson joint = revolute_joint(axis, f.at(r.a, r.b, 0.01), 0, hi);
  joint["friction"] = snap(rng.uniform(0.02, 0.1), 1e4);
  if (rng.chance(0.4))
    joint["spring"] = {{"stiffness", snap(rng.uniform(0.3, 2), 1e3)}, {"rest", 0}};
  r.part["joint"] = joint;
  r.travel = {false, 0, hi, false};
}

void button(ReceptorBuild& r, bool small, SuiteRng& rng) {
  const Face& f = r.face;
  const double depth = mm(rng.uniform(0.006, 0.012));
  const bool round = !small || rng.chance(0.5);
  // Small: 1-2 cm; otherwise a palm button of 5.4-7 cm.
  const double size = mm(small ? rng.uniform(0.01, 0.02) : rng.uniform(0.054, 0.07));
  r.reach = size;
  place(r, rng);
  r.part["geometry"] = round
                           ? cylinder_geometry(size / 2, depth, f.at(r.a, r.b, depth / 2), f.n)
                           : box_geometry(f.box_size(size, mm(size * rng.uniform(0.8, 1.2)), depth),
                                          f.at(r.a, r.b, depth / 2));
  const double travel = snap(small ? rng.uniform(0.002, 0.006) : rng.uniform(0.004, 0.012), 1e5);
  r.part["joint"] = {{"type", "prismatic"},
                     {"parent", "body"},
                     {"axis", json_vec(scale(f.n, -1))},
                     {"range", SpecJson::array({0, travel})},
                     {"spring", {{"stiffness", snap(rng.uniform(60, 300), 1)}, {"rest", 0}}}};
  r.travel = {false, 0, travel, true};
}

// A small slider knob moving along the face, outwards in its half or up.
void slider(ReceptorBuild& r, SuiteRng& rng) {
  const Face& f = r.face;
  const double su = mm(rng.uniform(0.012, 0.02)), sv = mm(rng.uniform(0.015, 0.025)),
               sn = mm(rng.uniform(0.008, 0.014));
  const bool vertical = rng.chance(0.4);
  const double room = vertical ? f.half_v : f.half_u;
  const double travel = snap(std::min(rng.uniform(0.03, 0.1), 0.55 * room), 1e4);
  r.reach = std::max(su, sv);
  r.sweeps = true;
  place(r, rng);
  if (vertical)
    r.b = mm(-0.3 * f.half_v);
  else
    r.a = mm(f.receptor_side * 0.3 * f.half_u);
  const V3 axis = vertical ? f.v : scale(f.u, f.receptor_side);
  r.part["geometry"] = box_geometry(f.box_size(su, sv, sn), f.at(r.a, r.b, sn / 2));
  r.part["joint"] = {{"type", "prismatic"},
                     {"parent", "body"},
                     {"axis", json_vec(axis)},
                     {"range", SpecJson::array({0, travel})},
                     {"friction", snap(rng.uniform(0.1, 0.6), 1e3)}};
  r.travel = {false, 0, travel, false};
}

// A drawer in the lower part of the receptor's half: front panel, pull and
// the box behind it (inside the body, like examples/kitchen_drawer).
void drawer(ReceptorBuild& r, const Body& body, SuiteRng& rng) {
  const Face& f = r.face;
  const double width = mm(rng.uniform(0.5, 0.8) * f.half_u);
  const double height = mm(rng.uniform(0.5, 0.9) * f.half_v);
  const double depth = mm(rng.uniform(0.5, 0.8) * body.d);
  r.reach = std::max(width, height);
  r.sweeps = true;
  r.a = mm(f.receptor_side * 0.5 * f.half_u);
  r.b = mm(-0.95 * f.half_v + height / 2);
  r.part["geometry"] = compound_geometry(
      {box_geometry(f.box_size(width, height, 0.02), f.at(r.a, r.b, 0.01)),
       box_geometry(f.box_size(0.4 * width, 0.015, 0.015), f.at(r.a, r.b + 0.25 * height, 0.0275)),
       box_geometry(f.box_size(0.9 * width, 0.75 * height, depth), f.at(r.a, r.b, -depth / 2))});
  r.part["mass"] = snap(rng.uniform(0.8, 3), 1e2);
  const double travel = snap(rng.uniform(0.4, 0.75) * depth, 1e4);
  r.part["joint"] = {{"type", "prismatic"},
                     {"parent", "body"},
                     {"axis", json_vec(f.n)},
                     {"range", SpecJson::array({0, travel})},
                     {"damping", snap(rng.uniform(2, 10), 1e2)},
                     {"friction", snap(rng.uniform(0.3, 1.5), 1e2)}};
  r.travel = {false, 0, travel, false};
}

SpecJson continuous_joint(const V3& axis, const V3& origin, SuiteRng& rng) {
  return {{"type", "continuous"},
          {"parent", "body"},
          {"axis", json_vec(axis)},
          {"origin", json_vec(origin, 1e4)},
          {"friction", snap(rng.uniform(0.005, 0.08), 1e4)}};
}

// A small endless encoder dial.
void dial(ReceptorBuild& r, SuiteRng& rng) {
  const Face& f = r.face;
  const double radius = mm(rng.uniform(0.012, 0.025)), length = mm(rng.uniform(0.012, 0.025));
  r.reach = 2 * radius;
  place(r, rng);
  r.part["geometry"] = pointer_knob(r, radius, length);
  r.part["joint"] = continuous_joint(turn_axis(f, rng), f.at(r.a, r.b, 0), rng);
  r.travel = {true, 0, kTwoPi, false};
}

// A hand-wheel with a crank peg near its rim.
void crank(ReceptorBuild& r, SuiteRng& rng) {
  const Face& f = r.face;
  const double radius = mm(std::min(rng.uniform(0.035, 0.06), 0.35 * std::min(f.half_u, f.half_v)));
  const double thickness = mm(rng.uniform(0.01, 0.018));
  const double peg = mm(rng.uniform(0.025, 0.045));
  r.reach = 2 * radius;
  place(r, rng);
  r.part["geometry"] = compound_geometry(
      {cylinder_geometry(radius, thickness, f.at(r.a, r.b, thickness / 2), f.n),
       cylinder_geometry(mm(rng.uniform(0.006, 0.01)), peg,
                         f.at(r.a, r.b + 0.7 * radius, thickness + peg / 2), f.n)});
  r.part["joint"] = continuous_joint(turn_axis(f, rng), f.at(r.a, r.b, 0), rng);
  r.travel = {true, 0, kTwoPi, false};
}

}  // namespace

ReceptorBuild build_receptor(const std::string& joint_type, bool small, const Body& body,
                             const SpecJson& colour, SuiteRng& rng) {
  ReceptorBuild r;
  if (joint_type == "revolute")
    r.kind = small ? (rng.chance(0.6) ? "knob" : "rocker") : (rng.chance(0.5) ? "knob" : "lever");
  else if (joint_type == "prismatic")
    r.kind =
        small ? (rng.chance(0.6) ? "button" : "slider") : (rng.chance(0.6) ? "button" : "drawer");
  else
    r.kind = small ? "dial" : "crank";
  // Mostly on the front; sometimes on the right side, seen at an angle.
  r.face = r.kind != "drawer" && rng.chance(0.2) ? body.right() : body.front();
  r.part = {{"name", r.kind}, {"role", "receptor"}};
  if (r.kind == "knob")
    knob(r, small, rng);
  else if (r.kind == "rocker")
    rocker(r, rng);
  else if (r.kind == "lever")
    lever(r, rng);
  else if (r.kind == "button")
    button(r, small, rng);
  else if (r.kind == "slider")
    slider(r, rng);
  else if (r.kind == "drawer")
    drawer(r, body, rng);
  else if (r.kind == "dial")
    dial(r, rng);
  else
    crank(r, rng);
  r.part["rgba"] = colour;
  r.part = in_spec_order(r.part);
  return r;
}

}  // namespace efc::synth::suite
