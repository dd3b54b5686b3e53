// efc runtime: the one definition of what a function template does over time.
//
// Dependency-free C++ (only <cmath>), so the playback harness, the generated
// MuJoCo callbacks, the Bullet program and every other binding share it. The
// Python targets get a generated mirror that is tested against the same vectors.
//
// A function template maps a receptor state s_R (a joint position) to an
// effector state s_E (the effect's quantity) through a mapping, then an effect
// realises s_E over time (e.g. temperature follows s_E as a first-order lag).
// Plain structs with aggregate layout: generated code embeds tables of them.
#ifndef EFC_RUNTIME_H_
#define EFC_RUNTIME_H_

#include <cmath>

namespace efc_rt {

enum MappingKind { kBinary = 0, kStep = 1, kLinear = 2, kCumulative = 3 };
enum EffectKind {
  kGeometry = 0,
  kIllumination = 1,
  kTemperature = 2,
  kFluid = 3,
  kAirflow = 4
};

// Every parameter resolved (the compiler fills defaults; see the spec).
struct MappingParams {
  int kind;           // MappingKind
  double r_lo, r_hi;  // receptor range; a continuous receptor uses [0, 2 pi]
  double e_lo, e_hi;  // effect range read as [off, on]; e_hi may be below e_lo
  double threshold;   // binary, step, cumulative
  double hysteresis;  // step: back to off once s_R < threshold - hysteresis
  int latching;       // binary: 1 = each press toggles
  double gain;        // linear
  double offset;      // linear
  double delta;       // cumulative: added per press
  double initial;     // cumulative: s_E before the first press
};

// A press is s_R rising to >= threshold after having been below
// threshold - press_band (press_band = 1% of the receptor range). The small
// band debounces a simulated joint that jitters around the threshold; an
// ideal press (down to the lower limit and back) always crosses it.
struct MappingState {
  double s_E;
  int armed;  // the receptor has been below the re-arm level since the last press
  int on;     // step and latching binary: the current state
  long presses;
};

inline double clamp_between(double v, double a, double b);
inline double press_band(const MappingParams& p);

void mapping_init(const MappingParams& p, double s_R0, MappingState* st);
// Advances the mapping to receptor state s_R; returns the new s_E.
inline double mapping_update(const MappingParams& p, double s_R, MappingState* st);

struct EffectParams {
  int kind;              // EffectKind
  double e_lo, e_hi;     // effect range [off, on]
  double time_constant;  // temperature: first-order lag (s)
  double droplet_volume_l;  // fluid: volume of one emitted droplet (litres)
};

// output: what the effect realises now:
//   geometry     joint position target (rad or m) = s_E
//   illumination light output (lm) = s_E
//   temperature  actual temperature (C), lagging s_E with time_constant
//   fluid        flow (L/min) = s_E; particles are emitted at that rate
//   airflow      air speed at the outlet (m/s) = s_E
struct EffectState {
  double output;
  double emit_remainder;  // fluid: fraction of a droplet carried to the next step
  long emitted;           // fluid: droplets emitted so far
  // temperature: the lag's per-step factor 1 - exp(-dt / tau), kept for the
  // dt it was computed for (exp costs more than the rest of a template, and
  // dt rarely changes between steps).
  double lag_dt;
  double lag_factor;
};

void effect_init(const EffectParams& p, EffectState* st);
// Advances the effect by dt seconds towards s_E. Returns how many droplets to
// emit during this step (fluid; 0 for every other effect).
inline int effect_step(const EffectParams& p, double s_E, double dt, EffectState* st);

// Droplets per second for a flow in L/min.
inline double droplet_rate(const EffectParams& p, double flow_l_per_min);

// Air speed (m/s) at a point `distance` metres along the outlet axis and
// `angle` radians off it, for outlet speed s (m/s): full speed at the outlet,
// falling linearly to 0 at `reach`; 0 outside the cone of half-angle
// `cone_angle`.
double air_speed_at(double s, double distance, double angle, double cone_angle,
                    double reach);
// Drag force magnitude (N) of air at `speed` on a body of cross-section `area`
// (m^2): 0.5 * rho_air * Cd * A * v^2 with rho_air = 1.2 kg/m^3, Cd = 1.
double air_drag(double speed, double area);

struct FunctionParams {
  MappingParams mapping;
  EffectParams effect;
};
struct FunctionState {
  MappingState mapping;
  EffectState effect;
};

void function_init(const FunctionParams& p, double s_R0, FunctionState* st);
// One control step: map s_R, then advance the effect by dt. Returns droplets
// to emit (fluid), else 0. The new s_E is st->mapping.s_E.
inline int function_step(const FunctionParams& p, double s_R, double dt, FunctionState* st);

// ---- Inline definitions: what runs every control step ----
// Inline so that each binding compiles them into its own control loop (the
// harness, the generated callbacks, the Bullet program): called across
// translation units, their code sat apart from the loop and made MuJoCo's own
// step measurably slower around it (bench/README.md, playback).

inline double clamp_between(double v, double a, double b) {
  const double lo = a < b ? a : b;
  const double hi = a < b ? b : a;
  return v < lo ? lo : (v > hi ? hi : v);
}

inline double press_band(const MappingParams& p) { return 0.01 * std::fabs(p.r_hi - p.r_lo); }

namespace detail {
// Returns 1 when s_R completes a press (rising edge through the threshold).
inline int press_edge(const MappingParams& p, double s_R, MappingState* st) {
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
}  // namespace detail

inline double mapping_update(const MappingParams& p, double s_R, MappingState* st) {
  switch (p.kind) {
    case kBinary:
      if (p.latching) {
        if (detail::press_edge(p, s_R, st)) st->on = !st->on;
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
      if (detail::press_edge(p, s_R, st)) st->s_E = clamp_between(st->s_E + p.delta, p.e_lo, p.e_hi);
      break;
    default:
      break;
  }
  return st->s_E;
}

inline double droplet_rate(const EffectParams& p, double flow_l_per_min) {
  if (p.droplet_volume_l <= 0 || flow_l_per_min <= 0) return 0;
  return flow_l_per_min / 60.0 / p.droplet_volume_l;
}

inline int effect_step(const EffectParams& p, double s_E, double dt, EffectState* st) {
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

inline int function_step(const FunctionParams& p, double s_R, double dt, FunctionState* st) {
  const double s_E = mapping_update(p.mapping, s_R, &st->mapping);
  return effect_step(p.effect, s_E, dt, &st->effect);
}

}  // namespace efc_rt

#endif  // EFC_RUNTIME_H_
