#include "pipeline/templates/mapping_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace efc::pipeline {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kThresholdLevels = 48;  // receptor grid: 2 % of the travel seen
constexpr int kLinearLevels = 24;
constexpr int kSub = 8;  // samples a frame for the mean target over a frame's interval
// Hysteresis widths tried, as fractions of the receptor range.
constexpr double kHysteresis[] = {0.01, 0.02, 0.035, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3};

// The samples in use: s_R interpolated over gaps, y's observed frames.
struct Prep {
  std::vector<double> s, y;
  std::vector<char> ok;
  int n = 0;
  double dt = 1.0 / 30, band = 0, r_lo = 0, r_hi = 1;
  double s_min = 0, s_max = 0;
  double floor2 = 0;
  int b_sign = 0;
  bool b_sign_all_models = false;
  std::vector<double> taus;
  int max_order = 1;
  bool start_anywhere = false;
  std::vector<double> s_fine;  // s linear between frames, kSub samples a frame: [0] = s[0], then (i-1, i]
  bool require_lag = false;
  bool fine_lag = false;  // lags shorter than kFineLagFrames run kSub steps a frame (fine_lag())
  int bin = 1;  // MappingSeries::bin_frames
  mutable double instant_bic = kInf;  // require_lag: the best model without a lag
};

// s_R with NaN filled by linear interpolation (ends: nearest value).
std::vector<double> fill_gaps(const std::vector<double>& v) {
  std::vector<double> out(v);
  const int n = static_cast<int>(v.size());
  int last = -1;
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) continue;
    if (last < 0) {
      for (int j = 0; j < i; ++j) out[j] = v[i];
    } else {
      for (int j = last + 1; j < i; ++j) out[j] = v[last] + (v[i] - v[last]) * (j - last) / double(i - last);
    }
    last = i;
  }
  if (last < 0) return {};
  for (int j = last + 1; j < n; ++j) out[j] = v[last];
  return out;
}

// Least squares y ~ a + b v over the observed samples; returns the RSS
// (infinite when v is constant there: the model says nothing).
double least_squares(const Prep& P, const std::vector<double>& v, double* a, double* b) {
  double sv = 0, sy = 0, svv = 0, svy = 0, syy = 0;
  int m = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!P.ok[i]) continue;
    const double x = v[i], y = P.y[i];
    sv += x, sy += y, svv += x * x, svy += x * y, syy += y * y;
    ++m;
  }
  if (m < 3) return kInf;
  const double vx = svv - sv * sv / m;
  if (vx <= 1e-12 * std::max(1.0, svv)) return kInf;
  const double cxy = svy - sv * sy / m;
  *b = cxy / vx;
  *a = (sy - *b * sv) / m;
  const double rss = (syy - sy * sy / m) - cxy * cxy / vx;
  return std::max(rss, 0.0);
}

