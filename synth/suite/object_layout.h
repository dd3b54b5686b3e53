// The layout every generated object shares: a box body standing on the floor
// (z >= 0), its front towards -y as in the examples, and the faces parts are
// mounted on. The receptor sits on the right half of the front face (or the
// front half of the right face); front-mounted effectors use the left half;
// the top carries the rest, so parts never overlap.
#pragma once

#include <initializer_list>
#include <string>

#include "synth/suite/spec_json.h"
#include "synth/suite/suite_rng.h"

namespace efc::synth::suite {

// A flat face of the body: centre, outward normal n, in-plane axes u (right,
// seen from outside) and v (up, or back on the top face), half-extents.
struct Face {
  std::string name;  // front, right, top
  V3 center, n, u, v;
  double half_u = 0, half_v = 0;
  // Which half of u the receptor uses (+1: +u half, -1: -u half).
  double receptor_side = 1;

  V3 at(double a, double b, double c) const {
    return add(center, add(scale(u, a), add(scale(v, b), scale(n, c))));
  }
  // An object-frame box size from sizes along u, v, n (faces are axis-aligned).
  V3 box_size(double su, double sv, double sn) const {
    V3 s;
    for (int k = 0; k < 3; ++k)
      s[k] = std::fabs(u[k]) * su + std::fabs(v[k]) * sv + std::fabs(n[k]) * sn;
    return s;
  }
};

struct Body {
  double w = 0, d = 0, h = 0;  // width (x), depth (y), height (z)
  double plinth = 0;           // an inset foot below the faces (0 = none)

  Face front() const;
  Face right() const;
  Face top() const;
};

Body draw_body(SuiteRng& rng);
SpecJson body_part(const Body& body, const SpecJson& rgba, SuiteRng& rng);

// ---- GEOMETRY values (centres always written, so parts can be moved).
SpecJson box_geometry(const V3& size, const V3& center);
SpecJson cylinder_geometry(double radius, double length, const V3& center, const V3& axis);
SpecJson sphere_geometry(double radius, const V3& center);
SpecJson compound_geometry(std::initializer_list<SpecJson> pieces);
// The same geometry moved by `offset` (primitives and compounds).
SpecJson translated_geometry(const SpecJson& geometry, const V3& offset);

// ---- colours
SpecJson rgba(double r, double g, double b);
SpecJson appliance_colour(SuiteRng& rng);  // white, steel, black, cream, ...
SpecJson control_colour(SuiteRng& rng);    // knobs and buttons

// The part's keys in the order the examples write them (name, role,
// geometry, mass, rgba, joint): the documents are read by people too.
SpecJson in_spec_order(const SpecJson& part);

// A fixed joint to the body.
SpecJson fixed_to_body();

// Lengths in metres on a 0.1 mm grid: below the renderer's depth resolution.
inline double mm(double x) { return snap(x, 1e4); }

}  // namespace efc::synth::suite
