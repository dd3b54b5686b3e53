// What makes an effect visible in RGB beyond what `efc play` shows: air
// motes (light streaks carried out of an airflow outlet at a speed that
// follows the air) and the glow of a lamp's effector (its material's
// emission follows the light's output). Visual only: bodies without
// contacts, materials; the dynamics stay `efc play`'s.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "compiler/ir.h"
#include "runtime/mujoco/efc_mujoco.h"

namespace efc::synth {

// Motes per airflow function (scene.h adds their bodies).
constexpr int kAirMotes = 24;

// Where mocap bodies go when they have nothing to show.
void set_mocap(const mjModel* m, mjData* d, int body, const Eigen::Vector3d& p, const Eigen::Quaterniond& q);

class EffectVisuals {
 public:
  // Finds the motes' bodies and the glow materials scene.h added; `parked`
  // is where idle motes wait (out of sight); `seed` places the motes.
  EffectVisuals(const Object& obj, const mjModel* m, const efc_mj::Controller& controller,
                const Eigen::Vector3d& parked, uint64_t seed);
  // For the state now, `dt` after the last call: moves the motes, sets the glow.
  void update(mjModel* m, mjData* d, const efc_mj::Controller& controller, double dt);

 private:
  struct Motes {
    int function = -1;  // the controller's row
    int site = -1, body = -1;
    Eigen::Vector3d direction;  // outlet direction in the effector body's frame
    double cone = 0.3, reach = 1.0;
    std::vector<int> bodies;
    std::vector<double> along;              // distance from the outlet
    std::vector<Eigen::Vector3d> across;    // unit offsets in the cone's cross-section
  };
  std::vector<Motes> motes_;
  std::vector<std::pair<int, int>> glows_;  // (controller row, material)
  Eigen::Vector3d parked_;
};

}  // namespace efc::synth