// y ~ a + b v with AR(1) errors (e_i = rho e_prev + w_i), by one
// Cochrane-Orcutt step: rho from the least-squares residuals of consecutive
// observed samples, then least squares on the quasi-differences
// y_i - rho y_prev ~ a (1 - rho) + b (v_i - rho v_prev). Returns the RSS of
// the innovations w (over *pairs terms). A camera that drifts over a part
// makes the pixels' errors slow; whitened, they no longer look like a
// response, and a switch at the wrong frame leaves a spike that counts.
// With v empty: the constant model (b = 0).
double fit_ar1(const Prep& P, const std::vector<double>* v, double* a, double* b, double* rho_out, int* pairs) {
  double a0 = 0, b0 = 0;
  if (v) {
    if (!std::isfinite(least_squares(P, *v, &a0, &b0))) return kInf;
  } else {
    double sy = 0;
    int m = 0;
    for (size_t i = 0; i < P.y.size(); ++i)
      if (P.ok[i]) sy += P.y[i], ++m;
    if (m < 3) return kInf;
    a0 = sy / m;
  }
  auto fitted = [&](size_t i) { return a0 + (v ? b0 * (*v)[i] : 0.0); };
  double num = 0, den = 0;
  long prev = -1;
  for (size_t i = 0; i < P.y.size(); ++i) {
    if (!P.ok[i]) continue;
    if (prev >= 0) {
      const double r = P.y[i] - fitted(i), rp = P.y[prev] - fitted(prev);
      num += r * rp, den += rp * rp;
    }
    prev = static_cast<long>(i);
  }
  const double rho = den > 0 ? std::clamp(num / den, 0.0, 0.98) : 0.0;
  // Normal equations of t ~ a x1 + b x2 over consecutive pairs.
  double s11 = 0, s12 = 0, s22 = 0, s1t = 0, s2t = 0, stt = 0;
  int m = 0;
  prev = -1;
  for (size_t i = 0; i < P.y.size(); ++i) {
    if (!P.ok[i]) continue;
    if (prev >= 0) {
      const double x1 = 1 - rho, x2 = v ? (*v)[i] - rho * (*v)[prev] : 0.0, t = P.y[i] - rho * P.y[prev];
      s11 += x1 * x1, s12 += x1 * x2, s22 += x2 * x2, s1t += x1 * t, s2t += x2 * t, stt += t * t;
      ++m;
    }
    prev = static_cast<long>(i);
  }
  if (m < 3 || s11 <= 0) return kInf;
  double A, B = 0;
  const double det = s11 * s22 - s12 * s12;
  if (v && det > 1e-12 * std::max(1e-300, s11 * s22)) {
    A = (s22 * s1t - s12 * s2t) / det;
    B = (s11 * s2t - s12 * s1t) / det;
  } else if (v) {
    return kInf;  // the profile says nothing after whitening
  } else {
    A = s1t / s11;
  }
  const double rss = stt - 2 * A * s1t - 2 * B * s2t + A * A * s11 + 2 * A * B * s12 + B * B * s22;
  *a = A, *b = B, *rho_out = rho, *pairs = m;
  return std::max(rss, 0.0);
}

void lag(const std::vector<double>& u, double tau, double dt, std::vector<double>* out, double x0 = NAN) {
  out->resize(u.size());
  if (u.empty()) return;
  if (tau <= 0) {
    *out = u;
    return;
  }
  const double f = 1.0 - std::exp(-dt / tau);
  double x = std::isfinite(x0) ? x0 : u[0];  // default: at rest at the start, the lag has settled
  for (size_t i = 0; i < u.size(); ++i) {
    x += (u[i] - x) * f;
    (*out)[i] = x;
  }
}

double bic(double rss, int n, double n_eff, int k, double floor2) {
  const double s2 = std::max(rss / std::max(n, 1), floor2);
  return n_eff * std::log(s2) + k * std::log(std::max(n_eff, 2.0));
}

// Tries every lag for one unit profile; keeps it in *best when it beats it.
std::vector<double> model_profile_impl(const MappingModel& m, const std::vector<double>& s, double band);

// A lag integrates its target over each frame's interval: the target's mean
// over (t_{i-1}, t_i] (s_R linear between frames, kSub samples a frame), so
// a switch between two frames moves the response by the fraction of the
// frame it came at. A driven joint's time constant is a frame or two, and
// a whole frame's error there looks like hysteresis.
// `delay` (in kSub-ths of a frame) shifts the target later: a drive's
// response (a second-order servo) starts late as well as slowly.
std::vector<double> interval_mean(const std::vector<double>& fine, size_t frames, int delay) {
  std::vector<double> out(frames);
  if (!frames) return out;
  out[0] = fine[0];
  for (size_t i = 1; i < frames; ++i) {
    double sum = 0;
    for (int k = 1; k <= kSub; ++k) {
      const long at = static_cast<long>((i - 1) * kSub + k) - delay;
      sum += fine[static_cast<size_t>(std::max(0L, at))];
    }
    out[i] = sum / kSub;
  }
  return out;
}

// The target's mean over each fine step (j-1, j] ([0]: u[0]). An on/off
// target switches inside the step, where s (linear there) crosses the
// model's level: the threshold, or a step's lower edge when it turns off;
// a linear map's is its ends' mean. An eighth of a frame is still a third
// of a fast drive's time constant: a switch placed at the step's end
// instead of inside it misses by a tenth of the lid's swing.
std::vector<double> step_means(const MappingModel& m, const std::vector<double>& s, const std::vector<double>& u) {
  std::vector<double> out(u);
  for (size_t j = 1; j < u.size(); ++j) {
    if (u[j] == u[j - 1]) continue;
    if (m.type == "linear" || s[j] == s[j - 1]) {
      out[j] = 0.5 * (u[j - 1] + u[j]);
      continue;
    }
    const double level = m.type == "step" && u[j] < u[j - 1] ? m.threshold - m.hysteresis : m.threshold;
    const double before = std::clamp((level - s[j - 1]) / (s[j] - s[j - 1]), 0.0, 1.0);
    out[j] = u[j - 1] * before + u[j] * (1 - before);
  }
  return out;
}

