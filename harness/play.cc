#include "harness/play.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "backends/common/lowering.h"
#include "harness/mujoco_errors.h"
#include "harness/playback.h"
#include "harness/plot_svg.h"
#include "harness/render.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

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
  Playback run;
  if (const int rc = run.open(obj, opts.profile, opts.duration, opts.dt, diags)) return rc;
  mjModel* m = run.model();
  mjData* d = run.data();
  const efc_mj::Controller& controller = run.controller();

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
      run.control(t);
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
      run.advance();
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
