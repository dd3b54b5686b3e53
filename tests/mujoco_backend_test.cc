// The MuJoCo target and the MuJoCo binding of the runtime: the MJCF loads in
// MuJoCo 2.2.2 without a warning, its kinematic tree and meshes match the
// spec, the Controller realises every effect, and the generated callbacks
// compile on their own and reproduce the in-process controller exactly.
//
// The IR is built by hand, resolved as resolve() would leave it (defaults,
// mass properties, bounding boxes), so these tests do not depend on the
// reader; example files are covered by the harness tests.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/mujoco/mujoco_backend.h"
#include "compiler/core/load.h"
#include "compiler/ir.h"
#include "runtime/mujoco/efc_mujoco.h"
#include "tests/process_temp_dir.h"


namespace efc_test {

using efc::Vec3;

inline std::vector<std::string>& mj_warnings() {
  static std::vector<std::string> w;
  return w;
}
inline void record_warning(const char* msg) { mj_warnings().push_back(msg); }
inline void fatal_error(const char* msg) {
  std::fprintf(stderr, "MuJoCo error: %s\n", msg);
  std::abort();
}
inline void install_mujoco_handlers() {
  mju_user_error = fatal_error;
  mju_user_warning = record_warning;
  mj_warnings().clear();
}

inline std::string temp_dir(const std::string& tag) {
  namespace fs = std::filesystem;
  static const efc_test::ProcessTempDir root("efc_mujoco_");
  const fs::path p = root.path() / tag;
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

inline efc::Part box_part(const std::string& name, const Vec3& size, const Vec3& center, double mass) {
  efc::Part p;
  p.name = name;
  p.geometry.kind = efc::GeomKind::Box;
  p.geometry.size = size;
  p.geometry.center = center;
  p.mass = mass;
  p.mass_props.mass = mass;
  p.mass_props.volume = size[0] * size[1] * size[2];
  p.mass_props.com = center;
  const double x = size[0], y = size[1], z = size[2];
  p.mass_props.inertia = {{{mass / 12 * (y * y + z * z), 0, 0},
                           {0, mass / 12 * (x * x + z * z), 0},
                           {0, 0, mass / 12 * (x * x + y * y)}}};
  for (int k = 0; k < 3; ++k) {
    p.bbox_min[k] = center[k] - size[k] / 2;
    p.bbox_max[k] = center[k] + size[k] / 2;
  }
  return p;
}

inline efc::Part sphere_part(const std::string& name, double r, const Vec3& center, double mass) {
  efc::Part p;
  p.name = name;
  p.geometry.kind = efc::GeomKind::Sphere;
  p.geometry.radius = r;
  p.geometry.center = center;
  p.mass = mass;
  p.mass_props.mass = mass;
  p.mass_props.volume = 4.0 / 3.0 * M_PI * r * r * r;
  p.mass_props.com = center;
  const double i = 0.4 * mass * r * r;
  p.mass_props.inertia = {{{i, 0, 0}, {0, i, 0}, {0, 0, i}}};
  for (int k = 0; k < 3; ++k) {
    p.bbox_min[k] = center[k] - r;
    p.bbox_max[k] = center[k] + r;
  }
  return p;
}

// A z-axis cylinder.
inline efc::Part cylinder_part(const std::string& name, double r, double len, const Vec3& center,
                               double mass) {
  efc::Part p;
  p.name = name;
  p.geometry.kind = efc::GeomKind::Cylinder;
  p.geometry.radius = r;
  p.geometry.length = len;
  p.geometry.center = center;
  p.geometry.axis = {0, 0, 1};
  p.mass = mass;
  p.mass_props.mass = mass;
  p.mass_props.com = center;
  const double ixx = mass * (3 * r * r + len * len) / 12;
  p.mass_props.inertia = {{{ixx, 0, 0}, {0, ixx, 0}, {0, 0, mass * r * r / 2}}};
  p.bbox_min = {center[0] - r, center[1] - r, center[2] - len / 2};
  p.bbox_max = {center[0] + r, center[1] + r, center[2] + len / 2};
  return p;
}

inline efc::Joint joint(efc::JointType type, const std::string& parent, int parent_index,
                        const Vec3& axis, const Vec3& origin, double lo, double hi) {
  efc::Joint j;
  j.type = type;
  j.parent = parent;
  j.parent_index = parent_index;
  j.axis = axis;
  j.has_axis = type != efc::JointType::Fixed;
  j.origin = origin;
  j.has_origin = true;
  j.has_range = type == efc::JointType::Revolute || type == efc::JointType::Prismatic;
  j.lo = lo;
  j.hi = hi;
  j.initial = type == efc::JointType::Continuous ? 0.0 : std::fmin(std::fmax(0.0, lo), hi);
  return j;
}

inline efc::Function function(const efc::Object& o, const std::string& name, const std::string& rec,
                              const std::string& eff, efc::MappingType mt, efc::EffectType et,
                              double e_lo, double e_hi) {
  efc::Function f;
  f.name = name;
  f.receptor = rec;
  f.effector = eff;
  f.receptor_index = o.find_part(rec);
  f.effector_index = o.find_part(eff);
  f.mapping.type = mt;
  f.effect.type = et;
  f.effect.has_range = true;
  f.effect.lo = e_lo;
  f.effect.hi = e_hi;
  // resolve() fills every optional that applies; these are the spec defaults
  // for the receptor range.
  const efc::Joint& j = *o.parts[f.receptor_index].joint;
  const double r_lo = j.type == efc::JointType::Continuous ? 0 : j.lo;
  const double r_hi = j.type == efc::JointType::Continuous ? 2 * M_PI : j.hi;
  switch (mt) {
    case efc::MappingType::Binary:
      f.mapping.threshold = (r_lo + r_hi) / 2;
      f.mapping.latching = false;
      break;
    case efc::MappingType::Step:
      f.mapping.threshold = r_lo + 0.7 * (r_hi - r_lo);
      f.mapping.hysteresis = 0.02 * (r_hi - r_lo);
      break;
    case efc::MappingType::Linear:
      f.mapping.gain = (e_hi - e_lo) / (r_hi - r_lo);
      f.mapping.offset = e_lo;
      break;
    case efc::MappingType::Cumulative:
      f.mapping.threshold = (r_lo + r_hi) / 2;
      f.mapping.delta = (e_hi - e_lo) / 4;
      f.mapping.initial = e_lo;
      break;
  }
  const efc::Part& p = o.parts[f.effector_index];
  const Vec3 centre{(p.bbox_min[0] + p.bbox_max[0]) / 2, (p.bbox_min[1] + p.bbox_max[1]) / 2,
                    (p.bbox_min[2] + p.bbox_max[2]) / 2};
  switch (et) {
    case efc::EffectType::Geometry:
      break;
    case efc::EffectType::Illumination:
      f.effect.color = Vec3{1.0, 0.9, 0.8};
      f.effect.position = centre;
      break;
    case efc::EffectType::Temperature:
      f.effect.time_constant = 30.0;
      f.effect.position = centre;
      break;
    case efc::EffectType::Fluid:
      f.effect.position = Vec3{centre[0], centre[1], p.bbox_min[2]};
      f.effect.direction = Vec3{0, 0, -1};
      f.effect.speed = 1.0;
      f.effect.droplet_radius = 0.004;
      break;
    case efc::EffectType::Airflow:
      f.effect.position = centre;
      f.effect.direction = Vec3{1, 0, 0};
      f.effect.cone_angle = 0.35;
      f.effect.reach = 0.6;
      break;
  }
  return f;
}

// Every effect type, a chain (door opened by the lever drives the lamp) and
// every joint type:
//   base (root box)
//   lever   revolute about +y at (0.1, 0, 0.06)      -> door (geometry), fan (airflow)
//   door    revolute about +z at (-0.1, 0.1, 0.05), with a spring -> bulb (illumination)
//   button  prismatic along -z, spring               -> spout (fluid, step)
//   knob    continuous about +z                       -> plate (temperature)
//   bulb, spout, plate, fan: fixed effectors
inline efc::Object make_test_object() {
  using efc::JointType;
  efc::Object o;
  o.name = "testobj";
  o.description = std::string("hand-built test object <all effects> & a \"chain\" -- ok");
  o.parts.push_back(box_part("base", {0.3, 0.3, 0.05}, {0, 0, 0.025}, 2.0));
  o.parts[0].role = efc::PartRole::Base;
  auto add = [&](efc::Part p, efc::Joint j) {
    p.joint = j;
    o.parts.push_back(p);
  };
  add(box_part("lever", {0.1, 0.02, 0.02}, {0.15, 0, 0.06}, 0.05),
      joint(JointType::Revolute, "base", 0, {0, 1, 0}, {0.1, 0, 0.06}, 0.0, 1.0));
  efc::Part door = box_part("door", {0.1, 0.01, 0.2}, {-0.05, 0.1, 0.15}, 0.3);
  door.rgba = std::array<double, 4>{0.2, 0.4, 0.8, 1.0};
  efc::Joint dj = joint(JointType::Revolute, "base", 0, {0, 0, 1}, {-0.1, 0.1, 0.05}, 0.0, 1.5);
  dj.spring = efc::Spring{0.5, 0.0, {}};
  dj.damping = 0.01;
  dj.friction = 0.001;
  add(door, dj);
  efc::Joint bj = joint(JointType::Prismatic, "base", 0, {0, 0, -1}, {0, 0, 0}, 0.0, 0.01);
  bj.spring = efc::Spring{50.0, 0.0, {}};
  add(box_part("button", {0.02, 0.02, 0.01}, {-0.1, -0.1, 0.055}, 0.01), bj);
  add(cylinder_part("knob", 0.02, 0.02, {0.1, -0.1, 0.06}, 0.02),
      joint(JointType::Continuous, "base", 0, {0, 0, 1}, {0.1, -0.1, 0.05}, 0, 0));
  add(sphere_part("bulb", 0.03, {0, 0, 0.35}, 0.05),
      joint(JointType::Fixed, "base", 0, {0, 0, 1}, {0, 0, 0}, 0, 0));
  add(cylinder_part("spout", 0.01, 0.1, {0.0, -0.1, 0.25}, 0.05),
      joint(JointType::Fixed, "base", 0, {0, 0, 1}, {0, 0, 0}, 0, 0));
  add(box_part("plate", {0.08, 0.08, 0.005}, {0.08, 0.08, 0.0525}, 0.1),
      joint(JointType::Fixed, "base", 0, {0, 0, 1}, {0, 0, 0}, 0, 0));
  add(box_part("fan", {0.02, 0.05, 0.05}, {0.14, 0, 0.3}, 0.1),
      joint(JointType::Fixed, "base", 0, {0, 0, 1}, {0, 0, 0}, 0, 0));
  using efc::EffectType;
  using efc::MappingType;
  // Spec order puts the chain's dependent first: build_bindings must reorder.
  o.functions.push_back(function(o, "lamp", "door", "bulb", MappingType::Linear,
                                 EffectType::Illumination, 0, 800));
  o.functions.push_back(function(o, "open", "lever", "door", MappingType::Linear,
                                 EffectType::Geometry, 0.0, 1.2));
  o.functions.push_back(function(o, "water", "button", "spout", MappingType::Step,
                                 EffectType::Fluid, 0, 6));
  efc::Function heat = function(o, "heat", "knob", "plate", MappingType::Linear,
                                EffectType::Temperature, 20, 250);
  heat.effect.time_constant = 0.5;
  o.functions.push_back(heat);
  efc::Function fan = function(o, "breeze", "lever", "fan", MappingType::Binary,
                               EffectType::Airflow, 0, 10);
  fan.effect.position = Vec3{0.15, 0, 0.3};
  o.functions.push_back(fan);
  return o;
}

}  // namespace efc_test

namespace {

using efc_test::install_mujoco_handlers;
using efc_test::mj_warnings;

struct Loaded {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  ~Loaded() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

// Writes the model (and meshes) into a fresh folder and loads it, failing the
// test on any load message or recorded warning.
// With `existing_xml`, loads that file instead of writing a new one.
void load_object(const efc::Object& obj, bool drive_receptors, const std::string& tag, Loaded* out,
                 const std::string& extra_body = "", const std::string& existing_xml = "") {
  install_mujoco_handlers();
  std::string xml_path = existing_xml;
  if (xml_path.empty()) {
    const std::string dir = efc_test::temp_dir(tag);
    efc::MjcfOptions opt;
    opt.drive_receptors = drive_receptors;
    efc::Diagnostics diags;
    ASSERT_TRUE(efc::write_mujoco_model(obj, dir, opt, diags, &xml_path));
    ASSERT_FALSE(diags.has_errors());
  }
  if (!extra_body.empty()) {
    std::ifstream in(xml_path);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string xml = ss.str();
    const size_t at = xml.find("  </worldbody>");
    xml.insert(at, extra_body);
    // The extra body's free joint adds 7 qpos the keyframe does not have.
    const size_t key = xml.find("<key name=\"initial\"");
    xml.erase(key, xml.find("/>", key) + 2 - key);
    std::ofstream(xml_path) << xml;
  }
  char error[1000] = "";
  out->m = mj_loadXML(xml_path.c_str(), nullptr, error, sizeof error);
  ASSERT_NE(out->m, nullptr) << error;
  EXPECT_STREQ(error, "") << "load message (a warning) from MuJoCo";
  EXPECT_TRUE(mj_warnings().empty()) << mj_warnings().front();
  out->d = mj_makeData(out->m);
  const int key = mj_name2id(out->m, mjOBJ_KEY, "initial");
  if (key >= 0) mj_resetDataKeyframe(out->m, out->d, key);
  mj_forward(out->m, out->d);
}

void expect_no_runtime_warnings(const mjData* d) {
  EXPECT_TRUE(mj_warnings().empty()) << mj_warnings().front();
  for (int w = 0; w < mjNWARNING; ++w) EXPECT_EQ(d->warning[w].number, 0) << "warning " << w;
}

int qadr(const mjModel* m, const char* joint) {
  const int j = mj_name2id(m, mjOBJ_JOINT, joint);
  EXPECT_GE(j, 0) << joint;
  return j >= 0 ? m->jnt_qposadr[j] : 0;
}
int vadr(const mjModel* m, const char* joint) {
  const int j = mj_name2id(m, mjOBJ_JOINT, joint);
  return j >= 0 ? m->jnt_dofadr[j] : 0;
}
int actuator(const mjModel* m, const char* name) {
  const int a = mj_name2id(m, mjOBJ_ACTUATOR, name);
  EXPECT_GE(a, 0) << name;
  return a;
}
int row_of(const efc_mj::Controller& c, const std::string& name) {
  for (int i = 0; i < c.count(); ++i)
    if (name == c.binding(i).name) return i;
  ADD_FAILURE() << "no function " << name;
  return 0;
}

// Geom world position of body `body`'s first geom.
efc::Vec3 geom_world(const mjModel* m, const mjData* d, const char* body) {
  const int b = mj_name2id(m, mjOBJ_BODY, body);
  const int g = m->body_geomadr[b];
  return {d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]};
}

void expect_near3(const efc::Vec3& a, const efc::Vec3& b, double tol, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tol) << what << " [" << k << "]";
}

// ----------------------------------------------------------------- tables
TEST(MujocoBindings, RowsAreTopologicalAndResolved) {
  const efc::Object obj = efc_test::make_test_object();
  const auto rows = efc::build_bindings(obj);
  ASSERT_EQ(rows.size(), 5u);
  std::vector<std::string> names;
  for (const auto& r : rows) names.push_back(r.name);
  const auto pos = [&](const std::string& n) { return std::find(names.begin(), names.end(), n) - names.begin(); };
  EXPECT_LT(pos("open"), pos("lamp")) << "lamp reads the door that 'open' drives";
  const auto& water = rows[pos("water")];
  EXPECT_STREQ(water.receptor_joint, "button");
  EXPECT_STREQ(water.effector_body, "spout");
  // 6 L/min of 4 mm droplets for 3 s wants 1,119; MuJoCo 2.2's 1000-number
  // keyframe leaves room for (1000 - 4 joints) / 7 free joints.
  EXPECT_EQ(water.droplet_count, 142);
  EXPECT_NEAR(water.params.effect.droplet_volume_l, 4.0 / 3.0 * M_PI * 0.004 * 0.004 * 0.004 * 1000, 1e-15);
  EXPECT_DOUBLE_EQ(water.params.mapping.threshold, 0.007);
  const auto& open = rows[pos("open")];
  EXPECT_STREQ(open.effector_joint, "door");
  EXPECT_DOUBLE_EQ(open.params.mapping.gain, 1.2);
  EXPECT_EQ(rows[pos("heat")].glow_max, efc_mj::kGlowFullC);
  EXPECT_DOUBLE_EQ(rows[pos("heat")].params.mapping.r_hi, 2 * M_PI);  // continuous receptor
  EXPECT_DOUBLE_EQ(rows[pos("breeze")].reach, 0.6);
}

// ------------------------------------------------------------------- MJCF
TEST(MujocoMjcf, EveryEffectLoadsWithoutWarning) {
  for (bool drive : {false, true}) {
    Loaded L;
    load_object(efc_test::make_test_object(), drive, drive ? "load_drive" : "load", &L);
    ASSERT_NE(L.m, nullptr);
    EXPECT_EQ(mj_name2id(L.m, mjOBJ_ACTUATOR, "efc_drive_lever") >= 0, drive);
    EXPECT_LT(mj_name2id(L.m, mjOBJ_ACTUATOR, "efc_drive_door"), 0) << "door is a geometry effector";
    EXPECT_GE(mj_name2id(L.m, mjOBJ_CAMERA, "efc_camera"), 0);
    EXPECT_GE(mj_name2id(L.m, mjOBJ_LIGHT, "efc_lamp_light"), 0);
    for (const char* s : {"efc_lamp_point", "efc_water_point", "efc_heat_point", "efc_breeze_point"})
      EXPECT_GE(mj_name2id(L.m, mjOBJ_SITE, s), 0) << s;
    EXPECT_GE(mj_name2id(L.m, mjOBJ_BODY, "efc_water_drop141"), 0);
    for (int i = 0; i < 500; ++i) mj_step(L.m, L.d);
    expect_no_runtime_warnings(L.d);
  }
  // Each effect on its own, and an object without functions.
  for (size_t keep = 0; keep <= 5; ++keep) {
    efc::Object obj = efc_test::make_test_object();
    if (keep < 5) obj.functions = {obj.functions[keep]};
    else obj.functions.clear();
    Loaded L;
    load_object(obj, true, "single" + std::to_string(keep), &L);
    ASSERT_NE(L.m, nullptr);
    for (int i = 0; i < 50; ++i) mj_step(L.m, L.d);
    expect_no_runtime_warnings(L.d);
  }
}

TEST(MujocoMjcf, KinematicTreeMatchesSpec) {
  const efc::Object obj = efc_test::make_test_object();
  Loaded L;
  load_object(obj, false, "kin", &L);
  ASSERT_NE(L.m, nullptr);
  mj_resetData(L.m, L.d);  // every joint at 0: the spec's reference configuration
  mj_forward(L.m, L.d);
  for (const efc::Part& p : obj.parts) {
    const int b = mj_name2id(L.m, mjOBJ_BODY, p.name.c_str());
    ASSERT_GE(b, 0) << p.name;
    expect_near3({L.d->xipos[3 * b], L.d->xipos[3 * b + 1], L.d->xipos[3 * b + 2]}, p.mass_props.com, 1e-12,
                 p.name + " com");
    expect_near3(geom_world(L.m, L.d, p.name.c_str()), p.geometry.center, 1e-12, p.name + " geom");
    EXPECT_NEAR(L.m->body_mass[b], p.mass_props.mass, 1e-12) << p.name;
  }
  // Rotate the door about +z through (-0.1, 0.1, 0.05), the lever about +y
  // through (0.1, 0, 0.06), push the button 5 mm along -z, turn the knob.
  const double th = 0.7, ph = 0.5;
  L.d->qpos[qadr(L.m, "door")] = th;
  L.d->qpos[qadr(L.m, "lever")] = ph;
  L.d->qpos[qadr(L.m, "button")] = 0.005;
  L.d->qpos[qadr(L.m, "knob")] = 2.0;
  mj_forward(L.m, L.d);
  const efc::Vec3 dc{-0.05 + 0.1, 0.1 - 0.1, 0.15 - 0.05};  // door centre - origin
  expect_near3(geom_world(L.m, L.d, "door"),
               {-0.1 + std::cos(th) * dc[0] - std::sin(th) * dc[1],
                0.1 + std::sin(th) * dc[0] + std::cos(th) * dc[1], 0.05 + dc[2]},
               1e-12, "door rotated");
  const efc::Vec3 lc{0.05, 0, 0};  // lever centre - origin; rotation about +y
  expect_near3(geom_world(L.m, L.d, "lever"),
               {0.1 + std::cos(ph) * lc[0], 0, 0.06 - std::sin(ph) * lc[0]}, 1e-12, "lever rotated");
  expect_near3(geom_world(L.m, L.d, "button"), {-0.1, -0.1, 0.055 - 0.005}, 1e-12, "button pushed");
  expect_near3(geom_world(L.m, L.d, "knob"), {0.1, -0.1, 0.06}, 1e-12, "knob on its axis");
  // The keyframe holds each joint's initial value (the door starts at 0).
  const int key = mj_name2id(L.m, mjOBJ_KEY, "initial");
  ASSERT_GE(key, 0);
  EXPECT_EQ(L.m->key_qpos[key * L.m->nq + qadr(L.m, "door")], 0.0);
  // Parked droplets wait far above everything.
  EXPECT_EQ(L.m->key_qpos[key * L.m->nq + qadr(L.m, "efc_water_drop0") + 2], 50.0);
}

TEST(MujocoMjcf, MeshVerticesLandWhereSpecSays) {
  efc::Object obj = efc_test::make_test_object();
  obj.functions.clear();
  // The door becomes a mesh (a closed box with outward triangles), on a
  // revolute joint so its body origin is not the object origin.
  efc::Part& door = obj.parts[obj.find_part("door")];
  const efc::Vec3 c = door.geometry.center, s = door.geometry.size;
  efc::MeshData mesh;
  for (int i = 0; i < 8; ++i)
    mesh.vertices.push_back({c[0] + (i & 1 ? 0.5 : -0.5) * s[0], c[1] + (i & 2 ? 0.5 : -0.5) * s[1],
                             c[2] + (i & 4 ? 0.5 : -0.5) * s[2]});
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  door.geometry = efc::Geometry{};
  door.geometry.kind = efc::GeomKind::Mesh;
  door.geometry.mesh_path = "meshes/door.obj";
  door.geometry.mesh = mesh;
  Loaded L;
  load_object(obj, false, "mesh", &L);
  ASSERT_NE(L.m, nullptr);
  ASSERT_EQ(L.m->nmesh, 1);
  for (double th : {0.0, 0.9}) {
    L.d->qpos[qadr(L.m, "door")] = th;
    mj_forward(L.m, L.d);
    const int b = mj_name2id(L.m, mjOBJ_BODY, "door");
    const int g = L.m->body_geomadr[b];
    ASSERT_EQ(L.m->geom_type[g], mjGEOM_MESH);
    const int id = L.m->geom_dataid[g];
    const float* v = L.m->mesh_vert + 3 * L.m->mesh_vertadr[id];
    const int nv = L.m->mesh_vertnum[id];
    const mjtNum* R = L.d->geom_xmat + 9 * g;
    const mjtNum* p = L.d->geom_xpos + 3 * g;
    for (const efc::Vec3& w0 : mesh.vertices) {
      // Where the spec's vertex must be once the door turned by th.
      const efc::Vec3 r{w0[0] + 0.1, w0[1] - 0.1, w0[2] - 0.05};
      const efc::Vec3 w{-0.1 + std::cos(th) * r[0] - std::sin(th) * r[1],
                        0.1 + std::sin(th) * r[0] + std::cos(th) * r[1], 0.05 + r[2]};
      double best = 1e9;
      for (int k = 0; k < nv; ++k) {
        double e = 0;
        for (int a = 0; a < 3; ++a) {
          const double x = p[a] + R[3 * a] * v[3 * k] + R[3 * a + 1] * v[3 * k + 1] + R[3 * a + 2] * v[3 * k + 2];
          e += (x - w[a]) * (x - w[a]);
        }
        best = std::min(best, std::sqrt(e));
      }
      EXPECT_LT(best, 1e-6) << "vertex " << w0[0] << " " << w0[1] << " " << w0[2] << " at th=" << th;
    }
  }
}

// ------------------------------------------------------------- controller
constexpr int kDrops = 142;  // the test object's pool (see RowsAreTopologicalAndResolved)

efc_mj::Controller* g_ctrl = nullptr;
void control_cb(const mjModel* m, mjData* d) {
  if (g_ctrl) g_ctrl->step(m, d);
}

struct Running {
  Loaded L;
  std::unique_ptr<efc_mj::Controller> c;
  std::vector<efc_mj::FunctionBinding> rows;
  ~Running() {
    mjcb_control = nullptr;
    g_ctrl = nullptr;
  }
};

void start(const efc::Object& obj, Running* r, const std::string& tag, const std::string& extra = "",
           const std::string& existing_xml = "") {
  load_object(obj, true, tag, &r->L, extra, existing_xml);
  ASSERT_NE(r->L.m, nullptr);
  r->rows = efc::build_bindings(obj);
  r->c = std::make_unique<efc_mj::Controller>(r->L.m, r->rows.data(), static_cast<int>(r->rows.size()));
  ASSERT_TRUE(r->c->ok()) << r->c->error();
  r->c->reset(r->L.m, r->L.d);
  g_ctrl = r->c.get();
  mjcb_control = control_cb;
}

void run_for(Running& r, double seconds) {
  const int n = static_cast<int>(std::lround(seconds / r.L.m->opt.timestep));
  for (int i = 0; i < n; ++i) mj_step(r.L.m, r.L.d);
}

TEST(MujocoController, MissingNameIsReported) {
  Loaded L;
  load_object(efc_test::make_test_object(), false, "missing", &L);
  ASSERT_NE(L.m, nullptr);
  auto rows = efc::build_bindings(efc_test::make_test_object());
  std::strcpy(rows[0].receptor_joint, "no_such_joint");
  efc_mj::Controller c(L.m, rows.data(), static_cast<int>(rows.size()));
  EXPECT_FALSE(c.ok());
  EXPECT_NE(c.error().find("no_such_joint"), std::string::npos) << c.error();
}

TEST(MujocoController, GeometryReachesTargetAndLightFollowsChain) {
  Running r;
  start(efc_test::make_test_object(), &r, "geom");
  ASSERT_NE(r.L.m, nullptr);
  mjModel* m = r.L.m;
  mjData* d = r.L.d;
  const int open = row_of(*r.c, "open"), lamp = row_of(*r.c, "lamp");
  for (double lever : {0.75, 0.2, 1.0}) {
    d->ctrl[actuator(m, "efc_drive_lever")] = lever;
    run_for(r, 3.0);
    const double target = 1.2 * lever;
    EXPECT_NEAR(r.c->readout(open).s_E, target, 0.01 * 1.2) << "lever " << lever;
    EXPECT_NEAR(d->qpos[qadr(m, "door")], r.c->readout(open).s_E, 0.02 * 1.2) << "lever " << lever;
    EXPECT_NEAR(r.c->readout(open).measured, d->qpos[qadr(m, "door")], 1e-12);
    // Chain: the lamp reads the door's joint.
    const double lm = r.c->readout(lamp).s_E;
    EXPECT_NEAR(lm, 800 / 1.5 * d->qpos[qadr(m, "door")], 1e-3 + 1e-6 * lm);
    const int light = mj_name2id(m, mjOBJ_LIGHT, "efc_lamp_light");
    EXPECT_NEAR(m->light_diffuse[3 * light + 0], 1.0 * lm / 1000, 1e-6);
    EXPECT_NEAR(m->light_diffuse[3 * light + 1], 0.9 * lm / 1000, 1e-6);
    EXPECT_NEAR(r.c->readout(lamp).measured, lm, 1e-4 * lm + 1e-9);
  }
  expect_no_runtime_warnings(d);
}

TEST(MujocoController, TemperatureLagsAndGlows) {
  Running r;
  start(efc_test::make_test_object(), &r, "heat");
  ASSERT_NE(r.L.m, nullptr);
  mjModel* m = r.L.m;
  mjData* d = r.L.d;
  const int heat = row_of(*r.c, "heat");
  const int plate_geom = m->body_geomadr[mj_name2id(m, mjOBJ_BODY, "plate")];
  const float base_g = m->geom_rgba[4 * plate_geom + 1];
  d->ctrl[actuator(m, "efc_drive_knob")] = M_PI;  // s_E = 20 + 230 / 2 = 135
  run_for(r, 0.5);                              // one time constant (knob moves in ~0.1 s)
  EXPECT_NEAR(r.c->readout(heat).s_E, 135.0, 0.5);
  const double t = r.c->readout(heat).measured;
  EXPECT_GT(t, 20 + 115 * 0.55);
  EXPECT_LT(t, 20 + 115 * 0.70);
  run_for(r, 4.0);
  EXPECT_NEAR(r.c->readout(heat).measured, 135.0, 0.5);
  // Glow: (135 - 20) / (400 - 20) of the way to red-hot.
  const float f = static_cast<float>((r.c->readout(heat).measured - 20) / 380);
  EXPECT_NEAR(m->geom_rgba[4 * plate_geom + 1], base_g * (1 - f) + 0.22f * f, 1e-4);
  EXPECT_NEAR(m->geom_rgba[4 * plate_geom + 0], 0.7f * (1 - f) + 1.0f * f, 1e-4);
}

TEST(MujocoController, FluidSpawnsDropletsAndMeasuresFlow) {
  Running r;
  start(efc_test::make_test_object(), &r, "fluid");
  ASSERT_NE(r.L.m, nullptr);
  mjModel* m = r.L.m;
  mjData* d = r.L.d;
  const int water = row_of(*r.c, "water");
  EXPECT_EQ(r.c->readout(water).measured, 0.0);
  d->ctrl[actuator(m, "efc_drive_button")] = 0.01;
  run_for(r, 1.5);
  EXPECT_DOUBLE_EQ(r.c->readout(water).s_E, 6.0);
  EXPECT_NEAR(r.c->readout(water).measured, 6.0, 0.06);
  // Droplets are in the air below the spout, launched downwards.
  int flying = 0;
  for (int i = 0; i < kDrops; ++i) {
    const int b = mj_name2id(m, mjOBJ_BODY, ("efc_water_drop" + std::to_string(i)).c_str());
    const double z = d->xpos[3 * b + 2];
    if (z < 10) {
      ++flying;
      EXPECT_LT(z, 0.2 + 1e-6);
      EXPECT_NEAR(d->xpos[3 * b], 0.0, 0.02);
      EXPECT_NEAR(d->xpos[3 * b + 1], -0.1, 0.02);
    } else {
      EXPECT_NEAR(z, 50.0, 1e-3) << "parked droplets stay pinned";
    }
  }
  EXPECT_GT(flying, 100);
  expect_no_runtime_warnings(d);
  // Release: the flow stops and, one window later, so does the measurement.
  d->ctrl[actuator(m, "efc_drive_button")] = 0.0;
  run_for(r, 0.3);
  EXPECT_EQ(r.c->readout(water).s_E, 0.0);
  run_for(r, efc_mj::kFlowWindow + 0.05);
  EXPECT_EQ(r.c->readout(water).measured, 0.0);
  run_for(r, efc_mj::kDropletLifetime);
  for (int i = 0; i < kDrops; ++i) {
    const int b = mj_name2id(m, mjOBJ_BODY, ("efc_water_drop" + std::to_string(i)).c_str());
    EXPECT_NEAR(d->xpos[3 * b + 2], 50.0, 1e-3) << "every droplet recycled";
  }
}

TEST(MujocoController, DropletsHitTheObject) {
  // A tray under the spout catches droplets: they collide with the object.
  efc::Object obj = efc_test::make_test_object();
  obj.parts.push_back(efc_test::box_part("tray", {0.1, 0.1, 0.01}, {0.0, -0.1, 0.12}, 0.1));
  obj.parts.back().joint = efc_test::joint(efc::JointType::Fixed, "base", 0, {0, 0, 1}, {0, 0, 0}, 0, 0);
  Running r;
  start(obj, &r, "tray");
  ASSERT_NE(r.L.m, nullptr);
  r.L.d->ctrl[actuator(r.L.m, "efc_drive_button")] = 0.01;
  run_for(r, 0.5);
  int resting = 0;
  for (int i = 0; i < kDrops; ++i) {
    const int b = mj_name2id(r.L.m, mjOBJ_BODY, ("efc_water_drop" + std::to_string(i)).c_str());
    const double z = r.L.d->xpos[3 * b + 2];
    if (z < 10) {
      EXPECT_GT(z, 0.125 - 0.002) << "droplet " << i << " fell through the tray";
      resting += z < 0.135;
    }
  }
  EXPECT_GT(resting, 10);
  expect_no_runtime_warnings(r.L.d);
}

TEST(MujocoController, AirflowPushesFreeBody) {
  const std::string prop =
      "    <body name=\"prop\" pos=\"0.35 0 0.3\">\n      <joint name=\"prop\" type=\"free\"/>\n"
      "      <inertial pos=\"0 0 0\" mass=\"0.01\" diaginertia=\"1e-6 1e-6 1e-6\"/>\n"
      "      <geom type=\"sphere\" size=\"0.03\"/>\n    </body>\n";
  for (bool on : {false, true}) {
    Running r;
    start(efc_test::make_test_object(), &r, on ? "air_on" : "air_off", prop);
    ASSERT_NE(r.L.m, nullptr);
    mjModel* m = r.L.m;
    mjData* d = r.L.d;
    m->opt.gravity[2] = 0;
    const int breeze = row_of(*r.c, "breeze");
    const int b = mj_name2id(m, mjOBJ_BODY, "prop");
    // Hold the lever (the breeze's receptor) where it is wanted.
    const int lever = qadr(m, "lever");
    d->qpos[lever] = on ? 1.0 : 0.0;
    d->ctrl[actuator(m, "efc_drive_lever")] = on ? 1.0 : 0.0;
    mj_forward(m, d);
    mj_step(m, d);
    EXPECT_EQ(r.c->readout(breeze).measured, on ? 10.0 : 0.0);
    const double speed = efc_rt::air_speed_at(on ? 10 : 0, 0.2, 0, 0.35, 0.6);
    EXPECT_NEAR(d->xfrc_applied[6 * b], efc_rt::air_drag(speed, M_PI * 0.03 * 0.03), 1e-12);
    EXPECT_EQ(d->xfrc_applied[6 * b + 1], 0.0);
    run_for(r, 0.2);
    const double vx = d->qvel[vadr(m, "prop") + 0];
    if (on) EXPECT_GT(vx, 0.05); else EXPECT_NEAR(vx, 0.0, 1e-9);
    // Out of the cone: the force is zeroed again next step.
    d->qpos[lever] = 0;
    d->ctrl[actuator(m, "efc_drive_lever")] = 0;
    run_for(r, 0.01);
    EXPECT_EQ(d->xfrc_applied[6 * b], 0.0);
  }
}

TEST(MujocoMjcf, UnwritableFolderIsAnErrorNotACrash) {
  efc::Diagnostics diags;
  EXPECT_FALSE(efc::find_backend("mujoco")->emit(efc_test::make_test_object(), "/proc/efc_no_such_dir", diags));
  ASSERT_TRUE(diags.has_errors());
  EXPECT_EQ(diags.items().front().code, "E0900");
}

// The in-memory output (what compile_bench times as efc's own work) is
// exactly what `emit` writes: the same paths, the same bytes, nothing else.
TEST(MujocoMjcf, GeneratedFilesAreExactlyWhatEmitWrites) {
  efc::Diagnostics diags;
  // kitchen_faucet has OBJ meshes: the meshes/ subfolder is covered too.
  auto obj = efc::load_spec(std::string(EFC_SOURCE_DIR) + "/examples/kitchen_faucet.json", {}, diags);
  ASSERT_TRUE(obj) << diags.items().size();
  std::vector<efc::OutputFile> files;
  ASSERT_TRUE(efc::generate_mujoco_target(*obj, diags, &files));
  const std::string dir = efc_test::temp_dir("generated_vs_written");
  ASSERT_TRUE(efc::find_backend("mujoco")->emit(*obj, dir, diags));
  std::map<std::string, std::string> written;
  namespace fs = std::filesystem;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    written[fs::relative(e.path(), dir).string()] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  std::map<std::string, std::string> generated;
  for (const efc::OutputFile& f : files) EXPECT_TRUE(generated.emplace(f.path, f.bytes).second) << f.path;
  EXPECT_EQ(written.size(), generated.size());
  EXPECT_TRUE(std::any_of(written.begin(), written.end(),
                          [](const auto& w) { return w.first.rfind("meshes/", 0) == 0; }));
  for (const auto& [path, bytes] : generated) {
    ASSERT_TRUE(written.count(path)) << path << " was generated but not written";
    EXPECT_EQ(written[path], bytes) << path;
  }
}

TEST(MujocoMjcf, TooManyLightsIsAWarning) {
  efc::Object obj = efc_test::make_test_object();
  obj.functions.clear();
  for (int i = 0; i < 8; ++i) {
    obj.parts.push_back(efc_test::sphere_part("bulb" + std::to_string(i), 0.01, {0.1 * i, 0, 0.4}, 0.01));
    obj.parts.back().joint = efc_test::joint(efc::JointType::Fixed, "base", 0, {0, 0, 1}, {0, 0, 0}, 0, 0);
    obj.functions.push_back(efc_test::function(obj, "lamp" + std::to_string(i), "lever",
                                               "bulb" + std::to_string(i), efc::MappingType::Binary,
                                               efc::EffectType::Illumination, 0, 100));
  }
  efc::Diagnostics diags;
  std::string xml;
  ASSERT_TRUE(efc::write_mujoco_model(obj, efc_test::temp_dir("lights"), {}, diags, &xml));
  ASSERT_EQ(diags.warning_count(), 1u);
  EXPECT_EQ(diags.items().front().code, "W0900");
  EXPECT_NE(diags.items().front().message.find("8 lights"), std::string::npos);
}

// -------------------------------------------------------- generated code
// The same receptor trajectory in the test and in the generated program.
#define EFC_TRAJECTORY                                 \
  "  const double t = d->time;\n"                     \
  "  d->qpos[q_lever] = 0.5 + 0.5 * std::sin(3 * t);\n" \
  "  d->qpos[q_button] = 0.005 + 0.005 * std::sin(7 * t);\n" \
  "  d->qpos[q_knob] = t;\n"                          \
  "  d->qvel[v_lever] = d->qvel[v_button] = d->qvel[v_knob] = 0;\n"

void drive(const mjModel* m, mjData* d, int q_lever, int q_button, int q_knob, int v_lever, int v_button,
           int v_knob) {
  const double t = d->time;
  d->qpos[q_lever] = 0.5 + 0.5 * std::sin(3 * t);
  d->qpos[q_button] = 0.005 + 0.005 * std::sin(7 * t);
  d->qpos[q_knob] = t;
  d->qvel[v_lever] = d->qvel[v_button] = d->qvel[v_knob] = 0;
}

TEST(MujocoCallbacks, GeneratedProgramMatchesInProcessController) {
  const efc::Object obj = efc_test::make_test_object();
  const std::string dir = efc_test::temp_dir("callbacks");
  const efc::Backend* backend = efc::find_backend("mujoco");
  ASSERT_NE(backend, nullptr);
  efc::Diagnostics diags;
  ASSERT_TRUE(backend->emit(obj, dir, diags));
  for (const char* f : {"testobj.xml", "testobj_callbacks.cc", "testobj_callbacks.h", "README.md",
                        "CMakeLists.txt", "efc_mujoco_runtime.h"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + f)) << f;
  // Six files and nothing else: no folder for primitive geometry, one runtime file.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 6);
  const int steps = 1500;
  const std::string main_cc = std::string(
      "#include <cmath>\n#include <cstdio>\n#include <cstdlib>\n#include \"testobj_callbacks.h\"\n"
      "static void err(const char* s) { std::fprintf(stderr, \"error %s\\n\", s); std::exit(3); }\n"
      "static void warn(const char* s) { std::fprintf(stderr, \"warning %s\\n\", s); std::exit(4); }\n"
      "int main() {\n  mju_user_error = err;\n  mju_user_warning = warn;\n"
      "  char e[1000] = \"\";\n  mjModel* m = mj_loadXML(\"testobj.xml\", 0, e, sizeof e);\n"
      "  if (!m || e[0]) { std::fprintf(stderr, \"load: %s\\n\", e); return 2; }\n"
      "  mjData* d = mj_makeData(m);\n"
      "  mj_resetDataKeyframe(m, d, mj_name2id(m, mjOBJ_KEY, \"initial\"));\n  mj_forward(m, d);\n"
      "  if (!efc_testobj_install(m)) return 5;\n  efc_testobj_reset(m, d);\n"
      "  auto J = [&](const char* n) { return mj_name2id(m, mjOBJ_JOINT, n); };\n"
      "  const int q_lever = m->jnt_qposadr[J(\"lever\")], v_lever = m->jnt_dofadr[J(\"lever\")];\n"
      "  const int q_button = m->jnt_qposadr[J(\"button\")], v_button = m->jnt_dofadr[J(\"button\")];\n"
      "  const int q_knob = m->jnt_qposadr[J(\"knob\")], v_knob = m->jnt_dofadr[J(\"knob\")];\n"
      "  for (int s = 0; s < ") + std::to_string(steps) + "; ++s) {\n" EFC_TRAJECTORY
      "    mj_step(m, d);\n"
      "    for (int i = 0; i < efc_testobj_function_count(); ++i)\n"
      "      std::printf(\"%s %.17g %.17g %.17g\\n\", efc_testobj_function_name(i), efc_testobj_s_R(i),\n"
      "                  efc_testobj_s_E(i), efc_testobj_measured(i));\n  }\n"
      "  efc_testobj_uninstall();\n  mj_deleteData(d);\n  mj_deleteModel(m);\n  return 0;\n}\n";
  std::ofstream(dir + "/main.cc") << main_cc;
  const std::string cmd = "cd '" + dir + "' && g++ -std=c++17 -O2 -Wall -Werror -o prog main.cc testobj_callbacks.cc "
                          "-lmujoco > build.log 2>&1 "
                          "&& ./prog > run.txt 2> run.err";
  const int rc = std::system(cmd.c_str());
  ASSERT_EQ(rc, 0) << "see " << dir << "/build.log, run.err";

  // The same model and trajectory in process.
  Running r;
  start(obj, &r, "callbacks_inproc", "", dir + "/testobj.xml");
  ASSERT_NE(r.L.m, nullptr);
  mjModel* m = r.L.m;
  mjData* d = r.L.d;
  std::string expected;
  char line[512];
  for (int s = 0; s < steps; ++s) {
    drive(m, d, qadr(m, "lever"), qadr(m, "button"), qadr(m, "knob"), vadr(m, "lever"), vadr(m, "button"),
          vadr(m, "knob"));
    mj_step(m, d);
    for (int i = 0; i < r.c->count(); ++i) {
      const auto& ro = r.c->readout(i);
      std::snprintf(line, sizeof line, "%s %.17g %.17g %.17g\n", r.c->binding(i).name, ro.s_R, ro.s_E,
                    ro.measured);
      expected += line;
    }
  }
  std::ifstream in(dir + "/run.txt");
  std::stringstream got;
  got << in.rdbuf();
  const std::string actual = got.str();
  // Report the first differing line, not a 7,500-line diff.
  std::istringstream a(actual), e(expected);
  std::string la, le;
  int n = 0;
  while (std::getline(e, le)) {
    ASSERT_TRUE(std::getline(a, la)) << "the generated program stopped at line " << n;
    ASSERT_EQ(la, le) << "line " << n;
    ++n;
  }
  EXPECT_FALSE(std::getline(a, la)) << "the generated program printed more lines";
  // The trajectory exercised every function.
  EXPECT_NE(expected.find("water 0.0"), std::string::npos);
}

}  // namespace