// Slower lags are stepped once a frame: within a frame they barely move,
// and the fine steps cost eight times as much.
constexpr double kFineLagFrames = 4;
bool runs_fine(const Prep& P, double tau) { return P.fine_lag && tau > 0 && tau < kFineLagFrames * P.dt; }

// A driven joint settles within a frame or two, faster than a lag stepped
// once a frame can follow (its response to a switch a third of a frame
// before a frame is a few per cent, not a third of its first frame's
// step): the lags run kSub steps a frame on the target's step means
// (step_means; delayed by `delay` kSub-ths of a frame), each exact for a
// target held over its step, and the response is read at the frames.
// tau2 > 0: a second lag in cascade.
void fine_lag(const std::vector<double>& means, size_t frames, int delay, double tau, double tau2, double dt,
              double x0, std::vector<double>* out) {
  out->assign(frames, 0.0);
  if (!frames || means.empty()) return;
  const double h = dt / kSub;
  const double f1 = 1.0 - std::exp(-h / tau), f2 = tau2 > 0 ? 1.0 - std::exp(-h / tau2) : 1.0;
  double x = std::isfinite(x0) ? x0 : means[0], y = x;
  (*out)[0] = tau2 > 0 ? y : x;
  for (size_t j = 1; j < means.size(); ++j) {
    const double target = means[static_cast<size_t>(std::max(0L, static_cast<long>(j) - delay))];
    x += (target - x) * f1;
    y += (x - y) * f2;
    if (j % kSub == 0 && j / kSub < frames) (*out)[j / kSub] = tau2 > 0 ? y : x;
  }
}

// The response as a binned signal sees it (MappingSeries::bin_frames):
// each observed sample the mean of its bin's frames, so a switch inside a
// bin gives the fraction of the bin it was on, as the counts do.
const std::vector<double>& binned_response(const Prep& P, const std::vector<double>& r, std::vector<double>* out) {
  const size_t N = r.size();
  out->assign(N, 0.0);
  for (size_t i = 0; i < N; ++i) {
    if (!P.ok[i]) continue;
    const size_t from = (i / P.bin) * P.bin, to = std::min(N, from + P.bin);
    double sum = 0;
    for (size_t j = from; j < to; ++j) sum += r[j];
    (*out)[i] = sum / static_cast<double>(to - from);
  }
  return *out;
}

// A model's own parameters before any lag's (a, b, and its switch: the
// threshold; a step's hysteresis, a linear map's second end and a
// saturating counter's limit one more).
int base_parameters(int idx, const MappingModel& m) {
  return idx == 2 || idx == 3 || (idx == 4 && m.saturate > 0) ? 5 : 4;
}

