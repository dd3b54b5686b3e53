// The typed intermediate representation of an interactive object (spec v1).
//
// Plain structs, filled by a front-end (the JSON reader today, the DSL later),
// completed by resolve() (defaults, mass properties) and validated by check().
// Backends read a resolved, checked Object and never re-validate.
//
// Conventions (see shared/spec/efc-spec-v1.md): SI units, z-up, every position,
// axis and mesh vertex in the object frame at the reference configuration where
// every joint position is 0.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

namespace efc {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<std::array<double, 3>, 3>;

// Where a node came from: a JSON pointer into the document plus the line and
// column of its value in the file the user wrote (1-based; 0 = unknown).
struct SourceLoc {
  std::string pointer;  // e.g. "/parts/1/joint"
  int line = 0;
  int col = 0;
};

// `x-` keys of a JSON object, kept verbatim (ignored by the compiler, preserved
// for round trips).
using Extensions = std::map<std::string, nlohmann::json>;

// ---------------------------------------------------------------- geometry
enum class GeomKind { Mesh, Box, Cylinder, Sphere, Compound };

// A triangle mesh in the object frame, already scaled.
struct MeshData {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  bool closed = true;  // every edge shared by exactly two triangles
};

struct Geometry {
  GeomKind kind = GeomKind::Box;
  SourceLoc loc;
  // mesh
  std::string mesh_path;      // as written in the spec (relative to the spec)
  std::string mesh_resolved;  // absolute path on disk, filled by the reader
  Vec3 scale{1, 1, 1};
  std::optional<MeshData> mesh;  // loaded by resolve()
  // box
  Vec3 size{0, 0, 0};  // full edge lengths
  Vec3 rpy{0, 0, 0};
  // box, cylinder, sphere
  Vec3 center{0, 0, 0};
  // cylinder, sphere
  double radius = 0;
  // cylinder
  double length = 0;
  Vec3 axis{0, 0, 1};
  // compound
  std::vector<Geometry> children;
  Extensions extensions;
};

// Mass properties in the object frame.
struct MassProperties {
  double mass = 0;
  double volume = 0;
  Vec3 com{0, 0, 0};
  Mat3 inertia{};  // about com, object-frame axes
};

// ---------------------------------------------------------------- joints
enum class JointType { Fixed, Revolute, Continuous, Prismatic };

struct Spring {
  double stiffness = 0;
  double rest = 0;
  SourceLoc loc;
};

struct Joint {
  JointType type = JointType::Fixed;
  SourceLoc loc;
  std::string parent;
  int parent_index = -1;  // index into Object::parts, filled by check()
  Vec3 axis{0, 0, 1};     // unit after resolve()
  bool has_axis = false;
  Vec3 origin{0, 0, 0};
  bool has_origin = false;
  bool has_range = false;
  double lo = 0, hi = 0;
  std::optional<double> initial;  // resolve(): clamped into range
  double damping = 0;
  double friction = 0;
  std::optional<Spring> spring;
  Extensions extensions;

  bool movable() const { return type != JointType::Fixed; }
};

// ---------------------------------------------------------------- parts
enum class PartRole { Base, Receptor, Effector, Other };

struct Part {
  std::string name;
  SourceLoc loc;
  PartRole role = PartRole::Other;
  Geometry geometry;
  std::optional<double> mass;  // as given; resolve() fills mass_props
  std::optional<std::array<double, 4>> rgba;
  std::optional<Joint> joint;  // absent only on the root
  MassProperties mass_props;   // filled by resolve()
  Vec3 bbox_min{0, 0, 0}, bbox_max{0, 0, 0};  // object frame, filled by resolve()
  Extensions extensions;
};

// ---------------------------------------------------------------- functions
enum class MappingType { Binary, Step, Linear, Cumulative };

// Optional fields are absent when the spec omits them; resolve() fills every
// one that applies to the mapping type (and sets the *_defaulted flags so a
// dump shows which values came from a rule).
struct Mapping {
  MappingType type = MappingType::Binary;
  SourceLoc loc;
  std::optional<double> threshold;   // binary, step, cumulative
  std::optional<bool> latching;      // binary
  std::optional<double> hysteresis;  // step
  std::optional<double> gain;        // linear
  std::optional<double> offset;      // linear
  std::optional<double> delta;       // cumulative (required)
  std::optional<double> initial;     // cumulative
  std::vector<std::string> defaulted;  // names of fields filled by resolve()
  Extensions extensions;
};

enum class EffectType { Geometry, Illumination, Temperature, Fluid, Airflow };

struct Effect {
  EffectType type = EffectType::Geometry;
  SourceLoc loc;
  bool has_range = false;
  double lo = 0, hi = 0;  // [off, on]: e_lo at rest, e_hi fully actuated
  // geometry
  std::optional<double> stiffness, damping;
  // illumination
  std::optional<Vec3> color;
  // illumination, temperature (a point on the effector)
  std::optional<Vec3> position;
  // temperature
  std::optional<double> time_constant;
  // fluid: emitter; airflow: outlet
  std::optional<Vec3> direction;
  std::optional<double> speed, droplet_radius;
  // airflow
  std::optional<double> cone_angle, reach;
  std::vector<std::string> defaulted;
  Extensions extensions;
  // Extension objects inside "emitter"/"outlet" (kept for round trips).
  Extensions point_extensions;
};

struct Function {
  std::string name;
  SourceLoc loc;
  std::string receptor, effector;
  int receptor_index = -1, effector_index = -1;  // filled by check()
  Mapping mapping;
  Effect effect;
  Extensions extensions;
};

// Line and column (1-based) of a spec value, keyed by its JSON pointer; a
// key's position is under "key:" + pointer (frontend/positioned_json.h).
using SourcePositions = std::unordered_map<std::string, std::pair<int, int>>;

// ---------------------------------------------------------------- object
struct Object {
  std::string file;       // the spec file as the user named it
  std::string base_dir;   // folder that relative paths resolve against
  int version = 1;
  std::string name;
  SourceLoc loc;
  std::optional<std::string> description;
  std::vector<Part> parts;
  std::vector<Function> functions;
  Extensions extensions;
  // Every value's position, keyed by JSON pointer (for field-level diagnostics).
  // Only ever looked up, never walked in order: a hash map, so building it for
  // every value of the document stays cheap.
  SourcePositions positions;

  int find_part(const std::string& n) const {
    for (size_t i = 0; i < parts.size(); ++i)
      if (parts[i].name == n) return static_cast<int>(i);
    return -1;
  }
  int root_index() const {
    for (size_t i = 0; i < parts.size(); ++i)
      if (!parts[i].joint) return static_cast<int>(i);
    return -1;
  }
};

const char* to_string(GeomKind);
const char* to_string(JointType);
const char* to_string(PartRole);
const char* to_string(MappingType);
const char* to_string(EffectType);

}  // namespace efc
