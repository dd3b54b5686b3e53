// `efc play`: the MuJoCo playback harness (shared/spec/cli.md). Compiles the
// object for MuJoCo into a temporary folder, drives every receptor that no
// function drives through a profile, runs the function templates each step
// through the runtime's MuJoCo binding, and logs t, F.s_R, F.s_E, F.measured.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"
#include "efc_profile.h"

namespace efc {

struct PlayOptions {
  Profile profile;
  double duration = 5.0;  // s
  double dt = 0.002;      // s (MuJoCo timestep)
  std::string csv_path;   // "" = no CSV
  std::string render_dir;  // "" = no frames
  double render_fps = 30;
  int render_width = 640, render_height = 480;
  std::string plot_path;  // "" = no SVG
  // Called with a progress line every 10% of the run (none when empty): the
  // CLI shows them on a terminal, through its diagnostics.
  std::function<void(const std::string&)> progress;
};

struct PlayLog {
  std::vector<std::string> columns;       // "t", then F.s_R, F.s_E, F.measured per function
  std::vector<std::vector<double>> rows;  // one per step, the first at t = 0
  int frames_written = 0;
  std::vector<std::string> mujoco_warnings;
};

// Returns the CLI exit code: 0 ok, 1 the input is wrong (diagnostics say
// why), 2 a file could not be written.
int play(const Object& obj, const PlayOptions& opts, Diagnostics& diags, PlayLog* log);

// Writes the log as CSV (to a temporary file, then renamed).
bool write_log_csv(const PlayLog& log, const std::string& path, std::string* error);

}  // namespace efc