void consider(const Prep& P, const std::vector<double>& u_at, MappingModel proto, int k_base,
              MappingModel* best, std::vector<double>& scratch) {
  std::vector<double> twice, binned;
  const bool lagged = P.taus.size() > 1;
  const std::vector<double> fine = lagged ? model_profile_impl(proto, P.s_fine, P.band) : std::vector<double>();
  // Only a lag under kFineLagFrames runs on the fine steps' means.
  const bool any_fine = std::any_of(P.taus.begin(), P.taus.end(), [&](double tau) { return runs_fine(P, tau); });
  const std::vector<double> fine_means = any_fine ? step_means(proto, P.s_fine, fine) : std::vector<double>();
  // Dead times tried: none, and for a driven joint (second order) up to
  // one and a half frames.
  std::vector<int> delays{0};
  if (lagged && P.max_order > 1) delays = {0, kSub / 2, kSub, 3 * kSub / 2};
  for (int delay : delays) {
  const std::vector<double> u_mean = lagged ? interval_mean(fine, u_at.size(), delay) : u_at;
  // Where the lag starts: settled at the first target, or (a temperature
  // starts at e_lo whatever its target: runtime) at either end of the
  // profile's levels.
  std::vector<double> starts{NAN};
  if (P.start_anywhere && !u_at.empty()) {
    const auto [lo, hi] = std::minmax_element(u_at.begin(), u_at.end());
    if (*lo != u_at[0]) starts.push_back(*lo);
    if (*hi != u_at[0] && *hi != *lo) starts.push_back(*hi);
  }
  for (double x0 : starts)
  for (int order = 1; order <= P.max_order; ++order)
  for (double tau : P.taus) {
    if (order > 1 && tau <= 0) continue;
    if (std::isfinite(x0) && tau <= 0) continue;
    if (delay > 0 && tau <= 0) continue;
    const std::vector<double>& u = tau > 0 ? u_mean : u_at;
    // Two lags in cascade: equal (a critically damped servo) or the second
    // faster (a servo whose damping exceeds the critical).
    static const double kRatios1[] = {1.0}, kRatios2[] = {1.0, 0.5, 0.25};
    const double* ratios = order > 1 ? kRatios2 : kRatios1;
    const int n_ratios = order > 1 ? 3 : 1;
    for (int ri = 0; ri < n_ratios; ++ri) {
    const double ratio = ratios[ri];
    if (runs_fine(P, tau)) {
      fine_lag(fine_means, u_at.size(), delay, tau, order > 1 ? tau * ratio : 0, P.dt, x0, &scratch);
    } else {
      lag(u, tau, P.dt, &scratch, x0);
      if (order > 1) {
        lag(scratch, tau * ratio, P.dt, &twice);
        scratch.swap(twice);
      }
    }
    // A binned signal: each sample its bin's mean (MappingSeries::bin_frames).
    const std::vector<double>& v = P.bin > 1 ? binned_response(P, scratch, &binned) : scratch;
    double a = 0, b = 0, rho = 0;
    int pairs = 0;
    const double rss = fit_ar1(P, &v, &a, &b, &rho, &pairs);
    // The sign holds for on/off models (on is e_hi); a linear or cumulative
    // map may fall as s_R or the presses rise (negative gain or delta),
    // unless the signal only rises with its effect (b_sign_all_models).
    const bool on_off = proto.type == "binary" || proto.type == "step";
    if (!std::isfinite(rss) || ((on_off || P.b_sign_all_models) && P.b_sign != 0 && P.b_sign * b <= 0)) continue;
    const int k = k_base + 1 + (tau > 0 ? 1 : 0) + (delay > 0 ? 1 : 0) + (ratio != 1 ? 1 : 0);  // + rho, lag, dead time, second lag
    const double score = bic(rss, pairs, pairs, k, P.floor2);
    if (P.require_lag && tau <= 0) {
      P.instant_bic = std::min(P.instant_bic, score);
      continue;
    }
    if (best->valid && score >= best->bic) continue;
    proto.tau = tau;
    proto.lag_order = order;
    proto.lag_start = x0;
    proto.lag_ratio = ratio;
    proto.delay = delay * P.dt / kSub;
    proto.a = a;
    proto.b = b;
    proto.rss = rss;
    proto.rho = rho;
    proto.pairs = pairs;
    proto.k = k;
    proto.bic = score;
    proto.valid = true;
    *best = proto;
    }
  }
  }
}

// A linear map's ramp is seen where the receptor, passing through it, puts
// frames on its slope: it is at least kRampFrames of the receptor's travel
// per frame there (the median over the frames that cross it). A narrower
// ramp is a switch between two frames whose timing the ramp's ends adjust
// to the noise (BIC pays for the one parameter, not for what it buys
// there): binary and step say the same with fewer.
constexpr double kRampFrames = 2;
bool ramp_seen(const Prep& P, double s0, double s1) {
  std::vector<double> travel;
  for (size_t i = 1; i < P.s.size(); ++i) {
    const double lo = std::min(P.s[i - 1], P.s[i]), hi = std::max(P.s[i - 1], P.s[i]);
    if (hi > lo && hi > s0 && lo < s1) travel.push_back(hi - lo);
  }
  if (travel.empty()) return true;
  std::nth_element(travel.begin(), travel.begin() + static_cast<long>(travel.size() / 2), travel.end());
  return s1 - s0 >= kRampFrames * travel[travel.size() / 2];
}

