// What the generated Bullet program builds, decided at emit time: one
// btMultiBody link per non-root part (parents before children), each link
// frame at the part's centre of mass and rotated onto the principal axes of
// its inertia (diagonalised here: Bullet wants a diagonal inertia in the link
// frame), collision pieces in link frames, joint drives with the MuJoCo
// target's gains, and the W0900 warnings the target owes the user.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "compiler/ir.h"

namespace efc {
namespace bullet {

using Quat = std::array<double, 4>;  // x y z w (btQuaternion order)

struct Shape {
  int link = -1;  // -1 = base
  enum Kind { Box = 0, Cylinder = 1, Sphere = 2, Hull = 3 } kind = Box;
  Vec3 pos{0, 0, 0};  // in the link frame
  Quat rot{0, 0, 0, 1};
  Vec3 size{0, 0, 0};  // box half extents; cylinder (r, r, half length); sphere (r, 0, 0)
  std::vector<Vec3> points;  // hull points, link frame
};

struct Link {
  int part = -1;
  int parent = -1;  // link index, -1 = base
  JointType type = JointType::Fixed;
  double mass = 0;
  Vec3 inertia{0, 0, 0};  // principal moments
  Mat3 frame{};           // columns: the link axes in the object frame
  Vec3 com{0, 0, 0};      // object frame, joint position 0
  Quat rot_parent_to_this{0, 0, 0, 1};
  Vec3 axis{0, 0, 1};           // this link's frame
  Vec3 parent_com_to_pivot{0, 0, 0};  // parent frame
  Vec3 pivot_to_com{0, 0, 0};         // this frame
  double lo = 0, hi = 0, initial = 0;
  bool limited = false;
  double damping = 0, friction = 0, spring_k = 0, spring_rest = 0;
  double joint_inertia = 0;  // joint-space inertia at q = 0 (subtree about the axis)
  double kp = 0;             // geometry-effect drive (0 = none)
  double kv_explicit = -1;   // the effect's damping when given, else -1 (computed)
  bool kinematic = false;    // a profile-driven receptor
};

struct Base {
  int part = -1;
  double mass = 0;
  Vec3 inertia{0, 0, 0};
  Mat3 frame{};
  Vec3 com{0, 0, 0};
};

struct Model {
  Base base;
  std::vector<Link> links;
  std::vector<int> part_link;  // per part: link index (-1 = base)
  std::vector<Shape> shapes;
  bool off_diagonal = false;  // some link frame is rotated onto principal axes
  std::vector<std::string> warnings;  // W0900 messages
  std::vector<std::string> warning_pointers;
};

Model make_model(const Object& obj, double timestep);

// Symmetric 3x3 eigen-decomposition (Jacobi): moments, and a right-handed
// rotation whose columns are the principal axes. Identity when already diagonal.
void principal_axes(const Mat3& inertia, Vec3* moments, Mat3* axes);
Quat to_quat(const Mat3& r);


}  // namespace bullet
}  // namespace efc
