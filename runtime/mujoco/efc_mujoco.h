// The MuJoCo binding of the efc runtime: applies function templates to a
// compiled efc model every control step. Shared by `efc play` (which builds the
// table in memory) and the generated <name>_callbacks.cc (which embeds the same
// table as C++ source), so both give the same s_E for the same trajectory.
//
// Naming contract with the MJCF backend (backends/mujoco): a part's body and
// joint carry the part's name; generated elements start with "efc_":
//   efc_<fn>_drive   position actuator of a geometry effect
//   efc_<fn>_damp    velocity actuator damping that drive
//   efc_<fn>_light   the light of an illumination effect
//   efc_<fn>_point   site at the effect's point (light, heat source, emitter, outlet)
//   efc_<fn>_drop<i> body + free joint of droplet i of a fluid effect
//   efc_drive_<part> position actuator on a receptor (only with drive_receptors)
#ifndef EFC_MUJOCO_H_
#define EFC_MUJOCO_H_

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "efc_runtime.h"

namespace efc_mj {

// Lumens that correspond to a light diffuse of 1.0 (MuJoCo lights have no unit).
constexpr double kLumensPerDiffuse = 1000.0;
// Temperature at which the glow is fully red-hot (C).
constexpr double kGlowFullC = 400.0;
// Window over which emitted droplets are counted to measure flow (s).
constexpr double kFlowWindow = 0.5;
// A droplet is recycled after this long (s) or once it falls this far below the object.
constexpr double kDropletLifetime = 3.0;
constexpr double kDropletFall = 1.0;

// One function template, fully resolved: a row of the table.
struct FunctionBinding {
  char name[72];
  efc_rt::FunctionParams params;
  char receptor_joint[72];  // joint whose qpos is s_R
  char effector_body[72];   // body that carries the effect
  char effector_joint[72];  // geometry: joint whose qpos is measured ("" otherwise)
  double direction[3];      // fluid emitter / airflow outlet direction (object frame)
  double color[3];          // illumination colour
  double speed;             // fluid: droplet launch speed (m/s)
  double droplet_radius;    // fluid (m)
  int droplet_count;        // fluid: size of the recycled pool
  double cone_angle;        // airflow: half-angle (rad)
  double reach;             // airflow (m)
  double glow_max;          // temperature: s_E at which the glow is full (e_hi)
};

struct FunctionReadout {
  double s_R = 0, s_E = 0, measured = 0;
};

class Controller {
 public:
  // Resolves every name in `table` against the model. On failure, error()
  // says which name is missing and ok() is false.
  Controller(const mjModel* m, const FunctionBinding* table, int count);
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  // Initialises the runtime from the current state (call after mj_resetData /
  // keyframe reset and mj_forward).
  void reset(const mjModel* m, mjData* d);
  // One control step: read receptors, run the templates (in table order, which
  // the backend makes topological so chains see their driver's output), apply
  // the effects. Call from mjcb_control or before mj_step.
  void step(const mjModel* m, mjData* d);

  int count() const { return static_cast<int>(rows_.size()); }
  const FunctionReadout& readout(int i) const { return readouts_[i]; }
  const FunctionBinding& binding(int i) const { return rows_[i]; }

 private:
  struct Droplet {
    int body = -1, qpos = -1, qvel = -1;
    bool alive = false;
    double born = 0;
  };
  struct Resolved {
    int receptor_qpos = -1;
    int effector_qpos = -1;
    int actuator = -1;
    int light = -1;
    int site = -1;
    int body = -1;
    std::vector<int> glow_geoms;
    std::vector<float> base_rgba;  // 4 per glow geom
    std::vector<Droplet> droplets;
    std::vector<double> emit_times;  // for the flow window
    size_t next_droplet = 0;
  };
  // What step() reads of a row: the row without its four names, in one
  // compact array. A row is mostly names (4 x 72 bytes); reading the rows
  // themselves every step would pull several times more cache lines through
  // the cache than the templates need, evicting MuJoCo's own data.
  struct Hot {
    efc_rt::FunctionParams params;
    double direction[3];
    double color[3];
    double speed;
    int droplet_count;
    double cone_angle;
    double reach;
    double glow_max;
  };
  void apply(const mjModel* m, mjData* d, int i, int emit);
  void park(const mjModel* m, mjData* d, Droplet& drop, int index);
  void fluid(const mjModel* m, mjData* d, int i, int emit);
  void airflow(const mjModel* m, mjData* d, int i);
  void clear_air_forces(mjData* d);

  std::vector<FunctionBinding> rows_;  // names: resolving, binding(i)
  std::vector<Hot> hot_;               // the rest: every step
  std::vector<efc_rt::FunctionState> states_;
  std::vector<Resolved> resolved_;
  std::vector<FunctionReadout> readouts_;
  double floor_z_ = 0;
  std::vector<int> free_bodies_;    // bodies on a free joint: what air can push
  std::vector<int> pushed_bodies_;  // bodies whose xfrc_applied we set last step
  std::string error_;
};

}  // namespace efc_mj

#endif  // EFC_MUJOCO_H_