namespace {

// The output folder builds with its own CMakeLists.txt, and efc_mujoco_runtime.h
// works as a single-header library: a second translation unit that includes it
// without EFC_RUNTIME_IMPLEMENTATION links against the library (the definitions
// exist exactly once, in the generated callbacks).
TEST(MujocoCallbacks, OutputFolderBuildsWithItsCMakeLists) {
  const efc::Object obj = efc_test::make_test_object();
  const std::string dir = efc_test::temp_dir("cmake_output");
  efc::Diagnostics diags;
  ASSERT_TRUE(efc::find_backend("mujoco")->emit(obj, dir, diags));
  std::ofstream(dir + "/user.cc")
      << "#include \"efc_mujoco_runtime.h\"\n"
         "double user_map(double s_R) {\n"
         "  efc_rt::MappingParams p{efc_rt::kLinear, 0, 1, 0, 100, 0, 0, 0, 100, 0, 0, 0};\n"
         "  efc_rt::MappingState st{};\n  return efc_rt::mapping_update(p, s_R, &st);\n}\n";
  std::ofstream(dir + "/main.cc")
      << "#include <cstdio>\n#include \"testobj_callbacks.h\"\n"
         "double user_map(double);\n"
         "int main() {\n  char e[1000] = \"\";\n"
         "  mjModel* m = mj_loadXML(\"testobj.xml\", 0, e, sizeof e);\n  if (!m) return 2;\n"
         "  if (!efc_testobj_install(m)) return 3;\n"
         "  std::printf(\"%d %g\\n\", efc_testobj_function_count(), user_map(0.25));\n"
         "  efc_testobj_uninstall();\n  mj_deleteModel(m);\n  return 0;\n}\n";
  const std::string cmd =
      "cd '" + dir + "' && cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > cmake.log 2>&1 && "
      "cmake --build build >> cmake.log 2>&1 && "
      "g++ -std=c++17 -Wall -Werror main.cc user.cc -I. -Lbuild -ltestobj_callbacks -lmujoco -o user "
      ">> cmake.log 2>&1 && LD_LIBRARY_PATH=build ./user > user.txt 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "see " << dir << "/cmake.log, user.txt";
  std::ifstream in(dir + "/user.txt");
  std::string out((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(out, std::to_string(efc::build_bindings(obj).size()) + " 25\n");
}

}  // namespace
