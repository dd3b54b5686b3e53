#include "synth/suite/generated_object.h"

#include "synth/suite/effector_parts.h"
#include "synth/suite/receptor_parts.h"
#include "synth/suite/template_params.h"

namespace efc::synth::suite {
namespace {

std::string function_name(const EffectorBuild& e, const std::string& effect) {
  if (effect == "temperature") return "heat";
  if (effect == "illumination") return "light";
  if (effect == "fluid") return "water";
  if (effect == "airflow") return "blow";
  if (e.kind == "ram") return "lift";
  if (e.kind == "tray") return "extend";
  return "open";
}

SpecJson function_json(const std::string& name, const std::string& receptor,
                       const std::string& effector, const SpecJson& mapping,
                       const SpecJson& effect) {
  return {{"name", name},
          {"receptor", receptor},
          {"effector", effector},
          {"mapping", mapping},
          {"effect", effect}};
}

// Fixed copies of the receptor below it, so "the knob" is not simply the one
// knob in view. Only for receptors that stay in place (not levers, sliders or
// drawers, which would sweep into them).
void add_decoys(const ReceptorBuild& r, SpecJson& parts, SuiteRng& rng) {
  const int count = rng.between(1, 2);
  const double pitch = r.reach + 0.015;
  for (int k = 1; k <= count; ++k) {
    if (r.b - k * pitch - r.reach / 2 < -0.95 * r.face.half_v) return;
    SpecJson decoy = {
        {"name", "decoy_" + std::to_string(k)},
        {"role", "other"},
        {"geometry", translated_geometry(r.part["geometry"], scale(r.face.v, -k * pitch))},
        {"rgba", r.part["rgba"]},
        {"joint", fixed_to_body()}};
    parts.push_back(decoy);
  }
}

// A second function on the same receptor: a small LED beside it that lights
// once the receptor passes a point (like examples/stove's hob lamp).
void add_indicator(const ReceptorBuild& r, SpecJson& parts, SpecJson& functions, SuiteRng& rng) {
  const Face& f = r.face;
  const double radius = mm(rng.uniform(0.003, 0.006));
  // Towards the middle of the face, beside the receptor; on the front it
  // must stay in the receptor's half.
  const double a = mm(r.a - f.receptor_side * (r.reach / 2 + 0.012 + radius));
  if (f.name == "front" && a - radius < 0.02) return;
  parts.push_back({{"name", "indicator_led"},
                   {"role", "effector"},
                   {"geometry", sphere_geometry(radius, f.at(a, r.b, 0))},
                   {"rgba", rgba(0.9, 0.9, 0.85)},
                   {"joint", fixed_to_body()}});
  const double on = snap(rng.uniform(1, 10), 10);
  const SpecJson effect = {
      {"type", "illumination"}, {"range", SpecJson::array({0, on})}, {"color", light_colour(rng)}};
  const std::string type = r.travel.continuous || rng.chance(0.5) ? "step" : "binary";
  functions.push_back(function_json("indicator", r.kind, "indicator_led",
                                    draw_mapping(type, r.travel, 0, on, rng), effect));
}

}  // namespace

GeneratedObject generate_object(const ObjectRequest& req, SuiteRng& rng) {
  const Body body = draw_body(rng);
  const SpecJson body_colour = appliance_colour(rng);
  // A quarter of the receptors are the body's colour: found by shape alone.
  const SpecJson receptor_colour = rng.chance(0.25) ? body_colour : control_colour(rng);
  const ReceptorBuild receptor =
      build_receptor(req.receptor_joint, req.small_receptor, body, receptor_colour, rng);
  const EffectorBuild effector = build_effector(req.effect, body, rng);

  GeneratedObject out;
  out.function = function_name(effector, req.effect);
  out.receptor = receptor.kind;
  out.effector = effector.kind;
  SpecJson parts =
      SpecJson::array({body_part(body, body_colour, rng), receptor.part, effector.part});
  SpecJson functions = SpecJson::array(
      {function_json(out.function, out.receptor, out.effector,
                     draw_mapping(req.mapping, receptor.travel, effector.off, effector.on, rng),
                     effector.effect)});
  if (!receptor.sweeps && rng.chance(0.3)) add_decoys(receptor, parts, rng);
  if (rng.chance(0.25)) add_indicator(receptor, parts, functions, rng);

  out.spec = {{"efc", 1},
              {"name", receptor.kind + "_" + effector.kind},
              {"description", "Generated: a " + receptor.kind + " on the " + receptor.face.name +
                                  " (" + req.receptor_joint + ") drives the " + effector.kind +
                                  " (" + req.mapping + " " + req.effect + ")."},
              {"parts", parts},
              {"functions", functions}};
  return out;
}

}  // namespace efc::synth::suite
