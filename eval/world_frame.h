// Where a spec's object frame sits in the world: the "x-efc-object-to-world"
// extension (shared/spec/sequence.md, "Frames of inferred specs"), 16 numbers
// row-major, the identity when absent. efc eval maps both specs through it
// before comparing axes, origins and surfaces.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc::eval {

// x_world = rotation * x_object + translation (any invertible linear part is
// accepted: a scaled frame scales lengths too).
struct WorldFrame {
  Mat3 rotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Vec3 translation{0, 0, 0};

  Vec3 point(const Vec3& p) const;
  Vec3 direction(const Vec3& d) const;  // the linear part only, normalised
};

// Reads obj's transform. False, with a located error (E1020) in diags, when
// the value is not 16 finite numbers whose last row is 0 0 0 1 and whose
// linear part is invertible.
bool object_to_world(const Object& obj, Diagnostics& diags, WorldFrame* out);

// The 16 numbers themselves (the extension's value, or object_pose.json's
// "object_to_world"): false with *problem, worded after `subject` ("'key'
// element 3 is not a finite number"), and *pointer_suffix ("/3", "/12" or
// "") naming the element at fault.
bool read_transform(const nlohmann::json& value, const std::string& subject, WorldFrame* out,
                    std::string* problem, std::string* pointer_suffix);

}  // namespace efc::eval
