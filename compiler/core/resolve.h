// Fills every default the spec defines, so later stages see explicit values:
// mapping parameters (thresholds, hysteresis, gain, offset, ...), effect
// ranges and realisation parameters (light position at the effector's
// bounding-box centre, EgoFun3D's emitter rule, ...), joint axes normalised,
// initial positions clamped, meshes loaded, mass and inertia from geometry.
// Runs after check_structure() (references are valid) and before check_resolved().
#pragma once

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

void resolve(Object& obj, Diagnostics& diags);

// Receptor range used by mappings: the joint's [lo, hi], or [0, 2 pi] for a
// continuous joint.
void receptor_range(const Object& obj, const Function& f, double* lo, double* hi);

}  // namespace efc
