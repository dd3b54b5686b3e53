"""Unit tests of backends/python/efc_templates.py, the Python mirror of runtime/.

Run from the repository root: python3 -m unittest discover -s tests/python
Expected values are computed by hand (binary-exact inputs where a boundary is
tested), so a changed operation order or rule fails here; bit-identity with
the C++ replay is checked against runtime/efc_replay on the same fixtures.
"""

import copy
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
MODULE = os.path.join(ROOT, "backends", "python", "efc_templates.py")
FIXTURES = os.path.join(HERE, "fixtures")
sys.path.insert(0, os.path.dirname(MODULE))

import efc_templates as efc  # noqa: E402


def fixture(name):
    return os.path.join(FIXTURES, name)


def mapping(kind, **fields):
    values = dict(r_lo=0.0, r_hi=100.0, e_lo=10.0, e_hi=20.0, threshold=50.0, hysteresis=0.0,
                  latching=0, gain=0.0, offset=0.0, delta=0.0, initial=0.0)
    values.update(fields)
    return efc.MappingParams(kind=kind, **values)


def effect(kind, **fields):
    values = dict(e_lo=20.0, e_hi=100.0, time_constant=0.0, droplet_volume_l=0.0)
    values.update(fields)
    return efc.EffectParams(kind=kind, **values)


def run_updates(p, s_R0, trajectory):
    st = efc.mapping_init(p, s_R0)
    return st, [efc.mapping_update(p, s_R, st) for s_R in trajectory]


class TempDirTest(unittest.TestCase):
    def setUp(self):
        self._dir = tempfile.TemporaryDirectory()
        self.dir = self._dir.name

    def tearDown(self):
        self._dir.cleanup()

    def write(self, name, text):
        path = os.path.join(self.dir, name)
        with open(path, "w", newline="") as f:
            f.write(text)
        return path


class ClampAndBand(unittest.TestCase):
    def test_clamp_between_accepts_either_order(self):
        self.assertEqual(efc.clamp_between(5.0, 0.0, 10.0), 5.0)
        self.assertEqual(efc.clamp_between(-1.0, 10.0, 0.0), 0.0)
        self.assertEqual(efc.clamp_between(11.0, 10.0, 0.0), 10.0)
        self.assertEqual(efc.clamp_between(3.0, 10.0, 0.0), 3.0)

    def test_press_band_is_one_percent_of_the_range_either_way(self):
        self.assertEqual(efc.press_band(mapping(efc.BINARY, r_lo=0.0, r_hi=100.0)), 1.0)
        self.assertEqual(efc.press_band(mapping(efc.BINARY, r_lo=100.0, r_hi=0.0)), 1.0)
        self.assertEqual(efc.press_band(mapping(efc.BINARY, r_lo=-300.0, r_hi=100.0)), 4.0)


class BinaryMapping(unittest.TestCase):
    def test_threshold_is_inclusive(self):
        p = mapping(efc.BINARY)
        st, out = run_updates(p, 50.0, [49.999, 50.0, 100.0, 0.0])
        self.assertEqual(out, [10.0, 20.0, 20.0, 10.0])
        self.assertEqual(efc.mapping_init(p, 50.0).s_E, 20.0)
        self.assertEqual(efc.mapping_init(p, 49.0).s_E, 10.0)

    def test_latching_toggles_once_per_press_with_the_band(self):
        p = mapping(efc.BINARY, latching=1)
        # re-arm level = 50 - 1 = 49: 49 itself does not re-arm, 48.5 does.
        st, out = run_updates(p, 0.0, [50.0, 60.0, 49.0, 70.0, 48.5, 49.5, 50.0, 0.0, 55.0])
        self.assertEqual(out, [20.0, 20.0, 20.0, 20.0, 20.0, 20.0, 10.0, 10.0, 20.0])
        self.assertEqual(st.presses, 3)

    def test_latching_starts_off_and_unarmed_above_the_rearm_level(self):
        p = mapping(efc.BINARY, latching=1)
        st = efc.mapping_init(p, 49.5)
        self.assertEqual((st.s_E, st.armed, st.on), (10.0, 0, 0))
        self.assertEqual(efc.mapping_update(p, 60.0, st), 10.0)  # no press without re-arming
        self.assertEqual(efc.mapping_init(p, 48.0).armed, 1)


class StepMapping(unittest.TestCase):
    def test_strict_threshold_and_hysteresis(self):
        p = mapping(efc.STEP, threshold=0.5, hysteresis=0.25, r_hi=1.0)
        st, out = run_updates(p, 0.5, [0.5, 0.5000001, 0.26, 0.25, 0.2499, 0.5, 0.75])
        self.assertEqual(out, [10.0, 20.0, 20.0, 20.0, 10.0, 10.0, 20.0])

    def test_starts_on_strictly_above_the_threshold(self):
        p = mapping(efc.STEP, threshold=0.5, hysteresis=0.25, r_hi=1.0)
        self.assertEqual(efc.mapping_init(p, 0.5).s_E, 10.0)
        self.assertEqual(efc.mapping_init(p, 0.5000001).s_E, 20.0)

    def test_reversed_effect_range(self):
        p = mapping(efc.STEP, e_lo=5.0, e_hi=-5.0)
        self.assertEqual(run_updates(p, 0.0, [60.0, 10.0])[1], [-5.0, 5.0])


