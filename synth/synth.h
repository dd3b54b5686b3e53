// `efc synth SPEC -o SEQ`: a synthetic egocentric RGB-D sequence of a hand
// operating the object, with exact ground truth (shared/spec/sequence.md).
//
// The object is compiled for MuJoCo exactly as `efc play` compiles it, placed
// in a room (synth/scene.h), operated by a mocap hand (synth/hand.h) through
// a receptor schedule (synth/timeline.h) and filmed by a moving head camera
// (synth/camera_path.h). The physics and the templates run through the same
// runtime binding as `efc play`; truth/profile.csv holds the receptor targets
// the run followed, so `efc play SPEC --profile csv:SEQ/truth/profile.csv`
// reproduces truth/joints.csv and truth/effects.csv.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"
#include "runtime/efc_profile.h"
#include "synth/suite/knobs.h"

namespace efc::synth {

struct SynthOptions {
  int frames = 150;
  double fps = 30;
  int width = 640, height = 480;
  // How each receptor moves while the hand operates it (cli.md's profiles;
  // csv:FILE is not offered: the hand's schedule owns the timeline).
  Profile profile;
  uint64_t seed = 0;
  SceneKnobs knobs;  // knobs.noise is the noise level
  bool preview = false;  // also write SEQ/preview.png (a contact sheet)
  // truth/spec.json: the spec as canonical JSON (the CLI renders it from the
  // user's file); its meshes are copied beside it.
  std::string spec_json;
  double dt = 0.002;     // physics step (s), as efc play
  int png_compression = 1;  // zlib level of every PNG written
  int threads = 0;       // encoding threads; 0 = one per core
  // Progress lines (frames done, rate, time left); none when empty.
  std::function<void(const std::string&)> progress;
};

struct SynthStats {
  int frames = 0;
  double seconds = 0;        // wall time of the whole run
  double render_seconds = 0; // of which rendering (RGB + depth + segmentation)
  uint64_t bytes = 0;        // size of the folder written
};

// Writes the sequence into out_dir (created; must not exist or be empty),
// all or nothing: it is built in a sibling temporary folder and renamed.
// Returns the CLI exit code: 0, 1 (the
// spec cannot be operated: diagnostics say why) or 2 (files, rendering).
int synthesize(const Object& obj, const SynthOptions& opts, const std::string& out_dir,
               Diagnostics& diags, SynthStats* stats);

}  // namespace efc::synth
