#include "harness/play.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>

#include "backends/common/lowering.h"
#include "backends/common/naming.h"
#include "backends/common/temp_dir.h"
#include "backends/mujoco/mujoco_backend.h"
#include "compiler/core/resolve.h"
#include "harness/mujoco_errors.h"
#include "harness/plot_svg.h"
#include "harness/render.h"
#include "runtime/mujoco/efc_mujoco.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

struct Drive {
  int part = -1;
  int actuator = -1;
  int qpos = -1;
  double lo = 0, hi = 0, q0 = 0;
};

bool write_frames_dir(const std::string& dir, Diagnostics& diags) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    diags.error("E0900", dir, 0, 0, "", "cannot create render folder: " + ec.message());
    return false;
  }
  return true;
}

}  // namespace

bool write_log_csv(const PlayLog& log, const std::string& path, std::string* error) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) {
      *error = "cannot write '" + path + "'";
      return false;
    }
    for (size_t i = 0; i < log.columns.size(); ++i) out << (i ? "," : "") << log.columns[i];
    out << "\n";
    char buf[32];
    for (const auto& row : log.rows) {
      for (size_t i = 0; i < row.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.9g", row[i]);
        out << (i ? "," : "") << buf;
      }
      out << "\n";
    }
    if (!out) {
      *error = "cannot write '" + path + "'";
      return false;
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    *error = "cannot write '" + path + "': " + ec.message();
    return false;
  }
  return true;
}