class LinearMapping(unittest.TestCase):
    def test_gain_offset_and_clamp(self):
        p = mapping(efc.LINEAR, r_lo=1.0, r_hi=3.0, e_lo=0.0, e_hi=10.0, gain=5.0, offset=0.0)
        self.assertEqual(run_updates(p, 2.0, [2.0, 0.0, 4.0, 2.5])[1], [5.0, 0.0, 10.0, 7.5])
        self.assertEqual(efc.mapping_init(p, 1.5).s_E, 2.5)

    def test_negative_gain(self):
        p = mapping(efc.LINEAR, r_lo=1.0, r_hi=3.0, e_lo=0.0, e_hi=10.0, gain=-5.0, offset=10.0)
        self.assertEqual(run_updates(p, 1.0, [2.0, 1.0, 3.5, 0.0])[1], [5.0, 10.0, 0.0, 10.0])

    def test_reversed_effect_range_clamps_to_both_ends(self):
        p = mapping(efc.LINEAR, r_lo=0.0, r_hi=2.0, e_lo=4.0, e_hi=0.0, gain=-2.0, offset=4.0)
        self.assertEqual(run_updates(p, 0.0, [0.5, -1.0, 3.0])[1], [3.0, 4.0, 0.0])


class CumulativeMapping(unittest.TestCase):
    def test_adds_delta_per_press_and_clamps(self):
        p = mapping(efc.CUMULATIVE, e_lo=0.0, e_hi=3.0, delta=1.0, initial=0.5)
        st, out = run_updates(p, 0.0, [50.0, 40.0, 60.0, 49.5, 70.0, 10.0, 50.0, 0.0, 50.0])
        self.assertEqual(out, [1.5, 1.5, 2.5, 2.5, 2.5, 2.5, 3.0, 3.0, 3.0])
        self.assertEqual(st.presses, 4)

    def test_initial_is_clamped_and_negative_delta_counts_down(self):
        p = mapping(efc.CUMULATIVE, e_lo=0.0, e_hi=3.0, delta=-1.25, initial=5.0)
        self.assertEqual(efc.mapping_init(p, 0.0).s_E, 3.0)
        self.assertEqual(run_updates(p, 0.0, [50.0, 0.0, 50.0, 0.0, 50.0])[1],
                         [1.75, 1.75, 0.5, 0.5, 0.0])

    def test_reversed_effect_range(self):
        p = mapping(efc.CUMULATIVE, e_lo=3.0, e_hi=0.0, delta=1.0, initial=1.0)
        self.assertEqual(run_updates(p, 0.0, [50.0, 0.0, 50.0, 0.0, 50.0])[1],
                         [2.0, 2.0, 3.0, 3.0, 3.0])

    def test_a_receptor_starting_pressed_must_release_first(self):
        p = mapping(efc.CUMULATIVE, e_lo=0.0, e_hi=10.0, delta=1.0, initial=0.0)
        self.assertEqual(run_updates(p, 80.0, [90.0, 48.0, 50.0])[1], [0.0, 0.0, 1.0])


