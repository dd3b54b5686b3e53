#include "synth/suite/template_params.h"

#include <algorithm>

namespace efc::synth::suite {
namespace {

// A point at fraction [f_lo, f_hi] of the travel.
double travel_point(const ReceptorTravel& t, double f_lo, double f_hi, SuiteRng& rng) {
  return t.lo + (t.hi - t.lo) * rng.uniform(f_lo, f_hi);
}

// Receptor positions: 1e-5 rad or m is below any sensor's resolution, and a
// 3 mm button still keeps 300 steps.
double snap_position(double x) { return snap(x, 1e5); }

SpecJson binary(const ReceptorTravel& t, SuiteRng& rng) {
  SpecJson m = {{"type", "binary"}};
  if (rng.chance(0.75)) m["threshold"] = snap_position(travel_point(t, 0.25, 0.8, rng));
  if (rng.chance(t.push_button ? 0.5 : 0.1)) m["latching"] = true;
  return m;
}

SpecJson step(const ReceptorTravel& t, SuiteRng& rng) {
  SpecJson m = {{"type", "step"}};
  // The chance stays drawn (the stream is unchanged) but the default is not
  // used: the paper's 70 % / 2 % rule switches back within one frame's worth
  // of a press's travel, so in a recording it is a binary switch at 70 %.
  const bool default_rule = !t.continuous && rng.chance(0.2);
  (void)default_rule;
  const double threshold = snap_position(travel_point(t, 0.3, 0.85, rng));
  // Below the threshold by at most 80 % of the way down, so returning to the
  // start of the travel always switches it off again; at least 8 % of the
  // travel, so that a recording shows the switch-off lagging the switch-on
  // point (a press crosses a few % of the travel per frame).
  const double width = std::min((t.hi - t.lo) * rng.uniform(0.08, 0.25), 0.8 * (threshold - t.lo));
  m["threshold"] = threshold;
  m["hysteresis"] = snap_position(width);
  return m;
}

SpecJson linear(const ReceptorTravel& t, double off, double on, SuiteRng& rng) {
  SpecJson m = {{"type", "linear"}};
  if (!t.continuous && rng.chance(0.25)) return m;  // range-to-range default
  // Saturates at or before the end of the travel (k >= 1); a continuous
  // wheel reaches `on` within its first turn or so.
  const double span = t.continuous ? (t.hi - t.lo) * rng.uniform(0.35, 1.0) : (t.hi - t.lo);
  const double k = t.continuous ? 1.0 : rng.uniform(1.0, 2.0);
  const double gain = (on - off) / span * k;
  const double kind = rng.unit();
  if (kind < 0.2) {  // turning it raises nothing: it starts at `on` and falls
    m["gain"] = -gain;
    m["offset"] = on;
  } else if (kind < 0.4) {  // a dead zone: off until a fraction of the travel
    m["gain"] = gain;
    m["offset"] = off - (on - off) * rng.uniform(0.1, 0.4);
  } else {
    m["gain"] = gain;
    m["offset"] = off;
  }
  m["gain"] = snap(m["gain"].get<double>(), 1e6);
  m["offset"] = snap(m["offset"].get<double>(), 1e6);
  return m;
}

SpecJson cumulative(const ReceptorTravel& t, double off, double on, SuiteRng& rng) {
  SpecJson m = {{"type", "cumulative"}};
  if (t.continuous || rng.chance(0.7))
    m["threshold"] = snap_position(travel_point(t, 0.45, 0.85, rng));
  const int presses = rng.between(2, 5);  // presses from off to on
  const double delta = snap((on - off) / presses, 1e6);
  if (rng.chance(0.2)) {  // a 'minus' button: starts at on, each press goes back
    m["delta"] = -delta;
    m["initial"] = on;
  } else {
    m["delta"] = delta;
    if (rng.chance(0.5)) m["initial"] = off;
  }
  return m;
}

}  // namespace

SpecJson draw_mapping(const std::string& type, const ReceptorTravel& travel, double off, double on,
                      SuiteRng& rng) {
  if (type == "binary") return binary(travel, rng);
  if (type == "step") return step(travel, rng);
  if (type == "linear") return linear(travel, off, on, rng);
  return cumulative(travel, off, on, rng);
}

}  // namespace efc::synth::suite