int play(const Object& obj, const PlayOptions& opts, Diagnostics& diags, PlayLog* log) {
  install_mujoco_handlers();
  take_mujoco_warnings();
  TempDir tmp("efc-play");
  if (tmp.path().empty()) {
    diags.error("E0900", obj.file, 0, 0, "", "cannot create a temporary folder");
    return 2;
  }
  MjcfOptions mjcf;
  mjcf.drive_receptors = true;
  mjcf.timestep = opts.dt;
  std::string xml_path;
  if (!write_mujoco_model(obj, tmp.path().string(), mjcf, diags, &xml_path)) return 2;

  char load_error[1024] = "";
  std::unique_ptr<mjModel, ModelDeleter> model;
  std::unique_ptr<mjData, DataDeleter> data;
  try {
    model.reset(mj_loadXML(xml_path.c_str(), nullptr, load_error, sizeof load_error));
    if (!model) {
      diags.error("E0901", obj.file, 0, 0, "",
                  std::string("MuJoCo rejected the compiled model: ") + load_error,
                  "this is a compiler defect: please report it with the spec");
      return 1;
    }
    data.reset(mj_makeData(model.get()));
  } catch (const MujocoError& e) {
    diags.error("E0901", obj.file, 0, 0, "", e.what());
    return 1;
  }
  mjModel* m = model.get();
  mjData* d = data.get();
  m->opt.timestep = opts.dt;
  const int key = mj_name2id(m, mjOBJ_KEY, "initial");
  if (key >= 0) mj_resetDataKeyframe(m, d, key);
  mj_forward(m, d);

  const std::vector<efc_mj::FunctionBinding> table = build_bindings(obj);
  efc_mj::Controller controller(m, table.data(), static_cast<int>(table.size()));
  if (!controller.ok()) {
    diags.error("E0901", obj.file, 0, 0, "", "binding the templates failed: " + controller.error());
    return 1;
  }
  // The receptors the profile moves, through their efc_drive_<part> actuators.
  std::vector<Drive> drives;
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
    drives.push_back(dr);
    if (opts.profile.kind == Profile::Kind::Csv && !opts.profile.csv_parts.count(p.name))
      diags.warning("W0902", opts.profile.csv_path, 1, 1, "",
                    "profile CSV has no column for receptor '" + p.name + "'; it holds its initial position");
  }
  // Every receptor starts where its profile starts (ramp, sweep and press:N at
  // the lower limit; hold:V at the initial position; csv:FILE at its first
  // row), so the first row (t = 0) and the templates' initial state see the
  // profile's start, not the spec's initial position: a receptor that jumped
  // there during the first steps would cross a threshold at the initial
  // position twice.
  for (const Drive& dr : drives) {
    const Joint& j = *obj.parts[dr.part].joint;
    double q = profile_target(opts.profile, obj.parts[dr.part].name, dr.lo, dr.hi, dr.q0, 0.0, opts.duration);
    if (j.has_range) q = std::clamp(q, j.lo, j.hi);
    d->qpos[dr.qpos] = q;
    d->ctrl[dr.actuator] = q;
  }
  mj_forward(m, d);
  controller.reset(m, d);

  if (opts.profile.kind == Profile::Kind::Hold && opts.profile.hold_at == Profile::HoldAt::Value) {
    for (const Drive& dr : drives)
      if (opts.profile.hold_value < dr.lo || opts.profile.hold_value > dr.hi)
        diags.warning("W0903", obj.file, 0, 0, "",
                      "hold value " + std::to_string(opts.profile.hold_value) +
                          " is outside the range of receptor '" + obj.parts[dr.part].name +
                          "'; its joint limit stops it");
  }

  log->columns = {"t"};
  for (int i = 0; i < controller.count(); ++i) {
    const std::string n = controller.binding(i).name;
    log->columns.push_back(n + ".s_R");
    log->columns.push_back(n + ".s_E");
    log->columns.push_back(n + ".measured");
  }

  std::unique_ptr<OffscreenRenderer> renderer;
  if (!opts.render_dir.empty()) {
    if (!write_frames_dir(opts.render_dir, diags)) return 2;
    renderer = std::make_unique<OffscreenRenderer>(m, opts.render_width, opts.render_height);
    if (!renderer->ok()) {
      diags.error("E0902", obj.file, 0, 0, "", "offscreen rendering unavailable: " + renderer->error());
      return 2;
    }
  }

  const long steps = std::lround(opts.duration / opts.dt);
  const double frame_period = opts.render_fps > 0 ? 1.0 / opts.render_fps : 0;
  double next_frame = 0;
  int last_percent = -1;
  try {
    for (long k = 0; k <= steps; ++k) {
      const double t = k * opts.dt;  // exact grid, not the accumulated d->time
      for (const Drive& dr : drives)
        d->ctrl[dr.actuator] = profile_target(opts.profile, obj.parts[dr.part].name, dr.lo, dr.hi,
                                              dr.q0, t, opts.duration);
      controller.step(m, d);
      std::vector<double> row{t};
      for (int i = 0; i < controller.count(); ++i) {
        const efc_mj::FunctionReadout& r = controller.readout(i);
        row.insert(row.end(), {r.s_R, r.s_E, r.measured});
      }
      log->rows.push_back(std::move(row));
      if (renderer && t + 1e-12 >= next_frame) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", log->frames_written);
        if (!renderer->render_png(m, d, (fs::path(opts.render_dir) / name).string())) {
          diags.error("E0900", opts.render_dir, 0, 0, "", "cannot write frame: " + renderer->error());
          return 2;
        }
        log->frames_written++;
        next_frame += frame_period;
      }
      if (k == steps) break;
      mj_step(m, d);
      if (opts.progress && steps > 0) {
        const int percent = static_cast<int>(100 * k / steps);
        if (percent / 10 != last_percent / 10) {
          char line[96];
          std::snprintf(line, sizeof line, "play: %3d%% (t = %.2f s of %.2f s)", percent, t,
                        opts.duration);
          opts.progress(line);
          last_percent = percent;
        }
      }
    }
  } catch (const MujocoError& e) {
    diags.error("E0901", obj.file, 0, 0, "", e.what());
    return 1;
  }
  log->mujoco_warnings = take_mujoco_warnings();
  for (const std::string& w : log->mujoco_warnings)
    diags.warning("W0901", obj.file, 0, 0, "", "MuJoCo warned during playback: " + w);

  if (!opts.csv_path.empty()) {
    std::string error;
    if (!write_log_csv(*log, opts.csv_path, &error)) {
      diags.error("E0900", opts.csv_path, 0, 0, "", error);
      return 2;
    }
  }
  if (!opts.plot_path.empty()) {
    std::vector<double> ts;
    for (const auto& row : log->rows) ts.push_back(row[0]);
    std::vector<PlotPanel> panels;
    for (int i = 0; i < controller.count(); ++i) {
      const std::string fname = controller.binding(i).name;
      const Function* fn = nullptr;
      for (const Function& g : obj.functions)
        if (g.name == fname) fn = &g;
      PlotSeries s_r{"s_R", {}}, s_e{"s_E", {}}, meas{"measured", {}};
      for (const auto& row : log->rows) {
        s_r.values.push_back(row[1 + 3 * i]);
        s_e.values.push_back(row[2 + 3 * i]);
        meas.values.push_back(row[3 + 3 * i]);
      }
      const bool prismatic = obj.parts[fn->receptor_index].joint->type == JointType::Prismatic;
      panels.push_back({fname + ": receptor " + fn->receptor, prismatic ? "m" : "rad", {s_r}});
      panels.push_back({fname + ": " + to_string(fn->effect.type) + " of " + fn->effector,
                        lowering::effect_unit(obj, *fn), {s_e, meas}});
    }
    std::string error;
    if (!write_plot_svg(opts.plot_path, ts, panels, &error)) {
      diags.error("E0900", opts.plot_path, 0, 0, "", error);
      return 2;
    }
  }
  return 0;
}

}  // namespace efc