class Effects(unittest.TestCase):
    def test_init_is_off(self):
        st = efc.effect_init(effect(efc.TEMPERATURE))
        self.assertEqual((st.output, st.emit_remainder, st.emitted, st.lag_dt, st.lag_factor),
                         (20.0, 0.0, 0, -1.0, 0.0))

    def test_direct_effects_follow_s_E(self):
        for kind in (efc.GEOMETRY, efc.ILLUMINATION, efc.AIRFLOW):
            p = effect(kind)
            st = efc.effect_init(p)
            self.assertEqual(efc.effect_step(p, 42.5, 0.002, st), 0)
            self.assertEqual(st.output, 42.5)

    def test_temperature_lags_exactly(self):
        p = effect(efc.TEMPERATURE, time_constant=2.0)
        st = efc.effect_init(p)
        efc.effect_step(p, 100.0, 0.5, st)
        # 20 + 80 (1 - e^-0.25) = 20 + 80 * 0.221199216928595...
        self.assertAlmostEqual(st.output, 37.69593735428761, places=12)
        self.assertEqual(st.output, 20.0 + (100.0 - 20.0) * (1.0 - math.exp(-0.5 / 2.0)))
        self.assertEqual(st.lag_dt, 0.5)

    def test_lag_factor_is_recomputed_when_dt_changes(self):
        p = effect(efc.TEMPERATURE, time_constant=2.0)
        st = efc.effect_init(p)
        efc.effect_step(p, 100.0, 0.5, st)
        efc.effect_step(p, 100.0, 0.5, st)
        # two steps of 0.5 s: 100 - 80 e^-0.5
        self.assertAlmostEqual(st.output, 51.47754722, places=7)
        efc.effect_step(p, 100.0, 2.0, st)
        self.assertEqual(st.lag_dt, 2.0)
        self.assertEqual(st.lag_factor, 1.0 - math.exp(-1.0))
        self.assertAlmostEqual(st.output, 100.0 - 80.0 * math.exp(-1.5), places=12)

    def test_zero_time_constant_jumps(self):
        p = effect(efc.TEMPERATURE, time_constant=0.0)
        st = efc.effect_init(p)
        efc.effect_step(p, 250.0, 0.002, st)
        self.assertEqual(st.output, 250.0)

    def test_fluid_emits_whole_droplets_at_the_rate(self):
        # 6 L/min of 1 mL droplets = 100 per second = 0.2 per 2 ms step
        p = effect(efc.FLUID, e_lo=0.0, e_hi=6.0, droplet_volume_l=0.001)
        st = efc.effect_init(p)
        emits = [efc.effect_step(p, 6.0, 0.002, st) for _ in range(10)]
        self.assertEqual(emits, [0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
        for _ in range(990):
            efc.effect_step(p, 6.0, 0.002, st)
        self.assertEqual(st.emitted, 200)
        self.assertEqual(st.output, 6.0)
        self.assertGreaterEqual(st.emit_remainder, 0.0)

    def test_fluid_several_droplets_per_step(self):
        p = effect(efc.FLUID, e_lo=0.0, e_hi=6.0, droplet_volume_l=0.001)
        st = efc.effect_init(p)
        self.assertEqual(efc.effect_step(p, 6.0, 0.025, st), 2)  # 2.5 droplets
        self.assertEqual(st.emit_remainder, 0.5)
        self.assertEqual(efc.effect_step(p, 6.0, 0.025, st), 3)
        self.assertEqual(st.emit_remainder, 0.0)

    def test_fluid_epsilon_keeps_a_droplet_lost_to_rounding(self):
        # 0.1 droplet per step: ten steps accumulate to 0.9999999999999999
        p = effect(efc.FLUID, e_lo=0.0, e_hi=6.0, droplet_volume_l=0.001)
        st = efc.effect_init(p)
        self.assertEqual([efc.effect_step(p, 6.0, 0.001, st) for _ in range(10)], [0] * 9 + [1])

    def test_no_flow_or_no_volume_emits_nothing(self):
        p = effect(efc.FLUID, e_lo=0.0, e_hi=6.0, droplet_volume_l=0.0)
        st = efc.effect_init(p)
        self.assertEqual([efc.effect_step(p, 6.0, 0.1, st) for _ in range(5)], [0] * 5)
        self.assertEqual(efc.droplet_rate(effect(efc.FLUID, droplet_volume_l=0.001), -1.0), 0.0)
        self.assertEqual(efc.droplet_rate(effect(efc.FLUID, droplet_volume_l=0.001), 6.0), 100.0)

    def test_function_step_maps_then_advances(self):
        params = efc.FunctionParams(mapping(efc.STEP, e_lo=0.0, e_hi=6.0),
                                    effect(efc.FLUID, e_lo=0.0, e_hi=6.0, droplet_volume_l=0.001))
        st = efc.function_init(params, 0.0)
        self.assertEqual(efc.function_step(params, 0.0, 0.5, st), 0)
        self.assertEqual(efc.function_step(params, 60.0, 0.5, st), 50)
        self.assertEqual((st.mapping.s_E, st.effect.output, st.effect.emitted), (6.0, 6.0, 50))


class Air(unittest.TestCase):
    def test_air_speed_falls_linearly_inside_the_cone(self):
        self.assertEqual(efc.air_speed_at(4.0, 0.75, 0.0, 0.3, 1.5), 2.0)
        self.assertEqual(efc.air_speed_at(4.0, 0.0, -0.3, 0.3, 1.5), 4.0)
        self.assertEqual(efc.air_speed_at(4.0, 1.5, 0.0, 0.3, 1.5), 0.0)
        self.assertEqual(efc.air_speed_at(4.0, 1.6, 0.0, 0.3, 1.5), 0.0)
        self.assertEqual(efc.air_speed_at(4.0, 0.5, 0.31, 0.3, 1.5), 0.0)
        self.assertEqual(efc.air_speed_at(4.0, -0.1, 0.0, 0.3, 1.5), 0.0)
        self.assertEqual(efc.air_speed_at(4.0, 0.0, 0.0, 0.3, 0.0), 0.0)

    def test_drag(self):
        self.assertAlmostEqual(efc.air_drag(10.0, 0.01), 0.6, places=15)
        self.assertEqual(efc.air_drag(0.0, 1.0), 0.0)

    def test_airflow_force_pushes_along_the_outlet_axis(self):
        fn = {"cone_angle": 0.35, "reach": 1.5}
        fx, fy, fz = efc.airflow_force(fn, 4.0, (0.0, 0.0, 1.0), (0.0, 0.0, -2.0), (0.0, 0.0, 0.25), 0.01)
        self.assertEqual((fx, fy), (0.0, 0.0))
        self.assertAlmostEqual(fz, -0.024, places=15)  # speed 2 m/s: 0.6 * 0.01 * 4
        self.assertEqual(efc.airflow_force(fn, 4.0, (0, 0, 0), (0, 0, 1), (1.0, 0.0, 0.1), 0.01), (0.0, 0.0, 0.0))
        self.assertEqual(efc.airflow_force(fn, 0.0, (0, 0, 0), (0, 0, 1), (0.0, 0.0, 0.1), 0.01), (0.0, 0.0, 0.0))


class Realisation(unittest.TestCase):
    def test_glow_fraction(self):
        fn = {"effect": {"e_lo": 20.0}, "glow_max": 400.0}
        self.assertEqual([efc.glow_fraction(fn, t) for t in (0.0, 20.0, 210.0, 400.0, 900.0)],
                         [0.0, 0.0, 0.5, 1.0, 1.0])
        self.assertEqual(efc.glow_fraction({"effect": {"e_lo": 20.0}, "glow_max": None}, 20.5), 0.5)
        self.assertEqual(efc.glow_fraction({"effect": {"e_lo": 20.0}, "glow_max": 10.0}, 21.0), 1.0)

    def test_hot_rgb(self):
        self.assertEqual(efc.HOT_RGB, (1.0, 0.22, 0.04))

    def test_flow_meter_counts_the_last_window(self):
        for meter in (efc.FlowMeter(window=0.5, dt=0.002), efc.FlowMeter()):
            for k in range(1000):
                meter.add(k * 0.002, 1)
            # 250 droplets of 1 mL in 0.5 s = 30 L/min
            self.assertAlmostEqual(meter.flow(999 * 0.002, 0.001), 30.0, places=12)
            self.assertEqual(meter.flow(10.0, 0.001), 0.0)

    def test_flow_meter_half_step_slack(self):
        # 301 droplets at k * 2 ms; at 0.6 s the one at 0.1 s is a rounding
        # error inside a bare 0.5 s window: the window holds 250 steps.
        meter = efc.FlowMeter(window=0.5)
        for k in range(301):
            meter.add(k * 0.002, 1)
        self.assertAlmostEqual(meter.flow(300 * 0.002, 0.001), 30.0, places=12)


class Profiles(TempDirTest):
    def target(self, text, t, lo=1.0, hi=3.0, q0=0.0, duration=4.0, part="lever"):
        return efc.profile_target(efc.parse_profile(text), part, lo, hi, q0, t, duration)

    def test_ramp(self):
        self.assertEqual([self.target("ramp", t) for t in (-1.0, 0.0, 1.0, 4.0, 5.0)],
                         [1.0, 1.0, 1.5, 3.0, 3.0])

    def test_sweep(self):
        self.assertEqual([self.target("sweep", t) for t in (0.0, 1.0, 2.0, 3.0, 4.0)],
                         [1.0, 2.0, 3.0, 2.0, 1.0])

    def test_press_cycles(self):
        def at(t):
            return self.target("press:2", t, lo=0.0, hi=1.0, duration=10.0)
        # cycle fractions 0, 0.1, 0.5 (dwell at hi), 0.9, second dwell, end
        self.assertEqual([at(t) for t in (0.0, 0.5, 2.5, 4.5, 7.5, 10.0)],
                         [0.0, 0.0, 1.0, 0.0, 1.0, 0.0])
        self.assertAlmostEqual(at(1.5), 0.5, places=12)  # rising
        self.assertAlmostEqual(at(3.5), 0.5, places=12)  # falling
        self.assertEqual(efc.parse_profile("press:3").presses, 3)

    def test_hold_approaches_over_a_tenth_of_a_second(self):
        self.assertEqual(efc.HOLD_APPROACH, 0.1)
        self.assertEqual([self.target("hold:0.5", t, q0=0.0) for t in (0.0, 0.05, 0.1, 3.0)],
                         [0.0, 0.25, 0.5, 0.5])
        self.assertEqual(self.target("hold:lo", 1.0, q0=2.0), 1.0)
        self.assertEqual(self.target("hold:hi", 1.0, q0=2.0), 3.0)
        self.assertEqual(self.target("hold:hi", 0.0, q0=2.0), 2.0)
        # at exactly 0.1 s the target is V itself, not q0 + (V - q0) * 1
        self.assertEqual(self.target("hold:-0.9", 0.1, q0=-2.0), -0.9)
        self.assertEqual(self.target("hold:-0.9", 0.05, q0=-2.0), -1.45)

    def test_zero_duration_is_the_end(self):
        self.assertEqual(self.target("ramp", 0.0, duration=0.0), 3.0)

    def test_csv_interpolates_and_holds_the_ends(self):
        path = self.write("p.csv", "t,lever\n0,0\n1,2\n3,6\n")
        p = efc.parse_profile("csv:" + path)
        at = [efc.profile_target(p, "lever", 0.0, 1.0, 0.0, t, 4.0) for t in (-1.0, 0.5, 1.0, 2.0, 5.0)]
        self.assertEqual(at, [0.0, 1.0, 2.0, 4.0, 6.0])
        self.assertEqual(efc.profile_target(p, "other", 0.0, 1.0, 0.7, 2.0, 4.0), 0.7)

    def test_csv_at_a_knot_is_the_knot_value(self):
        # upper_bound: the segment after the knot, u = 0 (not -2 + 1 x 1.1)
        p = efc.parse_profile("csv:" + self.write("p.csv", "t,lever\n0,-2\n1,-0.9\n2,5\n"))
        self.assertEqual(efc.profile_target(p, "lever", 0.0, 1.0, 0.0, 1.0, 4.0), -0.9)

    def test_csv_tolerates_blanks_spaces_and_crlf(self):
        p = efc.parse_profile("csv:" + fixture("profile_parts.csv"))
        self.assertEqual(sorted(p.csv_parts), ["dial", "ghost", "knob", "lever"])
        self.assertEqual(p.csv_t, [0.0, 0.5, 0.75, 1.2, 2.0, 2.1, 3.9])
        self.assertEqual(p.csv_parts["lever"][2], 0.041)

    def test_bad_arguments(self):
        cases = {
            "bogus": "unknown profile 'bogus' (expected ramp, sweep, press:N, hold:V, csv:FILE)",
            "ramp:2": "unknown profile 'ramp:2' (expected ramp, sweep, press:N, hold:V, csv:FILE)",
            "csv:": "unknown profile 'csv:' (expected ramp, sweep, press:N, hold:V, csv:FILE)",
            "press:0": "press:N needs a whole number of presses >= 1, got '0'",
            "press:1.5": "press:N needs a whole number of presses >= 1, got '1.5'",
            "press:1000001": "press:N needs a whole number of presses >= 1, got '1000001'",
            "hold:x": "hold:V needs a finite number, 'lo' or 'hi', got 'x'",
            "hold:inf": "hold:V needs a finite number, 'lo' or 'hi', got 'inf'",
        }
        for text, message in cases.items():
            with self.assertRaises(efc.EfcError) as caught:
                efc.parse_profile(text)
            self.assertEqual((caught.exception.message, caught.exception.line, caught.exception.io_error),
                             (message, 0, False), text)

    def test_numbers_as_strtod_reads_them(self):
        self.assertEqual(efc.parse_profile("press:0x10").presses, 16)
        self.assertEqual(efc.parse_profile("press: 2").presses, 2)
        self.assertEqual(efc.parse_profile("hold:5.").hold_value, 5.0)
        for bad in ("1 ", "1_0", "nan", "1e", "0x", "1e-310", "1e-400", "", "+"):
            self.assertIsNone(efc.parse_double(bad), bad)
        self.assertEqual(efc.parse_double("0x1.8p3"), 12.0)
        self.assertEqual(efc.parse_double("0x1p-1074"), 5e-324)  # exact: no ERANGE
        self.assertEqual(efc.parse_double("0e-999999"), 0.0)

    def csv_error(self, text):
        path = self.write("bad.csv", text)
        with self.assertRaises(efc.EfcError) as caught:
            efc.parse_profile("csv:" + path)
        return caught.exception.line, caught.exception.message

    def test_csv_content_errors_name_the_line(self):
        header = "profile CSV must start with a header 't,<part>[,<part>...]'"
        self.assertEqual(self.csv_error(""), (0, "profile CSV is empty"))
        self.assertEqual(self.csv_error("\n \n"), (2, "profile CSV is empty"))
        self.assertEqual(self.csv_error("t,a\n\n"), (2, "profile CSV has no data rows"))
        self.assertEqual(self.csv_error("\nx,a\n0,1\n"), (2, header))
        self.assertEqual(self.csv_error("t\n0\n"), (1, header))
        self.assertEqual(self.csv_error("t,a,a\n0,1,2\n"), (1, "profile CSV names a column twice"))
        self.assertEqual(self.csv_error("t,a\n0,1\n1,2,3\n"), (3, "expected 2 values, found 3"))
        self.assertEqual(self.csv_error("t,a\n0,1,\n"), (2, "expected 2 values, found 3"))
        self.assertEqual(self.csv_error("t,a\n0,1\n0,2\n"), (3, "times must increase strictly"))
        self.assertEqual(self.csv_error("t,a\nnan,1\n"), (2, "time 'nan' is not a finite number"))
        self.assertEqual(self.csv_error("t,a\n0, 1e999 \n"),
                         (2, "value '1e999' of column 'a' is not a finite number"))

    def test_unreadable_csv_is_an_io_error(self):
        with self.assertRaises(efc.EfcError) as caught:
            efc.parse_profile("csv:" + os.path.join(self.dir, "missing.csv"))
        self.assertTrue(caught.exception.io_error)
        self.assertIn("cannot read profile file", caught.exception.message)


class Logs(TempDirTest):
    TABLE = {"functions": [{"name": "f"}, {"name": "g"}]}

    def test_format_value_is_printf_g9(self):
        self.assertEqual([efc.format_value(v) for v in (0.0, -0.0, 1 / 3, 1e-10, 123456789012.0, 2.5,
                                                        float("inf"), float("nan"))],
                         ["0", "-0", "0.333333333", "1e-10", "1.23456789e+11", "2.5", "inf", "nan"])

    def test_columns_rows_and_atomic_write(self):
        log = efc.CsvLog(self.TABLE)
        self.assertEqual(log.columns, ["t", "f.s_R", "f.s_E", "f.measured", "g.s_R", "g.s_E", "g.measured"])
        log.add(0.0, [1 / 3, 4.0], s_R=[0.1, 0.2], s_E=[1.0, 2.0])
        path = os.path.join(self.dir, "out.csv")
        log.write(path)
        with open(path, "rb") as f:
            self.assertEqual(f.read(), b"t,f.s_R,f.s_E,f.measured,g.s_R,g.s_E,g.measured\n"
                                       b"0,0.1,1,0.333333333,0.2,2,4\n")
        self.assertEqual(os.listdir(self.dir), ["out.csv"])

    def test_add_reads_s_R_and_s_E_from_the_templates(self):
        table = efc.load_functions(fixture("kettle_functions.json"))
        tpl = efc.Templates(table)
        tpl.reset({"lever": 0.25, "lid": 0.5})
        log = efc.CsvLog(tpl)
        log.add(0.0, tpl.output)
        # reset maps s_R, but the effect starts at rest (e_lo) until the first step
        self.assertEqual(log.rows, [[0.0, 0.25, 0.5, 0.0, 0.5, 20.0, 20.0]])
        with self.assertRaises(efc.EfcError):
            efc.CsvLog(table).add(0.0, [0.0, 0.0])

    def test_unwritable_path_is_an_io_error(self):
        log = efc.CsvLog(self.TABLE)
        with self.assertRaises(efc.EfcError) as caught:
            log.write(os.path.join(self.dir, "no", "such", "dir.csv"))
        self.assertTrue(caught.exception.io_error)


class TemplatesAndReplay(unittest.TestCase):
    def test_lround_rounds_halves_away_from_zero(self):
        self.assertEqual([efc.lround(x) for x in (0.5, 1.5, 2.5, -2.5, 0.49999999999999994, 1000.4999, 3.0)],
                         [1, 2, 3, -3, 0, 1000, 3])

    def test_templates_step_reads_receptors_by_joint_name(self):
        tpl = efc.Templates(efc.load_functions(fixture("toaster_functions.json")))
        tpl.reset({"lever": 0.0, "carriage": 0.0})
        self.assertEqual((tpl.s_E, tpl.output), ([0.0, 20.0], [0.0, 20.0]))
        self.assertEqual(tpl.step({"lever": 0.09, "carriage": 0.0}, 0.002), [0, 0])
        self.assertEqual(tpl.s_R, [0.09, 0.09])
        self.assertEqual(tpl.s_E, [0.095, 240.0])
        self.assertEqual(tpl.output[0], 0.095)
        self.assertEqual(tpl.output[1], 20.0 + 220.0 * (1.0 - math.exp(-0.002 / 25.0)))
        with self.assertRaises(efc.EfcError):
            tpl.step({"carriage": 0.0}, 0.002)

    def test_replay_of_a_chain_by_hand(self):
        # lever ramps 0 -> 1; lift puts the lid at 2 x lever; heat (step at
        # lid > 1, tau = dt) then sees the lid of the same step.
        table = efc.load_functions(fixture("kettle_functions.json"))
        log = efc.replay(table, efc.parse_profile("ramp"), 0.25, 0.0625)
        self.assertEqual(log.text(),
                         "t,lift.s_R,lift.s_E,lift.measured,heat.s_R,heat.s_E,heat.measured\n"
                         "0,0,0,0,0,20,20\n"
                         "0.0625,0.25,0.5,0.5,0.5,20,20\n"
                         "0.125,0.5,1,1,1,20,20\n"
                         "0.1875,0.75,1.5,1.5,1.5,100,70.5696447\n"   # 20 + 80 (1 - 1/e)
                         "0.25,1,2,2,2,100,89.1731773\n")             # 100 - 80 / e^2

    def test_replay_holds_unprofiled_joints_and_counts_steps(self):
        table = efc.load_functions(fixture("chain_functions.json"))
        log = efc.replay(table, efc.parse_profile("hold:lo"), 1.0, 0.002)
        self.assertEqual(len(log.rows), 501)
        self.assertEqual(log.rows[-1][0], 500 * 0.002)
        self.assertEqual(efc.profile_joints(table), [table["joints"][0]])

    def test_replay_resets_with_the_profile_at_t0(self):
        # A latching switch held pressed from t = 0 by the profile has not
        # been pressed: reset sees the profile's position, not the initial one.
        with open(fixture("toaster_functions.json")) as f:
            doc = json.load(f)
        doc["functions"][1]["mapping"].update(kind="binary", latching=True)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "t_functions.json")
            with open(path, "w") as f:
                json.dump(doc, f)
            csv = os.path.join(folder, "p.csv")
            with open(csv, "w") as f:
                f.write("t,lever\n0,0.1\n1,0.1\n")
            log = efc.replay(efc.load_functions(path), efc.parse_profile("csv:" + csv), 0.5, 0.1)
        toast = log.columns.index("toast.s_E")
        self.assertEqual([row[toast] for row in log.rows], [20.0] * 6)

    def test_replay_press_counts_presses(self):
        table = efc.load_functions(fixture("chain_functions.json"))
        log = efc.replay(table, efc.parse_profile("press:3"), 6.0, 0.002)
        heat = log.columns.index("heat.s_E")
        # each press opens the lid past 1.2: 20 + 3 x 40, clamped at 180... 140
        self.assertEqual(log.rows[-1][heat], 140.0)


class Loader(TempDirTest):
    def setUp(self):
        super().setUp()
        with open(fixture("toaster_functions.json")) as f:
            self.doc = json.load(f)

    def load(self, doc):
        path = self.write("t_functions.json", json.dumps(doc))
        return efc.load_functions(path)

    def error(self, doc):
        with self.assertRaises(efc.EfcError) as caught:
            self.load(doc)
        self.assertFalse(caught.exception.io_error)
        return caught.exception.message

    def test_fixtures_load_with_numbers_as_floats(self):
        for name in sorted(os.listdir(FIXTURES)):
            if name.endswith("_functions.json"):
                efc.load_functions(fixture(name))
        doc = copy.deepcopy(self.doc)
        doc["joints"][0]["hi"] = 1
        table = self.load(doc)
        self.assertIsInstance(table["joints"][0]["hi"], float)
        self.assertEqual(efc.function_params(table["functions"][1]).mapping.kind, efc.STEP)

    def test_wrong_format_and_version(self):
        doc = dict(self.doc, format="efc-spec")
        self.assertIn("t_functions.json: /format: expected \"efc-functions\", found \"efc-spec\"", self.error(doc))
        self.assertIn("/version: expected version 1, found 2", self.error(dict(self.doc, version=2)))
        self.assertIn("/version: expected version 1, found a boolean", self.error(dict(self.doc, version=True)))

    def test_missing_field_names_its_path(self):
        doc = copy.deepcopy(self.doc)
        del doc["functions"][1]["mapping"]["gain"]
        self.assertIn("t_functions.json: /functions/1/mapping/gain: missing required field 'gain'",
                      self.error(doc))
        doc = copy.deepcopy(self.doc)
        del doc["joints"][0]["initial"]
        self.assertIn("/joints/0/initial: missing", self.error(doc))

    def test_wrong_types_name_their_path(self):
        cases = [
            (("functions", 0, "mapping", "gain"), "5", "/functions/0/mapping/gain: expected a number, found a string"),
            (("functions", 0, "mapping", "latching"), 0, "/functions/0/mapping/latching: expected a boolean"),
            (("functions", 0, "mapping", "kind"), "toggle", "/functions/0/mapping/kind: expected one of"),
            (("functions", 1, "effect", "kind"), None, "/functions/1/effect/kind: expected one of"),
            (("joints", 0, "lo"), True, "/joints/0/lo: expected a number, found a boolean"),
            (("joints", 0, "axis"), [0, 1], "/joints/0/axis: expected an array of 3 numbers"),
            (("joints", 0, "axis"), [0, "1", 0], "/joints/0/axis/1: expected a number"),
            (("joints", 1, "drive_by"), "servo", "/joints/1/drive_by: expected one of"),
            (("functions", 1, "glow_max"), None, "/functions/1/glow_max: expected a number"),
            (("functions", 1, "site"), None, "/functions/1/site: expected an object"),
            (("functions",), {}, "/functions: expected an array, found an object"),
        ]
        for keys, value, message in cases:
            doc = copy.deepcopy(self.doc)
            target = doc
            for key in keys[:-1]:
                target = target[key]
            target[keys[-1]] = value
            self.assertIn(message, self.error(doc), keys)

    def test_references_must_name_table_joints(self):
        doc = copy.deepcopy(self.doc)
        doc["functions"][1]["receptor"]["joint"] = "trigger"
        self.assertIn("/functions/1/receptor/joint: receptor joint 'trigger' is not one of", self.error(doc))
        doc = copy.deepcopy(self.doc)
        doc["functions"][0]["effector"]["joint"] = None
        self.assertIn("/functions/0/effector/joint: a geometry effect needs an effector joint", self.error(doc))
        doc = copy.deepcopy(self.doc)
        doc["joints"][1]["joint"] = "lever"
        self.assertIn("/joints/1/joint: joint 'lever' is listed twice", self.error(doc))

    def test_non_finite_numbers_are_rejected(self):
        path = self.write("nan_functions.json", json.dumps(self.doc).replace('"damping": 0.1', '"damping": NaN', 1))
        with self.assertRaises(efc.EfcError) as caught:
            efc.load_functions(path)
        self.assertIn("/joints/0/damping: expected a finite number", caught.exception.message)

    def test_syntax_errors_give_line_and_column(self):
        path = self.write("bad_functions.json", '{\n  "format": "efc-functions",\n  "version" 1\n}\n')
        with self.assertRaises(efc.EfcError) as caught:
            efc.load_functions(path)
        self.assertIn("bad_functions.json:3:13: invalid JSON", caught.exception.message)

    def test_missing_file_is_an_io_error(self):
        with self.assertRaises(efc.EfcError) as caught:
            efc.load_functions(os.path.join(self.dir, "none.json"))
        self.assertTrue(caught.exception.io_error)


class CommandLine(TempDirTest):
    def run_cli(self, *args):
        result = subprocess.run([sys.executable, MODULE] + list(args), capture_output=True, text=True)
        self.assertNotIn("Traceback", result.stderr)
        return result.returncode, result.stderr

    def test_writes_the_replay_csv(self):
        out = os.path.join(self.dir, "out.csv")
        rc, err = self.run_cli(fixture("kettle_functions.json"), "--profile", "ramp", "--duration", "0.25",
                               "--dt", "0.0625", "--csv", out)
        self.assertEqual((rc, err), (0, ""))
        with open(out, "rb") as f:
            lines = f.read().split(b"\n")
        self.assertEqual(lines[4], b"0.1875,0.75,1.5,1.5,1.5,100,70.5696447")
        self.assertEqual(len(lines), 7)  # header, 5 rows, final newline

    def test_main_is_callable(self):
        out = os.path.join(self.dir, "out.csv")
        self.assertEqual(efc.main([fixture("toaster_functions.json"), "--profile", "press:2",
                                   "--duration", "1", "--csv", out]), 0)
        with open(out) as f:
            self.assertEqual(len(f.read().splitlines()), 502)

    def test_bad_functions_file_is_exit_1(self):
        bad = self.write("bad_functions.json", '{"format": "efc-functions", "version": 1}')
        rc, err = self.run_cli(bad, "--profile", "ramp", "--duration", "1", "--csv", os.path.join(self.dir, "o.csv"))
        self.assertEqual(rc, 1)
        self.assertTrue(err.startswith("efc_templates: "), err)
        self.assertIn("/object: missing required field", err)
        broken = self.write("broken_functions.json", "{")
        self.assertEqual(self.run_cli(broken, "--profile", "ramp", "--duration", "1", "--csv",
                                      os.path.join(self.dir, "o.csv"))[0], 1)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "o.csv")))

    def test_bad_profile_csv_content_is_exit_1(self):
        csv = self.write("p.csv", "t,lever\n0,0\n0,1\n")
        rc, err = self.run_cli(fixture("toaster_functions.json"), "--profile", "csv:" + csv, "--duration", "1",
                               "--csv", os.path.join(self.dir, "o.csv"))
        self.assertEqual(rc, 1)
        self.assertIn("p.csv:3: times must increase strictly", err)

    def test_usage_and_io_errors_are_exit_2(self):
        out = os.path.join(self.dir, "o.csv")
        table = fixture("toaster_functions.json")
        cases = [
            ([table, "--profile", "wiggle", "--duration", "1", "--csv", out], "unknown profile 'wiggle'"),
            ([table, "--profile", "press:0", "--duration", "1", "--csv", out], "press:N needs"),
            ([table, "--profile", "csv:" + os.path.join(self.dir, "no.csv"), "--duration", "1", "--csv", out],
             "cannot read profile file"),
            ([table, "--profile", "ramp", "--duration", "0", "--csv", out], "--duration must be"),
            ([table, "--profile", "ramp", "--duration", "1e6", "--csv", out], "--duration must be"),
            ([table, "--profile", "ramp", "--duration", "1", "--dt", "0.2", "--csv", out], "--dt must be"),
            ([table, "--profile", "ramp", "--duration", "0.01", "--dt", "0.02", "--csv", out], "--dt must be"),
            ([table, "--profile", "ramp", "--duration", "1e5", "--dt", "0.001", "--csv", out], "--dt must be"),
            ([table, "--profile", "ramp", "--duration", "nan", "--csv", out], "--duration must be"),
            ([table, "--profile", "ramp", "--duration", "1"], "--csv"),
            ([table, "--profile", "ramp", "--duration", "x", "--csv", out], "--duration"),
            ([os.path.join(self.dir, "none.json"), "--profile", "ramp", "--duration", "1", "--csv", out],
             "cannot read"),
            ([table, "--profile", "ramp", "--duration", "1", "--csv", os.path.join(self.dir, "a", "b.csv")],
             "cannot write"),
        ]
        for args, message in cases:
            rc, err = self.run_cli(*args)
            self.assertEqual(rc, 2, args)
            self.assertIn(message, err, args)
            self.assertTrue(err.startswith("efc_templates: ") or err.startswith("usage:"), err)

    def test_help_is_exit_0(self):
        self.assertEqual(self.run_cli("--help")[0], 0)

    def test_csv_profile_without_a_receptor_column_warns(self):
        csv = self.write("p.csv", "t,knob\n0,0\n1,1\n")
        rc, err = self.run_cli(fixture("toaster_functions.json"), "--profile", "csv:" + csv, "--duration", "1",
                               "--csv", os.path.join(self.dir, "o.csv"))
        self.assertEqual(rc, 0)
        self.assertIn("warning: profile CSV has no column for receptor 'lever'", err)



