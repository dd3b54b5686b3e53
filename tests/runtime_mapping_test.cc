// The runtime's mappings and effects against the spec's formulas.
#include <gtest/gtest.h>

#include <cmath>

#include "efc_runtime.h"

using namespace efc_rt;

namespace {

MappingParams base(int kind) {
  MappingParams p{};
  p.kind = kind;
  p.r_lo = 0;
  p.r_hi = 1;
  p.e_lo = 0;
  p.e_hi = 10;
  p.threshold = 0.5;
  p.hysteresis = 0.1;
  p.gain = 10;
  p.offset = 0;
  p.delta = 2;
  p.initial = 0;
  return p;
}

}  // namespace

TEST(RuntimeMapping, BinaryFollowsThreshold) {
  MappingParams p = base(kBinary);
  MappingState st;
  mapping_init(p, 0, &st);
  EXPECT_EQ(st.s_E, 0);
  EXPECT_EQ(mapping_update(p, 0.49, &st), 0);
  EXPECT_EQ(mapping_update(p, 0.5, &st), 10);  // s_R >= t
  EXPECT_EQ(mapping_update(p, 0.9, &st), 10);
  EXPECT_EQ(mapping_update(p, 0.2, &st), 0);
}

TEST(RuntimeMapping, LatchingBinaryTogglesOnEachPress) {
  MappingParams p = base(kBinary);
  p.latching = 1;
  MappingState st;
  mapping_init(p, 0, &st);
  const double press[] = {0, 0.6, 1.0, 0.3, 0.0, 0.7, 0.1, 0.8, 0.0};
  const double want[] = {0, 10, 10, 10, 10, 0, 0, 10, 10};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(mapping_update(p, press[i], &st), want[i]) << i;
  EXPECT_EQ(st.presses, 3);
}

TEST(RuntimeMapping, PressNeedsReArmBelowBand) {
  MappingParams p = base(kCumulative);
  MappingState st;
  mapping_init(p, 0, &st);
  mapping_update(p, 0.6, &st);    // press 1
  mapping_update(p, 0.495, &st);  // within the 1% band: not re-armed
  mapping_update(p, 0.6, &st);    // no press
  EXPECT_EQ(st.s_E, 2);
  mapping_update(p, 0.48, &st);  // re-armed
  mapping_update(p, 0.6, &st);
  EXPECT_EQ(st.s_E, 4);
}

TEST(RuntimeMapping, StartingAbovePressIsNotAPress) {
  MappingParams p = base(kCumulative);
  MappingState st;
  mapping_init(p, 0.9, &st);
  mapping_update(p, 0.9, &st);
  EXPECT_EQ(st.s_E, 0);
  mapping_update(p, 0.0, &st);
  mapping_update(p, 0.9, &st);
  EXPECT_EQ(st.s_E, 2);
}

TEST(RuntimeMapping, StepHasHysteresis) {
  MappingParams p = base(kStep);
  MappingState st;
  mapping_init(p, 0, &st);
  EXPECT_EQ(mapping_update(p, 0.5, &st), 0);   // needs s_R > t
  EXPECT_EQ(mapping_update(p, 0.51, &st), 10);
  EXPECT_EQ(mapping_update(p, 0.45, &st), 10);  // inside the band
  EXPECT_EQ(mapping_update(p, 0.39, &st), 0);   // below t - h
  EXPECT_EQ(mapping_update(p, 0.45, &st), 0);
}

TEST(RuntimeMapping, LinearClampsBetweenEnds) {
  MappingParams p = base(kLinear);
  MappingState st;
  mapping_init(p, 0, &st);
  EXPECT_DOUBLE_EQ(mapping_update(p, 0.25, &st), 2.5);
  EXPECT_DOUBLE_EQ(mapping_update(p, 2.0, &st), 10);
  // Reversed range [off=10, on=0] with negative gain: clamp works either way.
  p.e_lo = 10;
  p.e_hi = 0;
  p.gain = -10;
  p.offset = 10;
  EXPECT_DOUBLE_EQ(mapping_update(p, 0.25, &st), 7.5);
  EXPECT_DOUBLE_EQ(mapping_update(p, 5, &st), 0);
  EXPECT_DOUBLE_EQ(mapping_update(p, -5, &st), 10);
}

TEST(RuntimeMapping, CumulativeClampsAndHolds) {
  MappingParams p = base(kCumulative);
  p.delta = 4;
  MappingState st;
  mapping_init(p, 0, &st);
  for (int i = 0; i < 5; ++i) {
    mapping_update(p, 0.0, &st);
    mapping_update(p, 1.0, &st);
  }
  EXPECT_EQ(st.s_E, 10);  // 4, 8, 10, 10, 10
  p.delta = -3;           // a minus button
  mapping_update(p, 0.0, &st);
  mapping_update(p, 1.0, &st);
  EXPECT_EQ(st.s_E, 7);
}

TEST(RuntimeEffect, TemperatureIsFirstOrderLag) {
  EffectParams e{kTemperature, 20, 200, 10, 0};
  EffectState st;
  effect_init(e, &st);
  EXPECT_EQ(st.output, 20);
  const double dt = 0.01;
  for (int i = 0; i < 1000; ++i) effect_step(e, 200, dt, &st);  // 10 s = one tau
  EXPECT_NEAR(st.output, 20 + 180 * (1 - std::exp(-1.0)), 1e-9);
}

// The lag factor is cached per dt: a step of another length must recompute it.
TEST(RuntimeEffect, TemperatureLagFollowsAChangingTimeStep) {
  EffectParams e{kTemperature, 20, 200, 10, 0};
  EffectState st;
  effect_init(e, &st);
  for (int i = 0; i < 500; ++i) effect_step(e, 200, 0.01, &st);  // 5 s
  for (int i = 0; i < 100; ++i) effect_step(e, 200, 0.05, &st);  // 5 s more
  EXPECT_NEAR(st.output, 20 + 180 * (1 - std::exp(-1.0)), 1e-9);
  for (int i = 0; i < 10; ++i) effect_step(e, 20, 1.0, &st);  // cooling for one tau
  EXPECT_NEAR(st.output, 20 + 180 * (1 - std::exp(-1.0)) * std::exp(-1.0), 1e-9);
}

TEST(RuntimeEffect, FluidEmitsAtRateWithRemainder) {
  EffectParams e{kFluid, 0, 6, 0, 1e-3};  // 1 mL droplets
  EffectState st;
  effect_init(e, &st);
  // 6 L/min = 0.1 L/s = 100 droplets/s; over 1 s at dt 0.001 exactly 100, although each step asks for 0.1.
  long total = 0;
  for (int i = 0; i < 1000; ++i) total += effect_step(e, 6, 0.001, &st);
  EXPECT_EQ(total, 100);
  EXPECT_EQ(st.emitted, 100);
  EXPECT_EQ(effect_step(e, 0, 0.001, &st), 0);
}

TEST(RuntimeEffect, AirSpeedFallsWithDistanceAndCone) {
  EXPECT_DOUBLE_EQ(air_speed_at(10, 0, 0, 0.3, 1), 10);
  EXPECT_DOUBLE_EQ(air_speed_at(10, 0.5, 0.1, 0.3, 1), 5);
  EXPECT_DOUBLE_EQ(air_speed_at(10, 0.5, 0.4, 0.3, 1), 0);
  EXPECT_DOUBLE_EQ(air_speed_at(10, 1.5, 0.0, 0.3, 1), 0);
  EXPECT_NEAR(air_drag(10, 0.01), 0.6, 1e-12);
}
