// Fitting the four mapping models of the spec (MAPPING in efc-spec-v1.md) to a
// receptor state s_R(t) and an observed effect signal y(t), scored by BIC.
//
// A model gives a unit profile u(t) from s_R (the runtime's semantics,
// re-implemented here because pipeline/ may not include runtime/):
//   binary      u = [s_R >= t]                      params t
//   binary/latch u toggles at each press             params t
//   step        on once s_R > t, off once s_R < t-h   params t, h
//   linear      u = clamp((s_R - s0) / (s1 - s0))     params s0, s1
//   cumulative  u = min(presses, P)                   params t (+ P when it clamps)
// A press is s_R rising through t after having been below t - band (band =
// 1 % of the receptor range, as the runtime debounces). The signal is
// y = a + b * lag(u) + e, a and b by least squares (the signal's units are
// unknown), lag: none, first order (a temperature, droplets) or two in
// cascade with a dead time (a driven joint), integrating u's mean over each
// frame's interval (sub-frame switch times; a driven joint's fast lags run
// 8 steps a frame, as it may settle within one). The errors e are AR(1): one
// Cochrane-Orcutt step, BIC = m log(RSS_w / m) + k log m over the m
// innovations, with a noise floor (a camera that moves slowly makes
// neighbouring frames' errors alike; whitened, they no longer pass for a
// response). The null model (a constant, AR(1) errors too) competes with
// them: a signal the receptor does not explain keeps the null. Grids, then
// each type's best refined on a finer grid (pipeline/templates/README.md).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace efc::pipeline {

struct MappingModel {
  std::string type;      // "null", "binary", "step", "linear", "cumulative"
  bool latching = false;  // binary
  double threshold = 0, hysteresis = 0;  // binary, step, cumulative
  double s0 = 0, s1 = 0;                 // linear: s_R where u = 0 and u = 1
  int saturate = 0;                      // cumulative: presses to saturate (0: never saturated in view)
  double tau = 0;                        // lag (s)
  int lag_order = 1;                     // 1: first order; 2: two in cascade (a driven joint)
  double lag_ratio = 1;                  // lag_order 2: the second lag's time constant / tau
  double delay = 0;                      // dead time before the lag (s; a driven joint)
  double lag_start = NAN;                // the lag's first state (NaN: settled at the first target)
  double a = 0, b = 0;                   // y = a + b u
  int presses = 0;                       // presses seen (binary latching, cumulative)
  std::vector<double> step_heights;      // cumulative: y's change at each press (signal units)
  double rss = 0, sigma = 0;             // of the innovations (AR(1) errors whitened)
  double rho = 0;                        // the errors' AR(1) coefficient
  int pairs = 0;                         // consecutive observed samples (the innovations)
  int k = 0;                             // parameters (incl. a, b, sigma)
  double bic = 0;
  // step: the log of its likelihood's mean over its hysteresis prior
  // relative to the best there (<= 0); the mapping types are chosen with
  // it in place of the hysteresis's log(n) in bic (apply_hysteresis_occam)
  double hysteresis_occam = 0;
  bool valid = false;
};

struct MappingSeries {
  std::vector<double> s_R;  // per frame; NaN = unknown: interpolated between known frames, held before
                            // the first; after the last, y is not scored (nothing says where s_R is)
  std::vector<double> y;    // per frame; NaN = not observed (skipped)
  double dt = 1.0 / 30;
  double r_lo = 0, r_hi = 1;  // receptor range (continuous: 0, 2 pi)
  bool allow_lag = true;
  int max_lag_order = 1;    // 2 also tries two lags in cascade (a joint's drive: smooth start and stop)
  double noise_floor = 0;   // smallest noise sigma of y (its units); 0: 1e-4 of y's spread
  // For the on/off models (binary, step): +1: y may only rise when the mapping is on (a heated part reddens; a
  // cooler shows nothing), -1: only fall, 0: either.
  int b_sign = 0;
  // The sign holds for every model, not only the on/off ones: a linear or
  // cumulative map's response then rises with its target too.
  bool b_sign_all_models = false;
  // The lag may start away from the first target (a temperature starts at
  // e_lo whatever the mapping asks at rest: a 'minus' button or a falling
  // dial is hot at rest only after warming up).
  bool lag_starts_anywhere = false;
  // Only lagged models count (a temperature has thermal inertia: it cannot
  // follow its target within a frame); the best instant model competes
  // with the null, and delta_bic is the gain over the better of the two.
  bool require_lag = false;
  // y is binned: observed once per bin_frames frames (from frame 0 on), its
  // sample the bin's mean (or a transform of it: droplets' and motes' root),
  // so a model's response is averaged over the bin's frames too: a switch
  // inside a bin shows as the fraction of the bin it was on, not as a ramp
  // that only a linear map could fit.
  int bin_frames = 1;
};

struct MappingFitResult {
  MappingModel null_model;
  std::vector<MappingModel> best;  // best of each: binary, binary latching, step, linear, cumulative
  int n = 0;                       // observed samples
  double n_eff = 0;                // after the autocorrelation discount
  double delta_bic = 0;            // null BIC - best BIC (evidence that s_R explains y)
  int best_index = -1;             // into best, by BIC (a step by choice_bic) + prior
  std::vector<double> posterior;   // per entry of best (prior x exp(-BIC/2)), sums to 1
};

// Prior mass of each entry of MappingFitResult::best: the four mapping types
// equally, binary's split between its two variants; a continuous receptor
// (no stops) is rarely an on/off switch, so binary gets less there.
std::vector<double> mapping_prior(bool continuous_receptor);

MappingFitResult fit_mappings(const MappingSeries& series, const std::vector<double>& prior);

// The unit profile of a model over s_R (no lag), for tests and reports.
std::vector<double> model_profile(const MappingModel& m, const std::vector<double>& s_R, double band);

nlohmann::json to_json(const MappingModel& m);

}  // namespace efc::pipeline
