// infer_templates: the signals, the fits, the choice (template_input.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <limits>

#include "pipeline/templates/effect_names.h"
#include "pipeline/templates/frame_signals.h"
#include "pipeline/templates/mapping_fit.h"
#include "pipeline/templates/mapping_names.h"
#include "pipeline/templates/template_input.h"
#include "pipeline/templates/template_json.h"
#include "pipeline/templates/vlm_client.h"
#include "pipeline/templates/vlm_images.h"

namespace efc::pipeline {
namespace {

const char* const kEffects[5] = {"geometry", "illumination", "temperature", "fluid", "airflow"};
const char* const kMappings[4] = {"binary", "step", "linear", "cumulative"};
// MappingFitResult::best entries -> mapping type index.
constexpr int kTypeOf[5] = {0, 0, 1, 2, 3};
// Evidence (BIC gain over the null) below which a signal is not believed
// to respond: 10, "very strong" on Kass and Raftery's scale of 2 ln B.
constexpr double kMinEvidence = 10.0;
// A driven joint's pose is measured to a fraction of a per cent of its
// travel, but the lags model its drive only to about one per cent of what
// it moved (a servo settling within a frame, opening against gravity and
// closing with it): below that, misfit is not noise, and a model's spare
// parameter (a step's second edge) would win by bending the switch's
// timing to it.
constexpr double kDriveFloor = 0.01;

int part_index(const TemplateInput& in, const std::string& name) {
  for (size_t i = 0; i < in.parts.size(); ++i)
    if (in.parts[i].name == name) return static_cast<int>(i);
  return -1;
}

bool movable(const PartObservation& p) { return p.joint_type != "fixed" && !p.joint_type.empty(); }

nlohmann::json summary(const std::vector<double>& y) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0;
  int n = 0;
  for (double v : y)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v), sum += v, ++n;
  if (!n) return {{"observed", 0}};
  return {{"observed", n}, {"min", lo}, {"max", hi}, {"mean", sum / n}};
}

// Spread of a series' finite values (for noise floors).
double spread(const std::vector<double>& y) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : y)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  return hi > lo ? hi - lo : 0;
}

// A three-frame running median over the observed frames: one frame of a
// swapped or missed mask does not make a step.
std::vector<double> median3(const std::vector<double>& y) {
  std::vector<double> out(y);
  for (size_t i = 1; i + 1 < y.size(); ++i) {
    const double a = y[i - 1], b = y[i], c = y[i + 1];
    if (std::isfinite(a) && std::isfinite(b) && std::isfinite(c)) out[i] = std::max(std::min(a, b), std::min(std::max(a, b), c));
  }
  return out;
}

// Blob areas (droplets, motes) are sparse counts: a few blobs come and go
// from frame to frame, and a one-frame median would erase them. They are
// summed over blocks of kBlobBin frames (one value at each block's middle
// frame, the others unobserved) and square-rooted, which makes a count's
// noise about the same whatever its mean (Anscombe), as the Gaussian
// likelihood of the fits assumes.
constexpr int kBlobBin = 5;

std::vector<double> binned_root(const std::vector<double>& y) {
  std::vector<double> out(y.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t b = 0; b < y.size(); b += kBlobBin) {
    double sum = 0;
    int n = 0;
    for (size_t i = b; i < std::min(y.size(), b + kBlobBin); ++i)
      if (std::isfinite(y[i])) sum += y[i], ++n;
    if (2 * n > kBlobBin) out[std::min(y.size() - 1, b + kBlobBin / 2)] = std::sqrt(sum / n);
  }
  return out;
}

// A model for a mapping type the data could not fit (no signal): the spec's
// defaults over the receptor range.
MappingModel default_model(int type, double r_lo, double r_hi) {
  MappingModel m;
  m.type = kMappings[type];
  m.threshold = type == 1 ? r_lo + 0.7 * (r_hi - r_lo) : 0.5 * (r_lo + r_hi);
  m.hysteresis = 0.02 * (r_hi - r_lo);
  m.s0 = r_lo;
  m.s1 = r_hi;
  m.b = 1;
  m.presses = 2;
  return m;
}

// A receptor last measured away from rest (further than this share of its
// range from q = 0) is not taken to have stayed there afterwards.
constexpr double kRestShare = 0.1;

