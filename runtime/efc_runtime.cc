// See efc_runtime.h for the meaning of every mapping and effect.
#include "efc_runtime.h"

#include <cmath>

namespace efc_rt {

double clamp_between(double v, double a, double b) {
  const double lo = a < b ? a : b;
  const double hi = a < b ? b : a;
  return v < lo ? lo : (v > hi ? hi : v);
}

double press_band(const MappingParams& p) { return 0.01 * std::fabs(p.r_hi - p.r_lo); }

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

// Returns 1 when s_R completes a press (rising edge through the threshold).
static int press_edge(const MappingParams& p, double s_R, MappingState* st) {
  if (!st->armed) {
    if (s_R < p.threshold - press_band(p)) st->armed = 1;
    return 0;
  }
  if (s_R >= p.threshold) {
    st->armed = 0;
    st->presses++;
    return 1;
  }
  return 0;
}

double mapping_update(const MappingParams& p, double s_R, MappingState* st) {
  switch (p.kind) {
    case kBinary:
      if (p.latching) {
        if (press_edge(p, s_R, st)) st->on = !st->on;
      } else {
        st->on = s_R >= p.threshold ? 1 : 0;
      }
      st->s_E = st->on ? p.e_hi : p.e_lo;
      break;
    case kStep:
      if (!st->on && s_R > p.threshold) st->on = 1;
      else if (st->on && s_R < p.threshold - p.hysteresis) st->on = 0;
      st->s_E = st->on ? p.e_hi : p.e_lo;
      break;
    case kLinear:
      st->s_E = clamp_between(p.offset + p.gain * (s_R - p.r_lo), p.e_lo, p.e_hi);
      break;
    case kCumulative:
      if (press_edge(p, s_R, st)) st->s_E = clamp_between(st->s_E + p.delta, p.e_lo, p.e_hi);
      break;
    default:
      break;
  }
  return st->s_E;
}

void effect_init(const EffectParams& p, EffectState* st) {
  st->output = p.e_lo;  // at rest: off (ambient temperature, no light, no flow)
  st->emit_remainder = 0;
  st->emitted = 0;
  st->lag_dt = -1;  // no factor yet
  st->lag_factor = 0;
}

double droplet_rate(const EffectParams& p, double flow_l_per_min) {
  if (p.droplet_volume_l <= 0 || flow_l_per_min <= 0) return 0;
  return flow_l_per_min / 60.0 / p.droplet_volume_l;
}

int effect_step(const EffectParams& p, double s_E, double dt, EffectState* st) {
  switch (p.kind) {
    case kTemperature: {
      // Exact discretisation of dT/dt = (s_E - T) / tau: stable for any dt.
      if (dt != st->lag_dt) {
        const double tau = p.time_constant > 0 ? p.time_constant : 1e-9;
        st->lag_factor = 1.0 - std::exp(-dt / tau);
        st->lag_dt = dt;
      }
      st->output += (s_E - st->output) * st->lag_factor;
      return 0;
    }
    case kFluid: {
      st->output = s_E;
      const double want = droplet_rate(p, s_E) * dt + st->emit_remainder;
      // The epsilon keeps a droplet from being lost to rounding when the
      // accumulated remainder lands a hair below a whole number.
      const double n = std::floor(want + 1e-9);
      st->emit_remainder = want - n > 0 ? want - n : 0;
      st->emitted += static_cast<long>(n);
      return static_cast<int>(n);
    }
    default:
      st->output = s_E;
      return 0;
  }
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

int function_step(const FunctionParams& p, double s_R, double dt, FunctionState* st) {
  const double s_E = mapping_update(p.mapping, s_R, &st->mapping);
  return effect_step(p.effect, s_E, dt, &st->effect);
}

}  // namespace efc_rt
