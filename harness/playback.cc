#include "harness/playback.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "backends/common/lowering.h"
#include "backends/common/naming.h"
#include "backends/mujoco/mujoco_backend.h"
#include "harness/mujoco_errors.h"

namespace efc {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool read_text(const std::string& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  *text = ss.str();
  return static_cast<bool>(in) || in.eof();
}

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  return static_cast<bool>(out);
}

}  // namespace

Playback::Playback() = default;

Playback::~Playback() {
  controller_.reset();
  if (data_) mj_deleteData(data_);
  if (model_) mj_deleteModel(model_);
}

int Playback::open(const Object& obj, const Profile& profile, double duration, double dt,
                   Diagnostics& diags, const EditMjcf& edit_mjcf) {
  obj_ = &obj;
  profile_ = profile;
  duration_ = duration;
  install_mujoco_handlers();
  take_mujoco_warnings();
  tmp_ = std::make_unique<TempDir>("efc-play");
  if (tmp_->path().empty()) {
    diags.error("E0900", obj.file, 0, 0, "", "cannot create a temporary folder");
    return 2;
  }
  model_dir_ = tmp_->path().string();
  MjcfOptions mjcf;
  mjcf.drive_receptors = true;
  mjcf.timestep = dt;
  std::string xml_path;
  if (!write_mujoco_model(obj, model_dir_, mjcf, diags, &xml_path)) return 2;
  if (edit_mjcf) {
    std::string text, error;
    if (!read_text(xml_path, &text)) {
      diags.error("E0900", xml_path, 0, 0, "", "cannot read the compiled model");
      return 2;
    }
    if (!edit_mjcf(&text, &error)) {
      diags.error("E0901", obj.file, 0, 0, "", error);
      return 1;
    }
    if (!write_text(xml_path, text)) {
      diags.error("E0900", xml_path, 0, 0, "", "cannot write the edited model");
      return 2;
    }
  }

  char load_error[1024] = "";
  try {
    model_ = mj_loadXML(xml_path.c_str(), nullptr, load_error, sizeof load_error);
    if (!model_) {
      diags.error("E0901", obj.file, 0, 0, "", std::string("MuJoCo rejected the compiled model: ") + load_error,
                  "this is a compiler defect: please report it with the spec");
      return 1;
    }
    data_ = mj_makeData(model_);
  } catch (const MujocoError& e) {
    diags.error("E0901", obj.file, 0, 0, "", e.what());
    return 1;
  }
  mjModel* m = model_;
  mjData* d = data_;
  m->opt.timestep = dt;
  const int key = mj_name2id(m, mjOBJ_KEY, "initial");
  if (key >= 0) mj_resetDataKeyframe(m, d, key);
  mj_forward(m, d);

  table_ = build_bindings(obj);
  controller_ = std::make_unique<efc_mj::Controller>(m, table_.data(), static_cast<int>(table_.size()));
  if (!controller_->ok()) {
    diags.error("E0901", obj.file, 0, 0, "", "binding the templates failed: " + controller_->error());
    return 1;
  }
  for (int pi : lowering::profile_driven_receptors(obj)) {
    const Part& p = obj.parts[pi];
    Drive dr;
    dr.part = pi;
    dr.actuator = mj_name2id(m, mjOBJ_ACTUATOR, naming::mjcf_receptor_drive(p.name).c_str());
    const int jid = mj_name2id(m, mjOBJ_JOINT, p.name.c_str());
    if (dr.actuator < 0 || jid < 0) {
      diags.error("E0901", obj.file, 0, 0, "", "compiled model has no drive for receptor '" + p.name + "'");
      return 1;
    }
    dr.qpos = m->jnt_qposadr[jid];
    if (p.joint->has_range) {
      dr.lo = p.joint->lo;
      dr.hi = p.joint->hi;
    } else {  // continuous receptors sweep one turn
      dr.lo = 0;
      dr.hi = 2 * kPi;
    }
    dr.q0 = d->qpos[dr.qpos];
    drives_.push_back(dr);
    if (profile.kind == Profile::Kind::Csv && !profile.csv_parts.count(p.name))
      diags.warning("W0902", profile.csv_path, 1, 1, "",
                    "profile CSV has no column for receptor '" + p.name + "'; it holds its initial position");
  }
  // Every receptor starts where its profile starts (ramp, sweep and press:N at
  // the lower limit; hold:V at the initial position; csv:FILE at its first
  // row), so the first row (t = 0) and the templates' initial state see the
  // profile's start, not the spec's initial position: a receptor that jumped
  // there during the first steps would cross a threshold at the initial
  // position twice.
  for (const Drive& dr : drives_) {
    const Joint& j = *obj.parts[dr.part].joint;
    double q = profile_target(profile, obj.parts[dr.part].name, dr.lo, dr.hi, dr.q0, 0.0, duration);
    if (j.has_range) q = std::clamp(q, j.lo, j.hi);
    d->qpos[dr.qpos] = q;
    d->ctrl[dr.actuator] = q;
  }
  mj_forward(m, d);
  controller_->reset(m, d);

  if (profile.kind == Profile::Kind::Hold && profile.hold_at == Profile::HoldAt::Value) {
    for (const Drive& dr : drives_)
      if (profile.hold_value < dr.lo || profile.hold_value > dr.hi)
        diags.warning("W0903", obj.file, 0, 0, "",
                      "hold value " + std::to_string(profile.hold_value) + " is outside the range of receptor '" +
                          obj.parts[dr.part].name + "'; its joint limit stops it");
  }
  return 0;
}

void Playback::control(double t) {
  for (const Drive& dr : drives_)
    data_->ctrl[dr.actuator] =
        profile_target(profile_, obj_->parts[dr.part].name, dr.lo, dr.hi, dr.q0, t, duration_);
  controller_->step(model_, data_);
}

void Playback::advance() { mj_step(model_, data_); }

}  // namespace efc