// The last frame where v is finite; -1 when none is.
int last_finite(const std::vector<double>& v) {
  int last = static_cast<int>(v.size()) - 1;
  while (last >= 0 && !std::isfinite(v[last])) --last;
  return last;
}

// s after frame `last`: held at s[last], or unknown (NaN).
std::vector<double> after_last(std::vector<double> s, int last, bool hold) {
  if (last < 0 || last >= static_cast<int>(s.size())) return s;
  for (size_t f = last + 1; f < s.size(); ++f) s[f] = hold ? s[last] : std::numeric_limits<double>::quiet_NaN();
  return s;
}

// s after its last measurement (the last finite value of `seen`, the same
// length): held where that was at rest, unknown otherwise. A track lost
// while the part still moved (the grip gone with the hand letting go of a
// lever on its way back) would hold a position the part left, and the
// effect's return to off would read as a ramp; a part left at rest stays.
std::vector<double> unknown_after_last_seen(const std::vector<double>& s, const std::vector<double>& seen, double r_lo,
                                            double r_hi) {
  const int last = last_finite(seen);
  if (last < 0 || !std::isfinite(s[last])) return s;
  return after_last(s, last, std::abs(s[last]) <= kRestShare * (r_hi - r_lo));
}

struct Hypothesis {
  bool has_signal = false;
  MappingFitResult fit;
  double evidence = 0;                  // BIC gain over the null
  std::vector<double> mapping_post{0.25, 0.25, 0.25, 0.25};
  nlohmann::json signal;
};

}  // namespace

