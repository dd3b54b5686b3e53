// Effectors for generated objects, one family per effect, with the effect's
// fields (range, colour, position, emitter, outlet, ...) as the spec asks:
//   temperature   burner disc or pot on top
//   illumination  lamp (stem + bulb) on top, indicator LED or backlit panel in front
//   fluid         faucet spout over the front edge, or a dispenser nozzle in front
//   airflow       round fan grille in front, or a vent on top
//   geometry      lid on top, side-hinged door, pull-out tray, lift ram, louvre flap
// Front-mounted effectors use the left half of the front face (the receptor
// has the right half), so nothing overlaps.
#pragma once

#include <string>

#include "synth/suite/object_layout.h"

namespace efc::synth::suite {

struct EffectorBuild {
  SpecJson part;     // role effector; fixed to the body unless the effect is geometry
  SpecJson effect;   // the EFFECT object, "range" included
  std::string kind;  // burner, pot, lamp, led, panel, spout, nozzle, grille, vent, lid, door, tray,
                     // ram, flap
  double off = 0, on = 0;  // the effect's range [off, on]
};

EffectorBuild build_effector(const std::string& effect, const Body& body, SuiteRng& rng);

// A light's colour: warm white, cool white or a coloured LED.
SpecJson light_colour(SuiteRng& rng);

}  // namespace efc::synth::suite
