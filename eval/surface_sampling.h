// Points spread uniformly over a part's surface (area-weighted), for the
// Chamfer distance. Deterministic: the same geometry, count and seed give the
// same points on every machine (our own generator and conversions, not the
// standard library's distributions, whose output is implementation-defined).
#pragma once

#include <cstdint>
#include <vector>

#include "compiler/ir.h"

namespace efc::eval {

// `count` points on the surface of g in the object frame (meshes already
// loaded and scaled by resolve(); boxes, cylinders and spheres exactly, not
// tessellated; compounds by their children's areas). Empty when g has no
// surface (an unloaded mesh, an empty compound).
std::vector<Vec3> sample_surface(const Geometry& g, int count, uint64_t seed);

}  // namespace efc::eval
