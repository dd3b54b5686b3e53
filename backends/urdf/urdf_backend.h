// The URDF target: <name>.urdf, its meshes (binary STL under meshes/,
// referenced by relative path), and <name>.functions.json, the sidecar that
// holds what URDF cannot: the function templates (resolved), joint springs and
// initial positions.
//
// Conventions (the URDF's header comment and the output README repeat them):
// - one link per part, named after the part; every link frame is
//   axis-aligned with the object frame. The root link's frame is the object
//   origin; a revolute/continuous part's link frame sits on its joint origin
//   (a point on the axis); a prismatic or fixed part's link frame sits at the
//   part's centre of mass.
// - one joint per non-root part, named after the part, in its parent link's
//   frame: origin xyz = child frame - parent frame (object frame), rpy 0;
//   axis = the unit axis. continuous joints are `continuous` (no <limit>).
// - revolute/prismatic <limit> lower/upper = the spec range; effort and
//   velocity are not in the spec: kEffortLimit and kVelocityLimit, chosen to
//   never bind for a household object.
// - <dynamics damping friction> from the spec (always written for movable joints).
// - inertials: the compiler's mass, centre of mass and full inertia about it.
// - primitives stay primitives (URDF cylinders run along z: the origin's rpy
//   turns z onto the spec's axis); a compound becomes several <visual> and
//   <collision> elements; meshes become meshes/<part>_<i>.stl in the link frame.
// - every function whose effect has a point (illumination, temperature,
//   fluid emitter, airflow outlet) gets a link `<function>_site` on a fixed
//   joint `<function>_site_joint` from the effector link, at the point; for
//   fluid and airflow the site's +z is the emitter/outlet direction (as the
//   MuJoCo target's site zaxis), otherwise rpy 0. A site link carries a
//   negligible inertial (kSiteMass) so loaders that give an inertial-less link
//   1 kg (PyBullet) do not add mass. A generated name already taken by a part
//   (or another site) gets a suffix _2, _3, ...; the sidecar names the result.
#pragma once

#include <string>
#include <vector>

#include "backends/common/output_file.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {
namespace urdf {

constexpr double kEffortLimit = 1000.0;   // N m (revolute) or N (prismatic)
constexpr double kVelocityLimit = 100.0;  // rad/s or m/s
constexpr double kSiteMass = 1e-6;        // kg
constexpr double kSiteInertia = 1e-12;    // kg m^2 (diagonal)

struct Site {
  int function = -1;
  int effector = -1;           // part index (the site's parent link)
  std::string link, joint;     // `<fn>_site`, `<fn>_site_joint` (suffixed if taken)
  Vec3 point{0, 0, 0};         // object frame
  Vec3 xyz{0, 0, 0};           // in the effector link's frame
  Vec3 rpy{0, 0, 0};           // site orientation (z along direction for fluid/airflow)
  bool directed = false;       // fluid/airflow
  Vec3 direction{0, 0, 0};     // unit, object frame (directed only)
};

struct MeshFile {
  int part = -1;
  std::string file;  // meshes/<part>_<i>.stl, relative to the URDF
  const MeshData* mesh = nullptr;
  Vec3 offset{0, 0, 0};  // minus the link frame's position
};

// Everything the URDF and the sidecar contain, decided before any text is written.
struct Plan {
  int root = -1;
  std::vector<Vec3> link_origin;           // per part: link frame origin, object frame
  std::vector<std::vector<int>> children;  // per part, spec order
  std::vector<std::string> link, joint;    // per part (joint "" for the root)
  std::vector<Site> sites;
  std::vector<int> site_of_function;       // index into sites, -1 if none
  std::vector<MeshFile> meshes;
  // W0900 warnings the target owes the user: (JSON pointer, message).
  struct Warning {
    SourceLoc loc;
    std::string message;
  };
  std::vector<Warning> warnings;
};

Plan make_plan(const Object& obj);

// The URDF document and the sidecar (JSON text) for a plan.
std::string write_urdf(const Object& obj, const Plan& plan);
std::string write_sidecar(const Object& obj, const Plan& plan);

std::string spec_file_name(const Object& obj);  // the spec's file name, no folder

Vec3 matrix_to_rpy(const Mat3& R);  // inverse of rpy_to_matrix (urdf_text.cc)

}  // namespace urdf

// The URDF and its meshes (meshes/*.stl), what a simulator loads: the URDF
// target and the Python targets carry the same bytes. No warnings (what URDF
// cannot say is each target's business). False after adding an error.
bool generate_urdf_model(const Object& obj, const urdf::Plan& plan, Diagnostics& diags,
                         std::vector<OutputFile>* files);

// The whole `--target urdf` folder: the model, <name>.functions.json and
// README.md, with W0900 warnings for what URDF cannot express.
bool generate_urdf_target(const Object& obj, Diagnostics& diags, std::vector<OutputFile>* files);

}  // namespace efc