class RunSettingsTest(unittest.TestCase):
    """The command line every simulator script shares (add_run_arguments, run_settings)."""

    def settings(self, *argv):
        import argparse
        parser = argparse.ArgumentParser()
        efc.add_run_arguments(parser)
        table = efc.load_functions(os.path.join(FIXTURES, "toaster_functions.json"))
        return efc.run_settings(parser.parse_args(list(argv)), table)

    def test_steps_and_duration(self):
        s = self.settings()
        self.assertEqual((s.steps, s.dt, s.duration), (efc.DEFAULT_STEPS, 0.002, efc.DEFAULT_STEPS * 0.002))
        s = self.settings("--steps", "100", "--dt", "0.01")
        self.assertEqual((s.steps, s.duration), (100, 1.0))
        s = self.settings("--duration", "1.0")
        self.assertEqual((s.steps, s.duration), (500, 1.0))
        s = self.settings("--steps", "10", "--duration", "5")
        self.assertEqual((s.steps, s.duration), (10, 5.0))
        self.assertIsNone(s.profile)

    def test_usage_errors_are_status_2(self):
        for argv in (["--steps", "0"], ["--dt", "0"], ["--dt", "0.5"], ["--duration", "-1"],
                     ["--profile", "wiggle"], ["--csv", "/no/such/folder/x.csv"]):
            with self.assertRaises(efc.EfcError, msg=argv) as caught:
                self.settings(*argv)
            self.assertEqual(caught.exception.status, 2, argv)

    def test_a_bad_profile_line_is_status_1_and_located(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "p.csv")
            with open(path, "w") as f:
                f.write("t,lever\n0,0\n1,abc\n")
            with self.assertRaises(efc.EfcError) as caught:
                self.settings("--profile", "csv:" + path)
            self.assertEqual(caught.exception.status, 1)
            self.assertTrue(caught.exception.message.startswith(path + ":3: "))

    def test_profile_warnings(self):
        self.assertEqual(self.settings("--profile", "press:2").warnings, [])
        w = self.settings("--profile", "hold:5").warnings
        self.assertEqual(len(w), 1)
        self.assertIn("lever", w[0])
        self.assertIn("its joint limit stops it", w[0])
        table = efc.load_functions(os.path.join(FIXTURES, "toaster_functions.json"))
        replay = efc.profile_warnings(table, efc.parse_profile("hold:5"), limited=False)
        self.assertIn("the replay follows it", replay[0])

if __name__ == "__main__":
    unittest.main()
