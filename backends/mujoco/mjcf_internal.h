// Helpers shared by the MuJoCo backend's files (not a public interface):
// number formatting, the body layout (world position of each part's body),
// and the drive gains chosen for geometry effects and receptor drives.
#pragma once

#include <string>
#include <vector>

#include "backends/output_file.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {
struct MjcfOptions;
namespace mjcf {
struct Plan;

// Shortest text that reads back as exactly `v` (std::to_chars): XML and C++
// both parse it, and generated code gets bit-identical doubles.
std::string num(double v);
std::string vec(const Vec3& v);
// Escapes text for an XML attribute or comment.
std::string xml_escape(const std::string& s);

// Where every part's body sits. All body frames are axis-aligned with the
// object frame, so only positions differ.
struct Layout {
  int root = -1;
  std::vector<Vec3> body_world;         // per part: body origin, object frame
  std::vector<std::vector<int>> children;  // per part: child parts, spec order
};
Layout make_layout(const Object& obj);

// Receptor range used by mappings (the joint range, [0, 2 pi] for continuous).
void receptor_range(const Object& obj, const Function& f, double* lo, double* hi);

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

// Fluid: litres in one droplet, and how many droplets a pool holds (enough
// for the peak flow over a droplet's lifetime, capped).
double droplet_volume_litres(double radius);
int droplet_pool_size(const Effect& e);
// Pool size per function (0 for non-fluid), after sharing the keyframe's
// room among all pools (MuJoCo 2.2 reads at most 1000 key qpos values).
std::vector<int> droplet_pool_sizes(const Object& obj);

// Default colour of a part without rgba.
constexpr double kDefaultRgba[4] = {0.7, 0.7, 0.72, 1.0};

}  // namespace mjcf

// The generated <name>_callbacks.h (the C API of <name>_callbacks.cc).
std::string callbacks_header(const Object& obj);

// The model's files (meshes, then <name>.xml) from an existing plan, so a
// caller that also needs the plan (the README) makes it once.
bool generate_model_files(const Object& obj, const MjcfOptions& options, mjcf::Plan* plan,
                          Diagnostics& diags, std::vector<OutputFile>* files);

}  // namespace efc
