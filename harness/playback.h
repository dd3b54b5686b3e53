// One playback of an object in MuJoCo, as `efc play` defines it: the object
// compiled for MuJoCo with a drive on every receptor no function drives, the
// receptors started where the profile starts, and every control step the
// profile's targets and then the function templates through the runtime's
// MuJoCo binding. `efc play` logs it; `efc synth` films it (and adds a room,
// a hand and a camera through edit_mjcf, visual only), so the two give the
// same joints and effects for the same profile.
#pragma once

#include <mujoco/mujoco.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backends/common/temp_dir.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"
#include "runtime/efc_profile.h"
#include "runtime/mujoco/efc_mujoco.h"

namespace efc {

class Playback {
 public:
  // A receptor the profile moves, through its efc_drive_<part> actuator.
  struct Drive {
    int part = -1;      // index into Object::parts
    int actuator = -1;
    int qpos = -1;
    double lo = 0, hi = 0, q0 = 0;  // the profile's range; q0 the initial position
  };
  // Rewrites the compiled MJCF document before it is loaded (false with
  // *error to stop). Whatever it adds must not change the dynamics.
  using EditMjcf = std::function<bool(std::string* mjcf, std::string* error)>;

  Playback();
  ~Playback();
  Playback(const Playback&) = delete;
  Playback& operator=(const Playback&) = delete;

  // Compiles, edits, loads and resets (the state at t = 0). Returns the CLI
  // exit code: 0, 1 (the model or its bindings are wrong), 2 (files).
  int open(const Object& obj, const Profile& profile, double duration, double dt, Diagnostics& diags,
           const EditMjcf& edit_mjcf = {});

  // The control step at time t: every drive's target from the profile, then
  // the templates. The readouts describe the state at t.
  void control(double t);
  // One physics step (mj_step).
  void advance();

  mjModel* model() { return model_; }
  mjData* data() { return data_; }
  const efc_mj::Controller& controller() const { return *controller_; }
  const std::vector<Drive>& drives() const { return drives_; }
  // The folder the model was compiled into (its meshes), alive with this object.
  const std::string& model_dir() const { return model_dir_; }

 private:
  const Object* obj_ = nullptr;
  Profile profile_;
  double duration_ = 0;
  std::unique_ptr<TempDir> tmp_;
  std::string model_dir_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  std::vector<efc_mj::FunctionBinding> table_;
  std::unique_ptr<efc_mj::Controller> controller_;
  std::vector<Drive> drives_;
};

}  // namespace efc