// A step's hysteresis as an Occam factor instead of a parameter BIC pays
// log(n) for. BIC assumes the data pin a parameter down to 1/sqrt(n) of
// its prior; a switch-off edge is pinned only to the receptor's travel
// between two samples, and a press sampled coarsely (a fan's flow counted
// every few frames) leaves any width fitting as well as none: a binary
// switch and a step then tie, as they should, and the prior decides. So
// the step's score in the choice of mapping (choice_bic) has its
// likelihood averaged over a uniform prior on the width, (0, min(30 % of
// the range, 80 % of the threshold's height)] (the widths tried; back at
// rest a step is off), at its fitted threshold with the lags profiled, in
// place of the best width's likelihood and its log(n). Every width is
// scored with the same k: their BICs' differences are their likelihoods'.
constexpr int kOccamWidths = 24;
void apply_hysteresis_occam(const Prep& P, MappingModel* step, std::vector<double>& scratch) {
  const double widest = std::min(0.3 * (P.r_hi - P.r_lo), 0.8 * (step->threshold - P.r_lo));
  if (!step->valid || !(widest > 0)) return;
  const double instant_bic = P.instant_bic;  // (consider keeps the best instant model: not these)
  std::vector<double> half_bic;
  for (int j = 0; j < kOccamWidths; ++j) {
    MappingModel m = *step, best;
    m.hysteresis = widest * (j + 0.5) / kOccamWidths;
    consider(P, model_profile_impl(m, P.s, P.band), m, 5, &best, scratch);
    if (best.valid) half_bic.push_back(-0.5 * best.bic);
  }
  P.instant_bic = instant_bic;
  if (half_bic.empty()) return;
  const double top = *std::max_element(half_bic.begin(), half_bic.end());
  double sum = 0;
  for (double h : half_bic) sum += std::exp(h - top);
  step->hysteresis_occam = std::log(sum / kOccamWidths);  // widths with no valid fit count as none
}

// The score the mapping types are chosen by: the BIC, but a step's
// hysteresis paid for by its Occam factor instead of log(n). The evidence
// that anything responds (delta_bic) stays the BIC's, the scale its bar
// (TemplateOptions::min_evidence) was set on: a width free to be anything
// also lets a step that never switches back off fit a drift for nothing.
double choice_bic(const MappingModel& m) {
  if (m.type != "step") return m.bic;
  return m.bic - 2 * m.hysteresis_occam - std::log(std::max(static_cast<double>(m.pairs), 2.0));
}

}  // namespace

std::vector<double> model_profile(const MappingModel& m, const std::vector<double>& s, double band) {
  return model_profile_impl(m, s, band);
}

namespace {
std::vector<double> model_profile_impl(const MappingModel& m, const std::vector<double>& s, double band) {
  std::vector<double> u(s.size(), 0.0);
  if (s.empty()) return u;
  const double t = m.threshold;
  if (m.type == "binary" && !m.latching) {
    for (size_t i = 0; i < s.size(); ++i) u[i] = s[i] >= t ? 1 : 0;
  } else if (m.type == "binary" || m.type == "cumulative") {
    bool armed = s[0] < t - band;
    int presses = 0, on = 0;
    for (size_t i = 0; i < s.size(); ++i) {
      if (!armed) {
        if (s[i] < t - band) armed = true;
      } else if (s[i] >= t) {
        armed = false;
        ++presses;
        on = !on;
      }
      if (m.type == "binary") u[i] = on;
      else u[i] = m.saturate > 0 ? std::min(presses, m.saturate) : presses;
    }
  } else if (m.type == "step") {
    int on = s[0] > t ? 1 : 0;
    for (size_t i = 0; i < s.size(); ++i) {
      if (!on && s[i] > t) on = 1;
      else if (on && s[i] < t - m.hysteresis) on = 0;
      u[i] = on;
    }
  } else if (m.type == "linear") {
    const double d = m.s1 - m.s0;
    for (size_t i = 0; i < s.size(); ++i) u[i] = d != 0 ? std::clamp((s[i] - m.s0) / d, 0.0, 1.0) : 0;
  }
  return u;
}
}  // namespace

