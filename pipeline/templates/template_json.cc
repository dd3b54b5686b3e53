#include "pipeline/templates/template_json.h"

#include <algorithm>
#include <cmath>

namespace efc::pipeline {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// The spec's default ranges (EFFECT), [off, on].
void default_range(const std::string& type, double* off, double* on) {
  if (type == "illumination") *off = 0, *on = 800;
  else if (type == "temperature") *off = 20, *on = 200;
  else if (type == "fluid") *off = 0, *on = 6;
  else *off = 0, *on = 10;  // airflow
}

double round_to(double v, double unit) { return std::round(v / unit) * unit; }

nlohmann::json vec(const Eigen::Vector3d& v) {
  return nlohmann::json::array({round_to(v.x(), 1e-4), round_to(v.y(), 1e-4), round_to(v.z(), 1e-4)});
}

}  // namespace

void receptor_range(const PartObservation& p, double* lo, double* hi) {
  if (p.joint_type == "continuous" || !(p.range_hi > p.range_lo)) {
    *lo = 0;
    *hi = kTwoPi;
  } else {
    *lo = p.range_lo;
    *hi = p.range_hi;
  }
}

TemplateJson template_json(const MappingModel& fit, const EffectEstimate& est, const PartObservation& receptor,
                           const PartObservation* effector, double dt) {
  TemplateJson out;
  double r_lo, r_hi;
  receptor_range(receptor, &r_lo, &r_hi);
  const double r_span = r_hi - r_lo;
  // A threshold strictly inside the receptor's range.
  auto inside = [&](double t) { return std::clamp(t, r_lo + 0.01 * r_span, r_hi - 0.01 * r_span); };

  // Presses to saturate (cumulative): the fit's clamp when it showed one,
  // else the presses seen (every press made the same step: not yet full).
  int presses_full = 1;
  if (fit.type == "cumulative") presses_full = fit.saturate > 0 ? fit.saturate : std::max(1, fit.presses);
  const double u_on = fit.type == "cumulative" ? presses_full : 1.0;

  // ---- the effect's range [off, on]
  double off, on;
  const bool geometry = est.type == "geometry" && effector;
  if (geometry) {
    // Joint units are measured: the fitted levels, inside the joint's range.
    const double j_lo = effector->range_lo, j_hi = effector->range_hi;
    off = std::clamp(fit.a, j_lo, j_hi);
    on = std::clamp(fit.a + fit.b * u_on, j_lo, j_hi);
    if (std::fabs(on - off) < 1e-6 * std::max(1.0, j_hi - j_lo)) {
      off = j_lo;
      on = j_hi;
    }
    out.notes["levels_measured"] = true;
  } else {
    default_range(est.type, &off, &on);
    if (fit.b < 0) std::swap(off, on);  // actuating it lowers the quantity
    out.notes["levels_measured"] = false;
  }
  out.effect = {{"type", est.type}, {"range", {off, on}}};

  // ---- the mapping
  nlohmann::json m = {{"type", fit.type}};
  if (fit.type == "binary") {
    m["threshold"] = inside(fit.threshold);
    m["latching"] = fit.latching;
  } else if (fit.type == "step") {
    const double t = inside(fit.threshold);
    m["threshold"] = t;
    m["hysteresis"] = std::clamp(fit.hysteresis, 0.0, std::max(0.0, 0.8 * (t - r_lo)));
  } else if (fit.type == "linear") {
    const double ds = fit.s1 - fit.s0;
    double gain = ds != 0 ? (on - off) / ds : 0;
    if (!std::isfinite(gain) || gain == 0) gain = (on - off) / r_span;
    m["gain"] = gain;
    m["offset"] = off - gain * (fit.s0 - r_lo);
  } else if (fit.type == "cumulative") {
    m["threshold"] = inside(fit.threshold);
    double delta = (on - off) / presses_full;
    if (!std::isfinite(delta) || delta == 0) delta = (on - off) / 2;
    m["delta"] = delta;
    m["initial"] = off;
    out.notes["presses_to_saturate"] = presses_full;
  }
  out.mapping = m;

  // ---- where the effect happens
  if (est.type == "temperature") {
    // The lag of the redness is the temperature's (the glow blends linearly
    // in temperature); no lag seen: a fast element, one frame.
    out.effect["time_constant"] = round_to(std::max(fit.tau, dt), 1e-3);
    if (est.has_position) out.effect["position"] = vec(est.position);
  } else if (est.type == "illumination") {
    if (est.has_position) out.effect["position"] = vec(est.position);
  } else if (est.type == "fluid") {
    if (est.has_position)
      out.effect["emitter"] = {{"position", vec(est.position)}, {"direction", vec(est.direction)}};
  } else if (est.type == "airflow") {
    if (est.has_position)
      out.effect["outlet"] = {{"position", vec(est.position)}, {"direction", vec(est.direction)}};
  }
  return out;
}

}  // namespace efc::pipeline
