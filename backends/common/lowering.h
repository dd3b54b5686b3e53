// The target-neutral rules every backend lowers an object with: in which order
// functions run, the receptor range a mapping sees, the resolved runtime
// parameters of each function, the servo gains of drives, droplet pools and
// effect points. Decided once here, so MuJoCo, URDF, Bullet and the Python
// targets realise the same object (after Drake's parsing/detail_common.h,
// which serves all its parsers).
//
// A backend reads a resolved, checked Object (compiler/core/load.h) and never
// re-validates; these functions assume one.
#pragma once

#include <string>
#include <vector>

#include "compiler/core/resolve.h"
#include "compiler/ir.h"
#include "runtime/efc_replay.h"
#include "runtime/efc_runtime.h"

namespace efc {
namespace lowering {

// ---------------------------------------------------------------- constants
// Realisation constants shared by every target (the MuJoCo binding in
// runtime/mujoco keeps its own copies, checked equal where both are seen).
constexpr double kGlowFullC = 400.0;       // C at which a heated part is fully red-hot
constexpr double kDropletLifetime = 3.0;   // s a droplet lives before it is recycled
constexpr double kFlowWindow = 0.5;        // s over which emitted droplets are counted
constexpr double kDefaultDropletRadius = 0.004;  // m
constexpr double kDefaultFluidSpeed = 1.0;       // m/s
constexpr double kDefaultConeAngle = 0.35;       // rad
constexpr double kDefaultReach = 0.6;            // m
constexpr double kDefaultTimeConstant = 30.0;    // s
// Drive rules (README "Choices where the spec is silent").
constexpr double kEffectDriveHz = 4.0;      // natural frequency of a geometry effect's servo
constexpr double kReceptorDriveHz = 10.0;   // of a profile's receptor servo
constexpr double kHoldTolerance = 0.01;     // steady error allowed, fraction of the range
constexpr double kWeakStiffness = 0.02;     // a given stiffness holding worse than this warns
// Droplet pools: the most one fluid effect keeps alive (300 colliding droplets
// step at about 1,400 steps/s on the reference machine, so 200 per emitter
// keeps MuJoCo playback faster than real time), the fewest, and MuJoCo 2.2's
// keyframe limit that bounds them all.
constexpr int kMaxDroplets = 200;
constexpr int kMinDroplets = 8;
constexpr int kMaxKeyframeQpos = 1000;

// Colour of a part without rgba.
constexpr double kDefaultRgba[4] = {0.7, 0.7, 0.72, 1.0};

// ---------------------------------------------------------------- parts
int receptor_part(const Object& obj, const Function& f);
int effector_part(const Object& obj, const Function& f);

// Where every part's frame sits. All frames are axis-aligned with the object
// frame, so only positions differ: a hinge (revolute, continuous) part's frame
// is on its joint axis (at the joint origin), every other part's at its centre
// of mass, the root's at its centre of mass too (MuJoCo body) or the object
// origin (URDF link: the URDF backend overrides the root).
struct Layout {
  int root = -1;
  std::vector<Vec3> frame;                  // per part: frame origin, object frame
  std::vector<std::vector<int>> children;   // per part: child parts, spec order
};
Layout make_layout(const Object& obj);

// ---------------------------------------------------------------- functions
// Function indices in evaluation order: topological over chains (a function
// whose receptor is another function's effector runs after it); ties keep
// spec order.
std::vector<int> evaluation_order(const Object& obj);

// The receptor range a mapping sees is efc::receptor_range
// (compiler/core/resolve.h): resolve() fills the mapping defaults from it, so
// there is exactly one.

// Receptor parts the profile drives (efc play, the generated programs):
// receptors of functions that are not the effector of a geometry effect
// (those move as their function says). Spec order, each once.
std::vector<int> profile_driven_receptors(const Object& obj);

// The effect's point in the object frame (the spec's, filled by resolve();
// the fallback is the effector's bounding-box centre) and its unit direction
// (fluid emitter, airflow outlet; the fallback is down for fluid, +x for air).
Vec3 effect_point(const Object& obj, const Function& f);
Vec3 effect_direction(const Effect& e);

// The unit of a function's s_E: rad or m (geometry, by the effector's
// joint), lm, C, L/min, m/s.
const char* effect_unit(const Object& obj, const Function& f);

// One function, lowered: the runtime's parameters plus what a binding needs
// to realise the effect. Every default the spec leaves open is filled here.
struct FunctionRow {
  int function = -1;  // index into obj.functions
  int receptor = -1, effector = -1;  // part indices
  efc_rt::FunctionParams params{};
  Vec3 direction{0, 0, 0};  // fluid, airflow: unit emitter/outlet direction (else 0)
  Vec3 color{0, 0, 0};      // illumination (else 0)
  double speed = 0;           // fluid: launch speed (m/s)
  double droplet_radius = 0;  // fluid (m)
  int droplet_count = 0;      // fluid: droplet pool size
  double cone_angle = 0;      // airflow: half angle (rad)
  double reach = 0;           // airflow (m)
  double glow_max = 0;        // temperature: s_E at which the glow is full
};
// In evaluation order.
std::vector<FunctionRow> function_rows(const Object& obj);

// The object as the no-simulator replay sees it (runtime/efc_replay.h):
// every movable joint in spec order (named after its part; a continuous one
// spans [0, 2 pi]) and the function rows, exactly as <name>_functions.json
// gives them to efc_templates.py.
struct ReplayModel {
  std::vector<ReplayJoint> joints;
  std::vector<ReplayFunction> functions;
};
ReplayModel replay_model(const Object& obj);

// ---------------------------------------------------------------- drives
// Gains of a position servo on part `part`'s joint.
struct DriveGains {
  double kp = 0;        // position gain (N m / rad or N / m)
  double kv = 0;        // velocity gain of the damping actuator
  double armature = 0;  // added to the joint when kp needs it to stay stable
  double inertia = 0;   // effective inertia about/along the joint (incl. armature)
};
// `tolerance`: allowed steady-state error (joint units) against the joint's
// spring, gravity and friction over [q_lo, q_hi]; `hz`: the natural frequency
// wanted; explicit stiffness/damping override the computed values.
DriveGains drive_gains(const Object& obj, const Layout& layout, int part, double q_lo,
                       double q_hi, double tolerance, double hz, double timestep,
                       const double* stiffness, const double* damping);
// A geometry effect's servo on its effector: within kHoldTolerance of the
// effect range at kEffectDriveHz, or the effect's stiffness/damping.
DriveGains geometry_drive(const Object& obj, const Layout& layout, const Function& f,
                          double timestep);
// The servo a profile moves a receptor with: kHoldTolerance of the joint range
// at kReceptorDriveHz.
DriveGains receptor_drive(const Object& obj, const Layout& layout, int part, double timestep);
// The warning owed when a geometry effect's explicit stiffness cannot hold its
// effector within kWeakStiffness of the range ("" when it can or none is given).
std::string weak_stiffness_warning(const Object& obj, const Layout& layout, const Function& f,
                                   double timestep);

// ---------------------------------------------------------------- fluid
// Litres in one droplet, and how many droplets a pool holds (enough for the
// peak flow over a droplet's lifetime, capped).
double droplet_volume_litres(double radius);
int droplet_pool_size(const Effect& e);
// Pool size per function (0 for non-fluid), after sharing the keyframe's room
// among all pools (MuJoCo 2.2 reads at most kMaxKeyframeQpos key qpos values;
// every target uses the same pools so their flows agree).
std::vector<int> droplet_pool_sizes(const Object& obj);

}  // namespace lowering
}  // namespace efc
