// See efc_runtime.h for the meaning of every mapping and effect.
#include "efc_runtime.h"

#include <cmath>

namespace efc_rt {

void mapping_init(const MappingParams& p, double s_R0, MappingState* st) {
  st->presses = 0;
  // A receptor that starts at or above the threshold has not been pressed:
  // it must come back below the re-arm level first.
  st->armed = s_R0 < p.threshold - press_band(p) ? 1 : 0;
  st->on = 0;
  switch (p.kind) {
    case kBinary:
      st->on = p.latching ? 0 : (s_R0 >= p.threshold ? 1 : 0);
      st->s_E = st->on ? p.e_hi : p.e_lo;
      break;
    case kStep:
      st->on = s_R0 > p.threshold ? 1 : 0;
      st->s_E = st->on ? p.e_hi : p.e_lo;
      break;
    case kLinear:
      st->s_E = clamp_between(p.offset + p.gain * (s_R0 - p.r_lo), p.e_lo, p.e_hi);
      break;
    case kCumulative:
      st->s_E = clamp_between(p.initial, p.e_lo, p.e_hi);
      break;
    default:
      st->s_E = p.e_lo;
  }
}

void effect_init(const EffectParams& p, EffectState* st) {
  st->output = p.e_lo;  // at rest: off (ambient temperature, no light, no flow)
  st->emit_remainder = 0;
  st->emitted = 0;
  st->lag_dt = -1;  // no factor yet
  st->lag_factor = 0;
}

double air_speed_at(double s, double distance, double angle, double cone_angle,
                    double reach) {
  if (distance < 0 || distance > reach || std::fabs(angle) > cone_angle || reach <= 0) return 0;
  return s * (1.0 - distance / reach);
}

double air_drag(double speed, double area) { return 0.5 * 1.2 * 1.0 * area * speed * speed; }

void function_init(const FunctionParams& p, double s_R0, FunctionState* st) {
  mapping_init(p.mapping, s_R0, &st->mapping);
  effect_init(p.effect, &st->effect);
}

}  // namespace efc_rt