std::vector<double> mapping_prior(bool continuous_receptor) {
  // binary, binary latching, step, linear, cumulative
  if (continuous_receptor) return {0.05, 0.05, 0.3, 0.3, 0.3};
  return {0.125, 0.125, 0.25, 0.25, 0.25};
}

MappingFitResult fit_mappings(const MappingSeries& series, const std::vector<double>& prior_in) {
  MappingFitResult R;
  Prep P;
  P.s = fill_gaps(series.s_R);
  const size_t N = std::min(series.s_R.size(), series.y.size());
  if (P.s.size() < N || N < 4) return R;
  P.s.resize(N);
  P.y.assign(series.y.begin(), series.y.begin() + N);
  P.ok.assign(N, 0);
  // After s_R's last known frame nothing says where the receptor is: those
  // frames' y are not scored (the lags still run through them, held).
  size_t known_until = 0;
  for (size_t i = 0; i < N; ++i)
    if (std::isfinite(series.s_R[i])) known_until = i + 1;
  double ylo = kInf, yhi = -kInf;
  for (size_t i = 0; i < known_until; ++i) {
    if (!std::isfinite(P.y[i])) continue;
    P.ok[i] = 1;
    ++P.n;
    ylo = std::min(ylo, P.y[i]);
    yhi = std::max(yhi, P.y[i]);
  }
  R.n = P.n;
  if (P.n < 4) return R;
  P.dt = series.dt > 0 ? series.dt : 1.0 / 30;
  P.r_lo = series.r_lo;
  P.r_hi = series.r_hi > series.r_lo ? series.r_hi : series.r_lo + 1;
  P.band = 0.01 * (P.r_hi - P.r_lo);
  P.s_min = *std::min_element(P.s.begin(), P.s.end());
  P.s_max = *std::max_element(P.s.begin(), P.s.end());
  const double fl = series.noise_floor > 0 ? series.noise_floor : 1e-4 * std::max(yhi - ylo, 1e-12);
  P.floor2 = fl * fl;
  P.b_sign = series.b_sign;
  P.b_sign_all_models = series.b_sign_all_models;
  P.max_order = series.allow_lag ? std::max(1, series.max_lag_order) : 1;
  P.start_anywhere = series.lag_starts_anywhere;
  P.require_lag = series.allow_lag && series.require_lag;
  P.bin = std::max(1, series.bin_frames);
  P.s_fine.assign(1 + (N - 1) * kSub, P.s[0]);
  for (size_t i = 1; i < N; ++i)
    for (int k = 1; k <= kSub; ++k) P.s_fine[(i - 1) * kSub + k] = P.s[i - 1] + (P.s[i] - P.s[i - 1]) * k / kSub;
  P.taus = {0};
  // A driven joint (two lags) may settle within a frame: its lags start at
  // half a frame, and the fast ones run kSub steps a frame (fine_lag). A
  // drive slower than 10 s would not be seen to move in a recording: its
  // lags stop there (a temperature's go on to minutes).
  P.fine_lag = series.allow_lag && P.max_order > 1;
  const double longest = P.fine_lag ? 10 : 150;
  if (series.allow_lag)
    for (double tau = P.fine_lag ? P.dt / 2 : P.dt; tau < longest; tau *= std::sqrt(2.0)) P.taus.push_back(tau);

  // The null model: a constant (with the same AR(1) errors as the others).
  {
    MappingModel m;
    m.type = "null";
    double b = 0;
    m.rss = fit_ar1(P, nullptr, &m.a, &b, &m.rho, &m.pairs);
    if (!std::isfinite(m.rss)) return R;
    m.k = 3;  // a, sigma, rho
    m.bic = bic(m.rss, m.pairs, m.pairs, m.k, P.floor2);
    m.valid = true;
    R.null_model = m;
  }

  R.best.resize(5);
  const double span = P.s_max - P.s_min;
  std::vector<double> scratch;
  if (span > 1e-3 * (P.r_hi - P.r_lo)) {
    std::vector<double> levels;
    for (int i = 0; i < kThresholdLevels; ++i) levels.push_back(P.s_min + span * (i + 0.5) / kThresholdLevels);
    for (double t : levels) {
      MappingModel m;
      m.threshold = t;
      m.type = "binary";
      consider(P, model_profile(m, P.s, P.band), m, 4, &R.best[0], scratch);
      m.latching = true;
      std::vector<double> u = model_profile(m, P.s, P.band);
      consider(P, u, m, 4, &R.best[1], scratch);
      m.latching = false;
      m.type = "step";
      for (double hf : kHysteresis) {
        m.hysteresis = hf * (P.r_hi - P.r_lo);
        if (m.hysteresis > 0.8 * (t - P.r_lo)) break;  // back at rest, a step is off
        consider(P, model_profile(m, P.s, P.band), m, 5, &R.best[2], scratch);
      }
      m.hysteresis = 0;
      m.type = "cumulative";
      m.saturate = 0;
      u = model_profile(m, P.s, P.band);
      const int presses = u.empty() ? 0 : static_cast<int>(u.back());
      m.presses = presses;
      consider(P, u, m, 4, &R.best[4], scratch);
      for (int sat = 1; sat < presses; ++sat) {
        m.saturate = sat;
        consider(P, model_profile(m, P.s, P.band), m, 5, &R.best[4], scratch);
      }
    }
    std::vector<double> lin;
    for (int i = 0; i < kLinearLevels; ++i) lin.push_back(P.s_min + span * i / (kLinearLevels - 1));
    for (int i = 0; i < kLinearLevels; ++i)
      for (int j = i + 1; j < kLinearLevels; ++j) {
        MappingModel m;
        m.type = "linear";
        m.s0 = lin[i];
        m.s1 = lin[j];
        if (!ramp_seen(P, m.s0, m.s1)) continue;
        consider(P, model_profile(m, P.s, P.band), m, 5, &R.best[3], scratch);
      }
    // The grids place a switch to within half a frame of a fast press; a
    // fast response (a driven joint) needs it to a fraction of that, or a
    // model with a spare parameter (a step's second edge, a linear's
    // narrow ramp) wins by correcting the timing. Each type's best is
    // refined on a finer grid around it (maximum likelihood, as the grid).
    const double dT = span / kThresholdLevels, dL = span / (kLinearLevels - 1);
    constexpr int kFine = 6;
    for (int idx : {0, 1, 4}) {
      if (!R.best[idx].valid) continue;
      const MappingModel base = R.best[idx];
      for (int j = -kFine; j <= kFine; ++j) {
        MappingModel m = base;
        m.threshold = base.threshold + dT * j / kFine;
        consider(P, model_profile(m, P.s, P.band), m, base_parameters(idx, base), &R.best[idx], scratch);
      }
    }
    if (R.best[2].valid) {
      const MappingModel base = R.best[2];
      for (int j = -kFine; j <= kFine; ++j)
        for (int h = -kFine; h <= kFine; ++h) {
          MappingModel m = base;
          m.threshold = base.threshold + dT * j / kFine;
          m.hysteresis = base.hysteresis + dT * h / kFine;
          if (m.hysteresis <= 0 || m.hysteresis > 0.8 * (m.threshold - P.r_lo)) continue;
          consider(P, model_profile(m, P.s, P.band), m, 5, &R.best[2], scratch);
        }
    }
    if (R.best[3].valid) {
      const MappingModel base = R.best[3];
      for (int i = -kFine; i <= kFine; ++i)
        for (int j = -kFine; j <= kFine; ++j) {
          MappingModel m = base;
          m.s0 = base.s0 + dL * i / kFine;
          m.s1 = base.s1 + dL * j / kFine;
          if (m.s1 <= m.s0 || !ramp_seen(P, m.s0, m.s1)) continue;
          consider(P, model_profile(m, P.s, P.band), m, 5, &R.best[3], scratch);
        }
    }
  }
  // A drive's time constant, between the grid's (a factor of sqrt 2
  // apart), matters as much as its switch's timing: each type's best
  // lagged model tries time constants an eighth of an octave apart, up to
  // an octave from its own (its second lag's ratio may have stood in for
  // the first's).
  if (P.fine_lag) {
    const std::vector<double> grid = P.taus;
    for (int idx = 0; idx < 5; ++idx) {
      const MappingModel base = R.best[idx];
      if (!base.valid || !(base.tau > 0)) continue;
      // (No instant model: the grid tried it with these parameters.)
      P.taus.clear();
      for (int e = -8; e <= 8; ++e)
        if (e != 0) P.taus.push_back(base.tau * std::pow(2.0, e / 8.0));
      consider(P, model_profile(base, P.s, P.band), base, base_parameters(idx, base), &R.best[idx], scratch);
    }
    P.taus = grid;
  }
  apply_hysteresis_occam(P, &R.best[2], scratch);
  // Presses seen by the latching variant (for reports).
  if (R.best[1].valid) {
    MappingModel c = R.best[1];
    c.type = "cumulative";
    c.saturate = 0;
    const std::vector<double> u = model_profile(c, P.s, P.band);
    R.best[1].presses = u.empty() ? 0 : static_cast<int>(u.back());
  }

  // The errors' autocorrelation is in every model (fit_ar1): the frames
  // count as the innovations they give.
  R.n_eff = R.null_model.pairs;
  auto rescore = [&](MappingModel& m) {
    if (m.valid) m.sigma = std::sqrt(std::max(m.rss / std::max(m.pairs, 1), P.floor2));
  };
  rescore(R.null_model);
  for (MappingModel& m : R.best) rescore(m);

  // Cumulative: the signal's change at each press (for delta).
  MappingModel& cm = R.best[4];
  if (cm.valid) {
    MappingModel c = cm;
    c.saturate = 0;
    const std::vector<double> u = model_profile(c, P.s, P.band);
    for (size_t i = 1; i < N; ++i)
      if (u[i] > u[i - 1]) {
        auto mean = [&](int from, int to) {
          double s = 0;
          int m = 0;
          for (int j = std::max(0, from); j < std::min<int>(static_cast<int>(N), to); ++j)
            if (P.ok[j]) s += P.y[j], ++m;
          return m ? s / m : std::nan("");
        };
        const int at = static_cast<int>(i);
        const int w = std::max(2, static_cast<int>(std::lround(std::max(cm.tau, 0.1) / P.dt)));
        cm.step_heights.push_back(mean(at + w, at + 2 * w) - mean(at - w, at));
      }
  }

  std::vector<double> prior = prior_in.size() == 5 ? prior_in : mapping_prior(false);
  double best_bic = kInf, best_choice = kInf;
  for (const MappingModel& m : R.best)
    if (m.valid) best_bic = std::min(best_bic, m.bic), best_choice = std::min(best_choice, choice_bic(m));
  R.posterior.assign(5, 0.0);
  double total = 0;
  for (int i = 0; i < 5; ++i) {
    if (!R.best[i].valid) continue;
    R.posterior[i] = prior[i] * std::exp(-0.5 * (choice_bic(R.best[i]) - best_choice));
    total += R.posterior[i];
  }
  if (total > 0) {
    for (double& p : R.posterior) p /= total;
    R.best_index = static_cast<int>(std::max_element(R.posterior.begin(), R.posterior.end()) - R.posterior.begin());
    // With a lag required, an instant response is a rival explanation
    // (e.g. a lamp's light tinting a part, not heat): the evidence is over
    // the better of the null and the best instant model.
    R.delta_bic = std::min(R.null_model.bic, P.instant_bic) - best_bic;
  }
  return R;
}

nlohmann::json to_json(const MappingModel& m) {
  nlohmann::json j = {{"type", m.type}, {"bic", m.bic}, {"k", m.k}, {"rss", m.rss}, {"sigma", m.sigma},
                      {"a", m.a}, {"b", m.b}, {"rho", m.rho}, {"valid", m.valid}};
  if (m.type == "binary") j["latching"] = m.latching;
  if (m.type == "binary" || m.type == "step" || m.type == "cumulative") j["threshold"] = m.threshold;
  if (m.type == "step") j["hysteresis"] = m.hysteresis, j["hysteresis_occam"] = m.hysteresis_occam;
  if (m.type == "linear") j["s0"] = m.s0, j["s1"] = m.s1;
  if (m.type == "cumulative") {
    j["saturate"] = m.saturate;
    j["presses"] = m.presses;
    j["step_heights"] = m.step_heights;
  }
  if (m.tau > 0) j["tau"] = m.tau, j["lag_order"] = m.lag_order, j["delay"] = m.delay, j["lag_ratio"] = m.lag_ratio;
  for (auto& [k, v] : j.items())
    if (v.is_number_float() && !std::isfinite(v.get<double>())) v = nullptr;
  return j;
}

}  // namespace efc::pipeline