std::vector<InferredFunction> infer_templates(const TemplateInput& input, const TemplateOptions& options,
                                              Diagnostics& diags) {
  std::vector<InferredFunction> out;
  if (!input.sequence) return out;
  const seq::Meta& meta = input.sequence->meta();
  const std::string seq_file = input.sequence->dir() + "/meta.json";
  const double dt = meta.fps > 0 ? 1.0 / meta.fps : 1.0 / 30;

  // Every effector's pixels, in one pass over the frames.
  std::vector<int> effectors;
  for (const seq::FunctionRef& f : input.functions) {
    const int e = part_index(input, f.effector);
    if (e >= 0 && std::find(effectors.begin(), effectors.end(), e) == effectors.end()) effectors.push_back(e);
  }
  const auto t0 = std::chrono::steady_clock::now();
  int failed = 0;
  const std::vector<EffectorSignals> signals = measure_effectors(input, effectors, options.threads, &failed);
  const double measure_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (failed > 0)
    diags.warning("E1065", seq_file, 0, 0, "",
                  std::to_string(failed) + " of " + std::to_string(meta.frames) +
                      " frames could not be read; the function templates use the rest",
                  "efc check-sequence SEQ names each bad file");

  std::string vlm_why;
  const bool vlm_on = !options.vlm_endpoint.empty();
  const bool vlm_ok = vlm_on && vlm_available(&vlm_why);
  if (vlm_on && !vlm_ok)
    diags.warning("E1064", seq_file, 0, 0, "", "the vision-language adapter is unavailable: " + vlm_why,
                  "install libcurl (libcurl4) or leave the endpoint unset");

  // The effects each effector is already given: two functions may not set
  // the same effect of one part (efc check, E0307), so a later function on
  // that part takes its best effect among the others.
  std::map<std::string, std::set<int>> effects_taken;
  for (size_t fi = 0; fi < input.functions.size(); ++fi) {
    const auto tf = std::chrono::steady_clock::now();
    const seq::FunctionRef& F = input.functions[fi];
    const std::string where = "/functions/" + std::to_string(fi);
    InferredFunction R;
    R.name = F.name;
    R.receptor = F.receptor;
    R.effector = F.effector;
    const int ri = part_index(input, F.receptor), ei = part_index(input, F.effector);
    PartObservation missing;
    missing.name = F.receptor;
    missing.joint_type = "revolute";
    const PartObservation& rec = ri >= 0 ? input.parts[ri] : missing;
    const PartObservation* eff = ei >= 0 ? &input.parts[ei] : nullptr;
    const bool effector_movable = eff && movable(*eff);  // geometry needs a movable effector
    double r_lo, r_hi;
    receptor_range(rec, &r_lo, &r_hi);

    // ---- s_R: the receptor's joint position, from its own track, and
    // (where the track was the part's) from the hand's contacts too
    std::vector<double> s_R = rec.q;
    s_R.resize(meta.frames, std::numeric_limits<double>::quiet_NaN());
    const double moved = spread(s_R);
    std::vector<double> s_R_hand = rec.q_hand;
    s_R_hand.resize(s_R_hand.empty() ? 0 : meta.frames, std::numeric_limits<double>::quiet_NaN());
    const bool hand_moved = !s_R_hand.empty() && spread(s_R_hand) >= 1e-3 * (r_hi - r_lo);
    if (ri < 0 || !movable(rec) || (moved < 1e-3 * (r_hi - r_lo) && !hand_moved))
      diags.warning("E1060", seq_file, 0, 0, where,
                    "function '" + F.name + "': the receptor '" + F.receptor +
                        (ri < 0 ? "' is not among the parts" : !movable(rec) ? "' has no movable joint" : "' never moves") +
                        "; its template is a guess",
                    "record the receptor being operated through its range");

    // ---- one signal per effect hypothesis
    const EffectorSignals* sig = nullptr;
    for (size_t k = 0; k < effectors.size(); ++k)
      if (effectors[k] == ei) sig = &signals[k];
    if (!sig || sig->frames_seen == 0)
      diags.warning("E1061", seq_file, 0, 0, where,
                    "function '" + F.name + "': the effector '" + F.effector + "' is never seen (no mask pixels)",
                    "the effect is judged from its joint and surroundings only");

    const std::vector<double> prior = mapping_prior(rec.joint_type == "continuous");
    // Each effect hypothesis's signal, once for both candidates for s_R:
    // geometry the effector's own joint position (where it moves; only in
    // the frames its track measured it: a lid opened out of view is not
    // shut there), the others from its pixels; a moving effector's own
    // pixels less what its pose explains (pose_shading_removed, on the
    // pose in every frame). Empty: no such signal.
    const auto frames_long = [&](std::vector<double> v) {
      v.resize(meta.frames, std::numeric_limits<double>::quiet_NaN());
      return v;
    };
    std::vector<std::vector<double>> signal(5);
    std::vector<double> surround;
    if (effector_movable && !eff->q.empty()) signal[0] = frames_long(eff->q_seen.empty() ? eff->q : eff->q_seen);
    const bool effector_moves =
        !signal[0].empty() && spread(signal[0]) >= 1e-3 * std::max(eff->range_hi - eff->range_lo, 1e-3);
    if (sig) {
      signal[1] = frames_long(median3(sig->glow));
      signal[2] = frames_long(median3(sig->heat));
      signal[3] = frames_long(binned_root(sig->droplets));
      signal[4] = frames_long(binned_root(sig->motes));
      surround = frames_long(sig->surround);
      if (effector_moves) {
        const std::vector<double> pose = frames_long(eff->q);
        for (std::vector<double>* y : {&signal[1], &signal[2], &surround}) *y = pose_shading_removed(*y, pose);
      }
    }
    // Every effect's signal fitted against one s_R.
    auto fit_hypotheses = [&](const std::vector<double>& s) {
      std::vector<Hypothesis> H(5);
      for (int k = 0; k < 5; ++k) {
        if (signal[k].empty()) continue;
        MappingSeries S;
        S.dt = dt;
        S.r_lo = r_lo;
        S.r_hi = r_hi;
        S.s_R = s;
        S.allow_lag = false;
        if (k == 0) {
          S.allow_lag = true;  // a driven joint follows its target
          S.max_lag_order = 2;
          S.noise_floor =
              std::max(1e-3 * std::max(eff->range_hi - eff->range_lo, 1e-3), kDriveFloor * spread(signal[0]));
        } else {
          if (k == 3) S.allow_lag = true;  // droplets in flight outlast the flow, and take time to fall into view
          if (k >= 3) S.bin_frames = kBlobBin;  // binned_root()
          if (k == 2) {
            S.allow_lag = true;            // temperature lags its target
            S.lag_starts_anywhere = true;  // from e_lo, whatever the target at rest
            S.b_sign = 1;                  // switched on, a part reddens (a cooler shows nothing)
            // Under every map: a falling one (a part hot at rest that its
            // knob cools) is not read; in the suites what fell with a
            // receptor was a lamp's colour leaving red-hot, or a drift.
            S.b_sign_all_models = true;
            S.require_lag = true;          // with thermal inertia (a lamp's tint is instant)
          }
          // Floors: a grey level (luminance), a thousandth of red-hot in
          // the colour (hot_component()), a millimetre (blobs: sqrt of m^2).
          S.noise_floor = k == 1 ? 0.5 / 255 : k == 2 ? 1e-3 : 1e-3;
        }
        const std::vector<double>& y = signal[k];
        S.y = y;
        Hypothesis& h = H[k];
        h.has_signal = true;
        h.signal = summary(y);
        h.fit = fit_mappings(S, prior);
        h.evidence = h.fit.best_index >= 0 ? std::max(0.0, h.fit.delta_bic) : 0;
        if (k == 1 && sig) {
          // A lamp shows on its bulb or on what it lights: the better of the
          // two signals (a bulb under a hood or inside a cabinet is hidden).
          MappingSeries A = S;
          A.y = surround;
          const MappingFitResult around = fit_mappings(A, prior);
          const double ev = around.best_index >= 0 ? std::max(0.0, around.delta_bic) : 0;
          h.signal["around"] = summary(A.y);
          h.signal["around_evidence"] = ev;
          if (ev > h.evidence) h.fit = around, h.evidence = ev;
        }
        if (h.fit.best_index >= 0) {
          h.mapping_post.assign(4, 0.0);
          for (int i = 0; i < 5; ++i) h.mapping_post[kTypeOf[i]] += h.fit.posterior[i];
        }
      }
      return H;
    };
    auto strongest = [](const std::vector<Hypothesis>& H) {
      double best = 0;
      for (const Hypothesis& h : H) best = std::max(best, h.evidence);
      return best;
    };
    // The fits leave out the frames after the receptor was last measured,
    // unless it was at rest then (unknown_after_last_seen; the fits hold a
    // position that is NaN at the start, where nobody has touched it yet).
    // The hand's contacts are held after the hand leaves, as before.
    std::vector<Hypothesis> H =
        fit_hypotheses(rec.q_seen.empty() ? s_R : unknown_after_last_seen(s_R, frames_long(rec.q_seen), r_lo, r_hi));
    // The hand's s_R where it moved: kept when some effect follows it
    // very strongly better (by kMinEvidence) than any follows the part's:
    // the part's own track measures the joint, the hand's contacts only
    // through a grip that slides and re-grasps (a knob's angle from a point
    // near its axis drifts by turns), so near-ties go to the part. The
    // part's track of a round knob may be its tracker's drift, though, and
    // then nothing follows it. When nothing follows either, the part's
    // stays.
    std::string s_R_source = "part";
    double evidence_part = strongest(H), evidence_hand = 0;
    if (hand_moved) {
      std::vector<Hypothesis> H_hand = fit_hypotheses(after_last(s_R_hand, last_finite(s_R_hand), true));
      evidence_hand = strongest(H_hand);
      if (evidence_hand - evidence_part >= kMinEvidence) H = std::move(H_hand), s_R = s_R_hand, s_R_source = "hand";
    }

    // ---- the effect: the signal the receptor explains best
    std::vector<double> effect_post(5, 0.0);
    double best_ev = 0;
    for (int k = 0; k < 5; ++k) best_ev = std::max(best_ev, H[k].evidence);
    const bool evident = best_ev >= kMinEvidence;
    for (int k = 0; k < 5; ++k) {
      if (k == 0 && !effector_movable) continue;
      effect_post[k] = std::exp(0.5 * (H[k].evidence - best_ev));
    }
    // Nothing responds visibly: the names' effect where they name one
    // (effect_names.h), else temperature (a heated part may not glow within
    // the clip, a long time constant or a cooler, where a light, a flow, air
    // or a moving part would have shown).
    std::string guess_from = "none";
    int guess = -1;
    if (!evident) {
      guess = effect_named(F.effector, F.name);
      guess_from = "names";
      if (guess < 0 || (guess == 0 && !effector_movable)) guess = 2, guess_from = "default";
      std::fill(effect_post.begin(), effect_post.end(), 0.05);
      effect_post[guess] = 0.8;
      if (!effector_movable) effect_post[0] = 0;
    }

    // ---- the optional second opinion
    nlohmann::json vlm_report;
    bool vlm_answered = false;
    if (vlm_ok) {
      VlmRequest req;
      req.endpoint = options.vlm_endpoint;
      req.model = options.vlm_model;
      req.api_key = options.vlm_api_key;
      if (req.api_key.empty())
        if (const char* k = std::getenv("EFC_VLM_API_KEY")) req.api_key = k;
      req.timeout_s = options.vlm_timeout_s;
      req.prompt = vlm_prompt(F.name, F.receptor, F.effector);
      req.pngs = vlm_frames(input, F.receptor, F.effector, s_R);
      const VlmAnswer a = ask_vlm(req);
      vlm_report = {{"ok", a.ok}, {"effect", a.effect}, {"mapping", a.mapping}, {"reasons", a.reasons},
                    {"error", a.error}, {"images", req.pngs.size()}};
      if (!a.ok) {
        diags.warning("E1063", seq_file, 0, 0, where,
                      "function '" + F.name + "': the vision-language model gave no usable answer (" + a.error +
                          "); the data's answer stands");
      } else {
        vlm_answered = true;
        std::vector<double> none(4, 0.25);
        combine_with_vlm(a, &effect_post, &none);
        for (Hypothesis& h : H) combine_with_vlm(a, nullptr, &h.mapping_post);
      }
    }

    std::set<int>& taken = effects_taken[F.effector];
    if (taken.size() < effect_post.size())
      for (int k : taken) effect_post[k] = 0;
    double total = 0;
    for (double p : effect_post) total += p;
    if (total <= 0) {
      effect_post.assign(5, 0.2);
      for (int k : taken) effect_post[k] = 0;
      if (!effector_movable) effect_post[0] = 0;
      total = 0;
      for (double p : effect_post) total += p;
      if (total <= 0) effect_post.assign(5, 0.2), total = 1;
    }
    for (double& p : effect_post) p /= total;
    const int ek = static_cast<int>(std::max_element(effect_post.begin(), effect_post.end()) - effect_post.begin());
    taken.insert(ek);
    // The guess moved by the second opinion, or taken by an earlier function
    // on the same effector: not the names' nor the default's.
    if (!evident && ek != guess) guess_from = "other";
    Hypothesis& h = H[ek];
    int mk = static_cast<int>(std::max_element(h.mapping_post.begin(), h.mapping_post.end()) - h.mapping_post.begin());
    if (!h.has_signal || h.fit.best_index < 0) {
      // No fit for this effect: the best model of any fitted signal, else binary.
      mk = 0;
      for (int k = 0; k < 5; ++k)
        if (H[k].fit.best_index >= 0) mk = kTypeOf[H[k].fit.best_index];
    }
    // Nothing responds: the fit is a fit to noise, and the receptor's name
    // (mapping_names.h) says more where it names a mapping; the spec's
    // defaults for that mapping then, not parameters fitted to noise. A
    // second opinion that answered has already moved the posterior.
    std::string mapping_from = evident ? "data" : "noise";
    const int named_mapping = evident || vlm_answered ? -1 : mapping_named(F.receptor);
    if (named_mapping >= 0) mk = named_mapping, mapping_from = "names";
    if (vlm_answered && !evident) mapping_from = "vlm";
    if (!evident)
      diags.warning("E1062", seq_file, 0, 0, where,
                    "function '" + F.name + "': no signal at the effector '" + F.effector +
                        "' follows the receptor; the effect is a guess (" + kEffects[ek] +
                        (guess_from == "names" ? ", from the names" : "") + "), and so is the mapping (" +
                        kMappings[mk] + (mapping_from == "names" ? ", from the receptor's name" : "") + ")",
                    "a longer recording, or the effector kept in view, shows the effect");
    MappingModel model = default_model(mk, r_lo, r_hi);
    if (h.fit.best_index >= 0 && named_mapping < 0) {
      // The best variant of that type (binary: latching or not).
      int pick = -1;
      for (int i = 0; i < 5; ++i)
        if (kTypeOf[i] == mk && h.fit.best[i].valid && (pick < 0 || h.fit.posterior[i] > h.fit.posterior[pick])) pick = i;
      if (pick >= 0) model = h.fit.best[pick];
    }

    // ---- where the effect happens
    EffectEstimate est;
    est.type = kEffects[ek];
    if (eff && !eff->bounds.isEmpty()) {
      const Eigen::AlignedBox3d& b = eff->bounds;
      const Eigen::Vector3d c = b.center();
      est.has_position = true;
      if (ek == 1) {
        est.position = c;  // the paper's rule: the effector's box centre
      } else if (ek == 2) {
        est.position = Eigen::Vector3d(c.x(), c.y(), b.max().z());  // heat shows on its top
      } else if (ek == 3) {
        // Above where the droplets fell, at the effector's lowest point.
        Eigen::Vector3d p = c;
        if (sig && sig->droplet_points > 0) p = sig->droplet_sum / double(sig->droplet_points);
        est.position = Eigen::Vector3d(std::clamp(p.x(), b.min().x(), b.max().x()),
                                       std::clamp(p.y(), b.min().y(), b.max().y()), b.min().z());
        est.direction = Eigen::Vector3d(0, 0, -1);
      } else if (ek == 4) {
        // The outlet: the box's point nearest the motes, blowing towards them.
        Eigen::Vector3d m = c + Eigen::Vector3d(0, 0, 0.2);
        if (sig && sig->mote_points > 0) m = sig->mote_sum / double(sig->mote_points);
        Eigen::Vector3d p(std::clamp(m.x(), b.min().x(), b.max().x()), std::clamp(m.y(), b.min().y(), b.max().y()),
                          std::clamp(m.z(), b.min().z(), b.max().z()));
        Eigen::Vector3d d = m - p;
        if (d.norm() < 1e-6) d = m - c;
        est.position = p;
        est.direction = d.norm() > 1e-9 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d(0, 0, 1);
      } else {
        est.has_position = false;
      }
    }
    const TemplateJson tj = template_json(model, est, rec, eff, dt);
    R.mapping = tj.mapping;
    R.effect = tj.effect;
    R.confidence = effect_post[ek] * h.mapping_post[mk];
    if (!evident) R.confidence = std::min(R.confidence, 0.2);

    // ---- the report: every score behind the choice
    nlohmann::json hyps = nlohmann::json::object();
    for (int k = 0; k < 5; ++k) {
      const Hypothesis& x = H[k];
      nlohmann::json j = {{"signal", x.has_signal ? x.signal : nlohmann::json("none")},
                          {"posterior", effect_post[k]}};
      if (x.has_signal && x.fit.n > 0) {
        j["evidence"] = x.evidence;
        j["n"] = x.fit.n;
        j["n_eff"] = x.fit.n_eff;
        j["null"] = to_json(x.fit.null_model);
        nlohmann::json models = nlohmann::json::array();
        for (size_t i = 0; i < x.fit.best.size(); ++i) {
          nlohmann::json mj = to_json(x.fit.best[i]);
          mj["posterior"] = x.fit.posterior.size() > i ? x.fit.posterior[i] : 0.0;
          models.push_back(mj);
        }
        j["models"] = models;
        j["mapping_posterior"] = {{"binary", x.mapping_post[0]}, {"step", x.mapping_post[1]},
                                  {"linear", x.mapping_post[2]}, {"cumulative", x.mapping_post[3]}};
      }
      hyps[kEffects[k]] = j;
    }
    R.report = {{"effect", kEffects[ek]},
                {"mapping", kMappings[mk]},
                {"evident", evident},
                {"guess_from", guess_from},
                {"mapping_from", mapping_from},
                {"min_evidence", kMinEvidence},
                {"hypotheses", hyps},
                {"chosen_model", to_json(model)},
                {"estimates", tj.notes},
                {"receptor_range", {r_lo, r_hi}},
                {"s_R", {{"source", s_R_source}, {"evidence_part", evidence_part},
                         {"evidence_hand", hand_moved ? nlohmann::json(evidence_hand) : nlohmann::json(nullptr)}}},
                {"measure_seconds_all_functions", measure_s},
                {"fit_seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - tf).count()}};
    if (!vlm_report.is_null()) R.report["vlm"] = vlm_report;
    out.push_back(std::move(R));
  }
  return out;
}

}  // namespace efc::pipeline
