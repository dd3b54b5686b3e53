// Function templates from a recording (issue 12, stage "function templates"):
// for each function of meta.json (receptor part R, effector part E), which
// effect E shows (geometry, illumination, temperature, fluid, airflow), which
// mapping ties it to R (binary, step, linear, cumulative), and the parameters.
//
// Method (pipeline/templates/README.md has the details):
//  1. s_R(t) is the receptor's joint position q. For every effect hypothesis
//     one signal y_k(t) is measured at the effector (frame_signals.h): its own
//     joint position (geometry), the brightness of its pixels (a glow:
//     illumination), their redness (a red-hot blend: temperature), small
//     unmasked foreground blobs below it (droplets: fluid) and around it
//     (air motes: airflow).
//  2. Each signal is explained by every mapping model (mapping_fit.h: the
//     runtime's equations re-implemented, an affine scale a + b u(t) and an
//     optional first-order lag) and by a null model (a constant). Models are
//     scored by BIC with the frame count corrected for autocorrelated
//     residuals; no threshold tuned to a data set.
//  3. The effect is the hypothesis whose signal the receptor explains best
//     (largest BIC gain over its null); the mapping is the best model of that
//     signal; mapping types share equal prior mass (variants split theirs).
//     The posterior of the pair is the confidence.
//  4. Parameters in receptor units from the fit (threshold, hysteresis,
//     gain, delta from the step heights, time constant from the lag); ranges
//     are the spec's physical defaults where pixels cannot measure units,
//     positions (light, emitter, outlet) in the object frame from the data.
//  5. Optionally a vision-language model (vlm_client.h) votes, as a prior.
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"
#include "sequence/sequence.h"

namespace efc::pipeline {

struct PartObservation {
  std::string name, role;                       // role from meta.json
  std::string joint_type;                       // "fixed", "revolute", "continuous", "prismatic"
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(), origin = Eigen::Vector3d::Zero();  // object frame
  double range_lo = 0, range_hi = 0;            // joint range (rad or m); 0,0 for fixed
  std::vector<double> q;                        // joint position per frame (NaN = unknown); empty for fixed
  // The same joint's position from the hand's contacts alone, where q came
  // from the part's own track (empty otherwise). A round knob's or a small
  // button's track may not show its motion while the hand's grip does: the
  // templates try both as s_R and keep the one the effector follows.
  std::vector<double> q_hand;
  // q where the part's track measured it, NaN where it was bridged between
  // measurements (empty: q is all measured). An effector's geometry signal
  // reads it: a lid opened out of view did not stay shut.
  std::vector<double> q_seen;
  std::vector<Eigen::Isometry3d> motion;        // per frame: the part's pose in the object frame relative to q = 0 (identity for fixed)
  Eigen::AlignedBox3d bounds;                   // object frame, at q = 0
  std::vector<Eigen::Vector3d> surface;         // fused surface points, object frame, at q = 0 (may be empty)
};

struct TemplateInput {
  const seq::Sequence* sequence = nullptr;      // opened; frames read on demand
  std::vector<Eigen::Isometry3d> camera_to_world;   // per frame (refined poses)
  Eigen::Isometry3d object_to_world = Eigen::Isometry3d::Identity();
  std::vector<PartObservation> parts;
  std::vector<seq::FunctionRef> functions;      // from meta.json
};

struct InferredFunction {
  std::string name, receptor, effector;
  nlohmann::json mapping, effect;               // spec v1 MAPPING and EFFECT objects (object frame for positions)
  double confidence = 0;                        // posterior of the chosen (effect, mapping), 0..1
  nlohmann::json report;                        // per-model scores (BIC), residuals, signals' summary
};

struct TemplateOptions {
  std::string vlm_endpoint;   // empty: off. e.g. "http://127.0.0.1:8765/v1" (OpenAI-compatible; POST {endpoint}/chat/completions)
  std::string vlm_model = "gpt-4o";
  std::string vlm_api_key;    // from env EFC_VLM_API_KEY when empty
  double vlm_timeout_s = 60;
  int threads = 2;
};

// Infers every function of input.functions. Problems (a receptor that never moves, an effector never seen)
// are warnings in diags (code range E1060-E1069, register them in compiler/codes.cc) and yield a best guess
// with low confidence; never a crash.
std::vector<InferredFunction> infer_templates(const TemplateInput& input, const TemplateOptions& options, Diagnostics& diags);

}  // namespace efc::pipeline
