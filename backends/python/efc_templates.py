"""efc runtime for Python: function templates, receptor profiles and the replay log.

A mirror of the C++ runtime (runtime/efc_runtime.{h,cc}, runtime/efc_profile.{h,cc}
and runtime/efc_replay.{h,cc}): every expression is evaluated in the same order with
the same libm functions, so the doubles computed here are bit-identical to the C++
ones. Standard library only, Python >= 3.8. See backends/python/README.md.

Replay with no simulator (the harness's CSV; measured = the effect's state):

    python3 efc_templates.py NAME_functions.json --profile press:3 --duration 6 \\
        [--dt 0.002] --csv out.csv

Exit status: 0 ok; 1 a bad functions file or profile CSV content; 2 usage or I/O.
"""

import argparse
import bisect
import collections
import decimal
import fractions
import json
import math
import os
import re
import sys

__all__ = [
    "EfcError", "load_functions", "Templates",
    "BINARY", "STEP", "LINEAR", "CUMULATIVE",
    "GEOMETRY", "ILLUMINATION", "TEMPERATURE", "FLUID", "AIRFLOW",
    "MappingParams", "MappingState", "EffectParams", "EffectState",
    "FunctionParams", "FunctionState", "function_params",
    "clamp_between", "press_band", "mapping_init", "mapping_update",
    "effect_init", "effect_step", "function_init", "function_step",
    "droplet_rate", "air_speed_at", "air_drag",
    "Profile", "parse_double", "parse_profile", "profile_target", "profile_joints", "HOLD_APPROACH",
    "CsvLog", "format_value", "glow_fraction", "HOT_RGB", "FlowMeter", "airflow_force",
    "lround", "check_timing", "replay", "main",
]

PROG = "efc_templates"


class EfcError(Exception):
    """A bad input, with a message fit for the user.

    line: 1-based line of a profile CSV error (0 when none); io_error: the file
    could not be read or written (exit status 2 rather than 1).
    """

    def __init__(self, message, line=0, io_error=False):
        super().__init__(message)
        self.message = message
        self.line = line
        self.io_error = io_error


# ---------------------------------------------------------------------------
# The runtime (runtime/efc_runtime.h). Kinds are the C++ enums' values.

BINARY, STEP, LINEAR, CUMULATIVE = 0, 1, 2, 3
GEOMETRY, ILLUMINATION, TEMPERATURE, FLUID, AIRFLOW = 0, 1, 2, 3, 4
MAPPING_KINDS = {"binary": BINARY, "step": STEP, "linear": LINEAR, "cumulative": CUMULATIVE}
EFFECT_KINDS = {"geometry": GEOMETRY, "illumination": ILLUMINATION,
                "temperature": TEMPERATURE, "fluid": FLUID, "airflow": AIRFLOW}
MAPPING_FIELDS = ("r_lo", "r_hi", "e_lo", "e_hi", "threshold", "hysteresis",
                  "gain", "offset", "delta", "initial")
EFFECT_FIELDS = ("e_lo", "e_hi", "time_constant", "droplet_volume_l")


class _Record:
    """A plain struct: fields by keyword, every other field 0."""

    __slots__ = ()

    def __init__(self, **fields):
        for name in self.__slots__:
            setattr(self, name, 0)
        for name, value in fields.items():
            setattr(self, name, value)

    def __repr__(self):
        body = ", ".join("%s=%r" % (n, getattr(self, n)) for n in self.__slots__)
        return "%s(%s)" % (type(self).__name__, body)


class MappingParams(_Record):
    """efc_rt::MappingParams; kind is BINARY..CUMULATIVE, latching 0 or 1."""

    __slots__ = ("kind",) + MAPPING_FIELDS[:6] + ("latching",) + MAPPING_FIELDS[6:]


class MappingState(_Record):
    __slots__ = ("s_E", "armed", "on", "presses")


class EffectParams(_Record):
    """efc_rt::EffectParams; kind is GEOMETRY..AIRFLOW."""

    __slots__ = ("kind",) + EFFECT_FIELDS


class EffectState(_Record):
    __slots__ = ("output", "emit_remainder", "emitted", "lag_dt", "lag_factor")


class FunctionParams:
    __slots__ = ("mapping", "effect")

    def __init__(self, mapping, effect):
        self.mapping = mapping
        self.effect = effect


class FunctionState:
    __slots__ = ("mapping", "effect")

    def __init__(self, mapping=None, effect=None):
        self.mapping = mapping if mapping is not None else MappingState()
        self.effect = effect if effect is not None else EffectState()


def function_params(fn):
    """FunctionParams of one function of a loaded table."""
    m, e = fn["mapping"], fn["effect"]
    mapping = MappingParams(kind=MAPPING_KINDS[m["kind"]], latching=1 if m["latching"] else 0,
                            **{name: m[name] for name in MAPPING_FIELDS})
    effect = EffectParams(kind=EFFECT_KINDS[e["kind"]], **{name: e[name] for name in EFFECT_FIELDS})
    return FunctionParams(mapping, effect)


def _ieee_divide(a, b):
    """a / b as C divides: Python raises on a zero divisor where C gives inf or NaN."""
    if b != 0:
        return a / b
    if a == 0 or a != a:
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def _exp(x):
    """C's exp: Python raises where C overflows to inf."""
    try:
        return math.exp(x)
    except OverflowError:
        return math.inf


def clamp_between(v, a, b):
    lo = a if a < b else b
    hi = b if a < b else a
    return lo if v < lo else (hi if v > hi else v)


def press_band(p):
    return 0.01 * math.fabs(p.r_hi - p.r_lo)


def mapping_init(p, s_R0, st=None):
    """Fills st (a new MappingState when None) for receptor state s_R0; returns it."""
    st = st if st is not None else MappingState()
    st.presses = 0
    # A receptor that starts at or above the threshold has not been pressed:
    # it must come back below the re-arm level first.
    st.armed = 1 if s_R0 < p.threshold - press_band(p) else 0
    st.on = 0
    if p.kind == BINARY:
        st.on = 0 if p.latching else (1 if s_R0 >= p.threshold else 0)
        st.s_E = p.e_hi if st.on else p.e_lo
    elif p.kind == STEP:
        st.on = 1 if s_R0 > p.threshold else 0
        st.s_E = p.e_hi if st.on else p.e_lo
    elif p.kind == LINEAR:
        st.s_E = clamp_between(p.offset + p.gain * (s_R0 - p.r_lo), p.e_lo, p.e_hi)
    elif p.kind == CUMULATIVE:
        st.s_E = clamp_between(p.initial, p.e_lo, p.e_hi)
    else:
        st.s_E = p.e_lo
    return st


def _press_edge(p, s_R, st):
    """1 when s_R completes a press (a rising edge through the threshold)."""
    if not st.armed:
        if s_R < p.threshold - press_band(p):
            st.armed = 1
        return 0
    if s_R >= p.threshold:
        st.armed = 0
        st.presses += 1
        return 1
    return 0


def mapping_update(p, s_R, st):
    """Advances the mapping to receptor state s_R; returns the new s_E."""
    if p.kind == BINARY:
        if p.latching:
            if _press_edge(p, s_R, st):
                st.on = 0 if st.on else 1
        else:
            st.on = 1 if s_R >= p.threshold else 0
        st.s_E = p.e_hi if st.on else p.e_lo
    elif p.kind == STEP:
        if not st.on and s_R > p.threshold:
            st.on = 1
        elif st.on and s_R < p.threshold - p.hysteresis:
            st.on = 0
        st.s_E = p.e_hi if st.on else p.e_lo
    elif p.kind == LINEAR:
        st.s_E = clamp_between(p.offset + p.gain * (s_R - p.r_lo), p.e_lo, p.e_hi)
    elif p.kind == CUMULATIVE:
        if _press_edge(p, s_R, st):
            st.s_E = clamp_between(st.s_E + p.delta, p.e_lo, p.e_hi)
    return st.s_E


def effect_init(p, st=None):
    """Fills st (a new EffectState when None): the effect at rest (off); returns it."""
    st = st if st is not None else EffectState()
    st.output = p.e_lo
    st.emit_remainder = 0.0
    st.emitted = 0
    st.lag_dt = -1.0  # no lag factor computed yet
    st.lag_factor = 0.0
    return st


def droplet_rate(p, flow_l_per_min):
    """Droplets per second for a flow in L/min."""
    if p.droplet_volume_l <= 0 or flow_l_per_min <= 0:
        return 0.0
    return flow_l_per_min / 60.0 / p.droplet_volume_l


def effect_step(p, s_E, dt, st):
    """Advances the effect by dt towards s_E; returns droplets to emit (fluid, else 0)."""
    if p.kind == TEMPERATURE:
        # Exact discretisation of dT/dt = (s_E - T) / tau; the factor is cached
        # per dt because exp costs more than the rest of a template.
        if dt != st.lag_dt:
            tau = p.time_constant if p.time_constant > 0 else 1e-9
            st.lag_factor = 1.0 - _exp(-dt / tau)
            st.lag_dt = dt
        st.output += (s_E - st.output) * st.lag_factor
        return 0
    if p.kind == FLUID:
        st.output = s_E
        want = droplet_rate(p, s_E) * dt + st.emit_remainder
        # The epsilon keeps a droplet from being lost to rounding when the
        # accumulated remainder lands a hair below a whole number.
        whole = want + 1e-9
        # C++ casts the floor to an integer, undefined for a NaN or infinite
        # flow (a simulation that blew up): emit nothing then.
        n = math.floor(whole) if math.isfinite(whole) else 0
        st.emit_remainder = want - n if want - n > 0 else 0.0
        st.emitted += n
        return n
    st.output = s_E
    return 0


def function_init(p, s_R0, st=None):
    st = st if st is not None else FunctionState()
    mapping_init(p.mapping, s_R0, st.mapping)
    effect_init(p.effect, st.effect)
    return st


def function_step(p, s_R, dt, st):
    """One control step: map s_R, then advance the effect by dt; returns droplets."""
    s_E = mapping_update(p.mapping, s_R, st.mapping)
    return effect_step(p.effect, s_E, dt, st.effect)


def air_speed_at(s, distance, angle, cone_angle, reach):
    """Air speed (m/s) `distance` m along the outlet axis, `angle` rad off it."""
    if distance < 0 or distance > reach or math.fabs(angle) > cone_angle or reach <= 0:
        return 0.0
    return s * (1.0 - distance / reach)


def air_drag(speed, area):
    """Drag (N): 0.5 * rho_air * Cd * A * v^2, rho_air = 1.2 kg/m^3, Cd = 1."""
    return 0.5 * 1.2 * 1.0 * area * speed * speed


# ---------------------------------------------------------------------------
# Templates: every function of a table, stepped in table order.

class Templates:
    """The function templates of a loaded table.

    s_R, s_E, output: per function (table order) after the last reset/step;
    output is the effect's state, what a simulator realises.
    """

    def __init__(self, table):
        self.table = table
        self.functions = table["functions"]
        self.params = [function_params(fn) for fn in self.functions]
        self.receptors = [fn["receptor"]["joint"] for fn in self.functions]
        self.states = [FunctionState() for _ in self.functions]
        count = len(self.functions)
        self.s_R = [0.0] * count
        self.s_E = [0.0] * count
        self.output = [0.0] * count

    def _receptor_position(self, positions, i):
        try:
            return float(positions[self.receptors[i]])
        except KeyError:
            raise EfcError("no position for joint '%s', the receptor of function '%s'"
                           % (self.receptors[i], self.functions[i]["name"])) from None

    def _read_back(self, i):
        state = self.states[i]
        self.s_E[i] = state.mapping.s_E
        self.output[i] = state.effect.output

    def reset(self, positions):
        """Starts every function from positions ({joint name: float})."""
        for i, params in enumerate(self.params):
            self.s_R[i] = self._receptor_position(positions, i)
            function_init(params, self.s_R[i], self.states[i])
            self._read_back(i)

    def step_function(self, i, s_R, dt):
        """Steps function i alone with receptor state s_R; returns droplets to emit."""
        self.s_R[i] = float(s_R)
        emit = function_step(self.params[i], self.s_R[i], dt, self.states[i])
        self._read_back(i)
        return emit

    def step(self, positions, dt):
        """One control step of every function; returns droplets to emit per function."""
        return [self.step_function(i, self._receptor_position(positions, i), dt)
                for i in range(len(self.params))]


# ---------------------------------------------------------------------------
# Profiles (runtime/efc_profile.{h,cc}, shared/spec/cli.md).

HOLD_APPROACH = 0.1  # seconds over which hold:V moves from the initial position to V

# What strtod accepts (C locale), less inf and nan, which are never finite.
_DECIMAL = re.compile(r"[ \t\n\v\f\r]*[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?")
_HEX = re.compile(r"[ \t\n\v\f\r]*([+-]?)0[xX]([0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)"
                  r"([pP][+-]?[0-9]+)?")
_SMALLEST_NORMAL = 2.2250738585072014e-308


def _exact_hex(match):
    sign, digits, exponent = match.group(1), match.group(2), match.group(3)
    whole, _, fraction = digits.partition(".")
    mantissa = int((whole + fraction) or "0", 16)
    power = (int(exponent[1:]) if exponent else 0) - 4 * len(fraction)
    value = fractions.Fraction(mantissa) * fractions.Fraction(2) ** power
    return -value if sign == "-" else value


def parse_double(text):
    """The C++ parse_double: a whole string strtod reads, finite, without ERANGE; else None."""
    decimal_match = _DECIMAL.fullmatch(text)
    hex_match = None if decimal_match else _HEX.fullmatch(text)
    if decimal_match is None and hex_match is None:
        return None
    try:
        value = float(text) if decimal_match else float.fromhex(text.strip(" \t\n\v\f\r"))
    except (ValueError, OverflowError):
        return None
    if not math.isfinite(value):
        return None
    # glibc sets ERANGE when a non-zero number underflows to zero or to an
    # inexact subnormal.
    if value == 0:
        digits = (decimal_match or hex_match).group(1 if decimal_match else 2)
        return value if digits.strip("0.") == "" else None
    if math.fabs(value) < _SMALLEST_NORMAL:
        if hex_match:
            exact = _exact_hex(hex_match)
        else:
            exact = fractions.Fraction(decimal.Decimal(text.strip(" \t\n\v\f\r")))
        if exact != fractions.Fraction(value):
            return None
    return value


class Profile:
    """A parsed --profile: kind is ramp, sweep, press, hold or csv."""

    def __init__(self, kind, text):
        self.kind = kind
        self.text = text
        self.presses = 1          # press:N
        self.hold_at = "value"    # hold: value, lo or hi
        self.hold_value = 0.0     # hold:V
        self.csv_path = ""        # csv:FILE
        self.csv_t = []           # strictly increasing
        self.csv_parts = {}       # column -> positions

    def __repr__(self):
        return "Profile(%r)" % self.text


def _trim(s):
    return s.strip(" \t\r")


def _split_cells(line):
    # str.split keeps a trailing empty cell, as the C++ split does explicitly.
    return [_trim(cell) for cell in line.split(",")]


def _read_lines(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        raise EfcError("cannot read profile file '%s'" % path, io_error=True) from None
    lines = data.decode("utf-8", "surrogateescape").split("\n")
    if lines[-1] == "":
        lines.pop()  # std::getline yields no line after a final newline
    return lines


def _read_csv(profile):
    header = []
    lines = _read_lines(profile.csv_path)
    for n, text in enumerate(lines, 1):
        if _trim(text) == "":
            continue
        cells = _split_cells(text)
        if not header:
            header = cells
            if header[0] != "t" or len(header) < 2:
                raise EfcError("profile CSV must start with a header 't,<part>[,<part>...]'", line=n)
            for name in header[1:]:
                profile.csv_parts[name] = []
            if len(profile.csv_parts) != len(header) - 1:
                raise EfcError("profile CSV names a column twice", line=n)
            continue
        if len(cells) != len(header):
            raise EfcError("expected %d values, found %d" % (len(header), len(cells)), line=n)
        t = parse_double(cells[0])
        if t is None:
            raise EfcError("time '%s' is not a finite number" % cells[0], line=n)
        if profile.csv_t and t <= profile.csv_t[-1]:
            raise EfcError("times must increase strictly", line=n)
        profile.csv_t.append(t)
        for name, cell in zip(header[1:], cells[1:]):
            v = parse_double(cell)
            if v is None:
                raise EfcError("value '%s' of column '%s' is not a finite number" % (cell, name),
                               line=n)
            profile.csv_parts[name].append(v)
    if not profile.csv_t:
        raise EfcError("profile CSV has no data rows" if header else "profile CSV is empty",
                       line=len(lines))


def parse_profile(text):
    """Parses a --profile argument (csv:FILE also reads FILE); raises EfcError.

    The error's line is set (1-based) for CSV content errors, io_error when the
    file cannot be read; neither for a bad profile argument.
    """
    colon = text.find(":")
    head = text if colon < 0 else text[:colon]
    arg = "" if colon < 0 else text[colon + 1:]
    if text == "ramp":
        return Profile("ramp", text)
    if text == "sweep":
        return Profile("sweep", text)
    if head == "press" and colon >= 0:
        profile = Profile("press", text)
        n = parse_double(arg)
        if n is None or n < 1 or n != math.floor(n) or n > 1e6:
            raise EfcError("press:N needs a whole number of presses >= 1, got '%s'" % arg)
        profile.presses = int(n)
        return profile
    if head == "hold" and colon >= 0:
        profile = Profile("hold", text)
        if arg in ("lo", "hi"):
            profile.hold_at = arg
        else:
            value = parse_double(arg)
            if value is None:
                raise EfcError("hold:V needs a finite number, 'lo' or 'hi', got '%s'" % arg)
            profile.hold_value = value
        return profile
    if head == "csv" and colon >= 0 and arg:
        profile = Profile("csv", text)
        profile.csv_path = arg
        _read_csv(profile)
        return profile
    raise EfcError("unknown profile '%s' (expected ramp, sweep, press:N, hold:V, csv:FILE)" % text)


def _interpolate(ts, vs, t):
    if t <= ts[0]:
        return vs[0]
    if t >= ts[-1]:
        return vs[-1]
    i = bisect.bisect_right(ts, t)  # std::upper_bound
    u = (t - ts[i - 1]) / (ts[i] - ts[i - 1])
    return vs[i - 1] + u * (vs[i] - vs[i - 1])


def _press_level(profile, u):
    """0 = lo, 1 = hi. Each cycle rests at lo, rises, dwells at hi, returns, rests:
    the rests let a sprung receptor settle, so every press is a clean edge."""
    cycle = u * profile.presses
    c = cycle - math.floor(cycle)
    if c < 0.2:
        a = 0.0
    elif c < 0.4:
        a = (c - 0.2) / 0.2
    elif c < 0.6:
        a = 1.0
    elif c < 0.8:
        a = 1 - (c - 0.6) / 0.2
    else:
        a = 0.0
    if u >= 1.0:
        a = 0.0
    return a


def profile_target(profile, part, lo, hi, q0, t, duration):
    """Target position of a receptor with range [lo, hi] that started at q0, at time t."""
    if duration > 0:
        ratio = t / duration
        u = 0.0 if ratio < 0.0 else (1.0 if 1.0 < ratio else ratio)  # std::clamp
    else:
        u = 1.0
    kind = profile.kind
    if kind == "ramp":
        return lo + (hi - lo) * u
    if kind == "sweep":
        return lo + (hi - lo) * 2 * u if u < 0.5 else hi - (hi - lo) * (2 * u - 1)
    if kind == "press":
        return lo + (hi - lo) * _press_level(profile, u)
    if kind == "hold":
        v = lo if profile.hold_at == "lo" else (hi if profile.hold_at == "hi" else profile.hold_value)
        if t >= HOLD_APPROACH:
            return v
        return q0 + (v - q0) * (t / HOLD_APPROACH)
    if kind == "csv":
        values = profile.csv_parts.get(part)
        return q0 if values is None else _interpolate(profile.csv_t, values, t)
    return q0


def profile_joints(table):
    """The joints a profile drives (drive_by == "profile"), in table order."""
    return [j for j in table["joints"] if j["drive_by"] == "profile"]


# ---------------------------------------------------------------------------
# The log, as efc play writes it.

def format_value(v):
    """printf's "%.9g" (Python's % formatting gives the same digits; only a NaN's
    sign, which glibc prints, needs help)."""
    if v != v:
        return "-nan" if math.copysign(1.0, v) < 0 else "nan"
    return "%.9g" % v


def _write_atomically(path, text):
    temp = path + ".tmp"
    try:
        with open(temp, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
        os.replace(temp, path)
    except OSError as e:
        try:
            os.remove(temp)
        except OSError:
            pass
        raise EfcError("cannot write '%s': %s" % (path, e.strerror or e), io_error=True) from None


class CsvLog:
    """Columns t, then F.s_R, F.s_E, F.measured per function F (table order).

    CsvLog(table) or CsvLog(table, templates) or CsvLog(templates): add(t, measured)
    takes s_R and s_E from the templates unless they are passed.
    """

    def __init__(self, table, templates=None):
        if isinstance(table, Templates):
            templates, table = table, table.table
        self.templates = templates
        self.columns = ["t"]
        for fn in table["functions"]:
            self.columns += [fn["name"] + ".s_R", fn["name"] + ".s_E", fn["name"] + ".measured"]
        self.rows = []

    def add(self, t, measured, s_R=None, s_E=None):
        if s_R is None or s_E is None:
            if self.templates is None:
                raise EfcError("CsvLog.add needs s_R and s_E, or a CsvLog made with the Templates")
            s_R = self.templates.s_R if s_R is None else s_R
            s_E = self.templates.s_E if s_E is None else s_E
        row = [float(t)]
        for i in range(len(measured)):
            row += [float(s_R[i]), float(s_E[i]), float(measured[i])]
        self.rows.append(row)

    def text(self):
        lines = [",".join(self.columns)]
        lines += [",".join(format_value(v) for v in row) for row in self.rows]
        return "\n".join(lines) + "\n"

    def write(self, path):
        """Writes the CSV through a temporary file; raises EfcError (io_error)."""
        _write_atomically(path, self.text())


# ---------------------------------------------------------------------------
# Realisation helpers, as the MuJoCo binding (runtime/mujoco/efc_mujoco.cc).

HOT_RGB = (1.0, 0.22, 0.04)  # colour of a fully glowing part (red-hot)


def glow_fraction(fn, temperature):
    """0..1: how far a temperature effect's part glows, 1 at fn["glow_max"]."""
    e_lo = fn["effect"]["e_lo"]
    glow_max = fn.get("glow_max")
    full = glow_max if glow_max is not None and glow_max > e_lo else e_lo + 1
    f = _ieee_divide(temperature - e_lo, full - e_lo)  # e_lo + 1 == e_lo for huge e_lo
    return 0.0 if f < 0 else (1.0 if f > 1 else f)


class FlowMeter:
    """Flow (L/min) from the droplets a simulator actually spawned in the last `window` s.

    Half a step of slack keeps a time's rounding from counting one step too many;
    the step is dt when given, else the spacing of the last two add() times.
    """

    def __init__(self, window=0.5, dt=None):
        self.window = window
        self.dt = dt
        self._spawns = collections.deque()  # (t, n)
        self._count = 0
        self._last_t = None
        self._step = 0.0

    def add(self, t, n):
        if self._last_t is not None and t > self._last_t:
            self._step = t - self._last_t
        self._last_t = t
        if n > 0:
            self._spawns.append((t, n))
            self._count += n

    def flow(self, t, droplet_volume_l):
        step = self.dt if self.dt is not None else self._step
        edge = t - self.window + 0.5 * step
        while self._spawns and self._spawns[0][0] <= edge:
            self._count -= self._spawns.popleft()[1]
        return self._count * droplet_volume_l / self.window * 60.0


def _normalized(v):
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return [v[0] / n, v[1] / n, v[2] / n] if n > 0 else [v[0], v[1], v[2]]


def airflow_force(fn, output, outlet, axis, point, area):
    """Force (N, 3-vector along the outlet axis) of an airflow effect with outlet
    speed `output` on a body of cross-section `area` at `point` (world frame)."""
    if output == 0:
        return (0.0, 0.0, 0.0)
    a = _normalized(axis)
    v = [point[k] - outlet[k] for k in range(3)]
    along = v[0] * a[0] + v[1] * a[1] + v[2] * a[2]
    vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
    rest = vv - along * along
    off = math.sqrt(rest if 0.0 < rest else 0.0)
    angle = math.atan2(off, along)
    speed = air_speed_at(output, along, angle, fn["cone_angle"], fn["reach"])
    if speed == 0:
        return (0.0, 0.0, 0.0)
    f = air_drag(speed, area)
    return (f * a[0], f * a[1], f * a[2])


# ---------------------------------------------------------------------------
# Loading <name>_functions.json (format efc-functions, version 1).

def _pointer(parent, key):
    token = str(key).replace("~", "~0").replace("/", "~1")
    return parent + "/" + token


def _kind_of(value):
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, list):
        return "an array"
    return "an object"


class _Checker:
    """Type-checks a parsed table; errors name the file and the JSON pointer."""

    def __init__(self, path):
        self.path = path

    def fail(self, pointer, message):
        raise EfcError("%s: %s: %s" % (self.path, pointer or "/", message))

    def expect(self, value, pointer, wanted):
        self.fail(pointer, "expected %s, found %s" % (wanted, _kind_of(value)))

    def object(self, value, pointer):
        if not isinstance(value, dict):
            self.expect(value, pointer, "an object")
        return value

    def array(self, value, pointer):
        if not isinstance(value, list):
            self.expect(value, pointer, "an array")
        return value

    def get(self, obj, pointer, key):
        if key not in obj:
            self.fail(_pointer(pointer, key), "missing required field '%s'" % key)
        return obj[key]

    def string(self, obj, pointer, key, nullable=False):
        value = self.get(obj, pointer, key)
        if not (isinstance(value, str) or (nullable and value is None)):
            self.expect(value, _pointer(pointer, key), "a string or null" if nullable else "a string")
        return value

    def number_value(self, value, pointer):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.expect(value, pointer, "a number")
        try:
            number = float(value)
        except OverflowError:  # an integer beyond any double
            number = math.inf
        if not math.isfinite(number):
            self.fail(pointer, "expected a finite number")
        return number

    def number(self, obj, pointer, key, nullable=False):
        """Checks obj[key] and stores it as a float (or None when nullable)."""
        value = self.get(obj, pointer, key)
        if nullable and value is None:
            return None
        if nullable and (isinstance(value, bool) or not isinstance(value, (int, float))):
            self.expect(value, _pointer(pointer, key), "a number or null")
        obj[key] = self.number_value(value, _pointer(pointer, key))
        return obj[key]

    def vector(self, obj, pointer, key, size=3, nullable=False):
        value = self.get(obj, pointer, key)
        here = _pointer(pointer, key)
        if nullable and value is None:
            return None
        if not isinstance(value, list) or len(value) != size:
            self.expect(value, here, "an array of %d numbers%s" % (size, " or null" if nullable else ""))
        obj[key] = [self.number_value(v, _pointer(here, i)) for i, v in enumerate(value)]
        return obj[key]

    def word(self, obj, pointer, key, words, nullable=False):
        value = self.get(obj, pointer, key)
        if nullable and value is None:
            return None
        if not isinstance(value, str) or value not in words:
            allowed = ", ".join(sorted(words)) + (" or null" if nullable else "")
            self.fail(_pointer(pointer, key), "expected one of %s, found %s"
                      % (allowed, json.dumps(value) if isinstance(value, str) else _kind_of(value)))
        return value

    def boolean(self, obj, pointer, key):
        value = self.get(obj, pointer, key)
        if not isinstance(value, bool):
            self.expect(value, _pointer(pointer, key), "a boolean")
        return value

    def integer(self, obj, pointer, key, nullable=False):
        value = self.get(obj, pointer, key)
        if nullable and value is None:
            return None
        if isinstance(value, bool) or not isinstance(value, int):
            self.expect(value, _pointer(pointer, key), "an integer" + (" or null" if nullable else ""))
        return value

    def sub_object(self, obj, pointer, key, nullable=False):
        value = self.get(obj, pointer, key)
        if nullable and value is None:
            return None
        if not isinstance(value, dict):
            self.expect(value, _pointer(pointer, key), "an object or null" if nullable else "an object")
        return value

    def numbers(self, obj, pointer, key, fields, nullable=False):
        """An object of number fields (a drive, a spring)."""
        value = self.sub_object(obj, pointer, key, nullable)
        if value is not None:
            for name in fields:
                self.number(value, _pointer(pointer, key), name)
        return value


def _check_joint(c, joint, pointer):
    c.object(joint, pointer)
    for key in ("part", "joint", "link", "parent_link"):
        c.string(joint, pointer, key)
    c.word(joint, pointer, "type", {"revolute", "continuous", "prismatic"})
    for key in ("lo", "hi", "initial", "damping", "friction"):
        c.number(joint, pointer, key)
    c.vector(joint, pointer, "axis")
    c.vector(joint, pointer, "origin")
    c.word(joint, pointer, "drive_by", {"profile", "function"}, nullable=True)
    c.numbers(joint, pointer, "drive", ("kp", "kv"), nullable=True)
    c.numbers(joint, pointer, "spring", ("stiffness", "rest"), nullable=True)


def _check_site(c, fn, pointer, required):
    site = c.sub_object(fn, pointer, "site", nullable=not required)
    if site is None:
        return
    here = _pointer(pointer, "site")
    c.string(site, here, "link")
    c.string(site, here, "parent_link")
    for key in ("xyz", "rpy", "point"):
        c.vector(site, here, key)


def _check_function(c, fn, pointer, joint_names):
    c.object(fn, pointer)
    c.string(fn, pointer, "name")
    for end in ("receptor", "effector"):
        ref = c.sub_object(fn, pointer, end)
        here = _pointer(pointer, end)
        c.string(ref, here, "part")
        c.string(ref, here, "link")
        c.string(ref, here, "joint", nullable=end == "effector")
    mapping = c.sub_object(fn, pointer, "mapping")
    here = _pointer(pointer, "mapping")
    c.word(mapping, here, "kind", MAPPING_KINDS)
    for key in MAPPING_FIELDS:
        c.number(mapping, here, key)
    c.boolean(mapping, here, "latching")
    effect = c.sub_object(fn, pointer, "effect")
    here = _pointer(pointer, "effect")
    kind = c.word(effect, here, "kind", EFFECT_KINDS)
    for key in EFFECT_FIELDS:
        c.number(effect, here, key)
    c.string(fn, pointer, "unit")
    _check_realisation(c, fn, pointer, kind)
    receptor = fn["receptor"]["joint"]
    if receptor not in joint_names:
        c.fail(_pointer(_pointer(pointer, "receptor"), "joint"),
               "receptor joint '%s' is not one of the table's joints" % receptor)
    effector = fn["effector"]["joint"]
    if kind == "geometry" and effector not in joint_names:
        c.fail(_pointer(_pointer(pointer, "effector"), "joint"),
               "a geometry effect needs an effector joint of the table, found %s"
               % (json.dumps(effector) if effector is not None else "null"))


def _check_realisation(c, fn, pointer, kind):
    """The fields a simulator needs: required where they apply, else null or typed."""
    _check_site(c, fn, pointer, required=kind != "geometry")
    c.vector(fn, pointer, "direction", nullable=kind not in ("fluid", "airflow"))
    c.vector(fn, pointer, "color", nullable=kind != "illumination")
    for key in ("speed", "droplet_radius"):
        c.number(fn, pointer, key, nullable=kind != "fluid")
    c.integer(fn, pointer, "droplet_pool", nullable=kind != "fluid")
    for key in ("cone_angle", "reach"):
        c.number(fn, pointer, key, nullable=kind != "airflow")
    c.number(fn, pointer, "glow_max", nullable=kind != "temperature")
    c.numbers(fn, pointer, "drive", ("kp", "kv"), nullable=kind != "geometry")


def _check_table(c, doc):
    c.object(doc, "")
    form = c.get(doc, "", "format")
    if form != "efc-functions":
        c.fail("/format", "expected \"efc-functions\", found %s"
               % (json.dumps(form) if isinstance(form, str) else _kind_of(form)))
    version = c.get(doc, "", "version")
    if isinstance(version, bool) or not isinstance(version, int) or version != 1:
        c.fail("/version", "expected version 1, found %s"
               % (version if isinstance(version, int) and not isinstance(version, bool)
                  else _kind_of(version)))
    for key in ("object", "urdf", "root_link"):
        c.string(doc, "", key)
    if "description" in doc:
        c.string(doc, "", "description", nullable=True)
    c.number(doc, "", "timestep")
    joints = c.array(c.get(doc, "", "joints"), "/joints")
    names = set()
    for i, joint in enumerate(joints):
        _check_joint(c, joint, _pointer("/joints", i))
        if joint["joint"] in names:
            c.fail(_pointer(_pointer("/joints", i), "joint"), "joint '%s' is listed twice" % joint["joint"])
        names.add(joint["joint"])
    functions = c.array(c.get(doc, "", "functions"), "/functions")
    for i, fn in enumerate(functions):
        _check_function(c, fn, _pointer("/functions", i), names)
    return doc


def load_functions(path):
    """Reads and checks <name>_functions.json; returns the table (the JSON object,
    numbers as floats). Raises EfcError naming the file and the bad field's JSON
    pointer (io_error set when the file cannot be read)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise EfcError("%s: cannot read: %s" % (path, e.strerror or e), io_error=True) from None
    try:
        doc = json.loads(data.decode("utf-8"))
    except UnicodeDecodeError as e:
        raise EfcError("%s: not UTF-8 text (byte %d)" % (path, e.start)) from None
    except json.JSONDecodeError as e:
        raise EfcError("%s:%d:%d: invalid JSON: %s" % (path, e.lineno, e.colno, e.msg)) from None
    except (ValueError, RecursionError) as e:
        raise EfcError("%s: invalid JSON: %s" % (path, e)) from None
    return _check_table(_Checker(path), doc)


# ---------------------------------------------------------------------------
# Replay with no simulator: the same as runtime/efc_replay.h.

def lround(x):
    """C's lround: halves away from zero (Python's round() goes to even)."""
    whole = math.floor(math.fabs(x))
    n = int(whole) + (1 if math.fabs(x) - whole >= 0.5 else 0)
    return -n if x < 0 else n


def check_timing(duration, dt):
    """The C++ CLI's limits on --duration and --dt; raises EfcError."""
    if not duration > 0 or duration > 1e5:
        raise EfcError("--duration must be a positive number of seconds (at most 1e5)")
    if not dt > 0 or dt > 0.1 or dt > duration or duration / dt > 5e7:
        raise EfcError("--dt must be in (0, 0.1] seconds, not exceed --duration, and give "
                       "at most 50 million steps")


def replay(table, profile, duration, dt):
    """Runs the templates over the profile with ideal joints; returns the CsvLog.

    Every joint starts at its initial position; profile joints follow
    profile_target (q0 = initial) at every step including t = 0; a geometry
    effect puts its effector joint at its output (an ideal servo), so a later
    function in a chain sees it in the same step. measured = the effect's output.
    """
    check_timing(duration, dt)
    joints = table["joints"]
    driven = profile_joints(table)
    positions = {j["joint"]: j["initial"] for j in joints}

    def drive(t):
        for j in driven:
            positions[j["joint"]] = profile_target(profile, j["part"], j["lo"], j["hi"],
                                                   j["initial"], t, duration)

    tpl = Templates(table)
    log = CsvLog(table, tpl)
    drive(0.0)
    tpl.reset(positions)
    geometry_effectors = [fn["effector"]["joint"] if fn["effect"]["kind"] == "geometry" else None
                          for fn in tpl.functions]
    steps = lround(duration / dt)
    for k in range(steps + 1):
        t = k * dt
        drive(t)
        for i, effector in enumerate(geometry_effectors):
            tpl.step_function(i, positions[tpl.receptors[i]], dt)
            if effector is not None:
                positions[effector] = tpl.output[i]
        log.add(t, tpl.output)
    return log


def profile_warnings(table, profile, limited=True):
    """What efc play warns about a profile: a CSV without a receptor's column, a hold
    value outside a receptor's range (`limited`: a simulator's joint limit stops it;
    the replay follows it)."""
    warnings = []
    for j in profile_joints(table):
        if profile.kind == "csv" and j["part"] not in profile.csv_parts:
            warnings.append("profile CSV has no column for receptor '%s'; it holds its initial "
                            "position" % j["part"])
        if profile.kind == "hold" and profile.hold_at == "value" and \
                not j["lo"] <= profile.hold_value <= j["hi"]:
            warnings.append("hold value %s is outside the range [%s, %s] of receptor '%s'; %s"
                            % (format_value(profile.hold_value), format_value(j["lo"]),
                               format_value(j["hi"]), j["part"],
                               "its joint limit stops it" if limited else
                               "the replay follows it (a simulator's joint limit would stop it)"))
    return warnings


# ---------------------------------------------------------------------------
# What every simulator script's command line shares (backends/python/README.md).

DEFAULT_STEPS = 1000


def add_run_arguments(parser, headless_help="run without a window"):
    """--steps, --dt, --profile, --duration, --csv and --headless."""
    parser.add_argument("--steps", type=int, default=None,
                        help="simulation steps (default: --duration / dt, else %d)" % DEFAULT_STEPS)
    parser.add_argument("--dt", type=float, default=None,
                        help="timestep in seconds (default: the functions file's timestep)")
    parser.add_argument("--profile", default=None,
                        help="drive the receptors no function moves, as efc play does: ramp, sweep, "
                             "press:N, hold:V|lo|hi, csv:FILE (without it they are left to you or "
                             "your agent)")
    parser.add_argument("--duration", type=float, default=None,
                        help="seconds the profile spans (default: steps x dt)")
    parser.add_argument("--csv", default=None,
                        help="write t, then F.s_R, F.s_E, F.measured per function F (as efc play)")
    parser.add_argument("--headless", action="store_true", help=headless_help)


class RunSettings:
    """The shared options resolved: steps, dt, duration, profile (None without
    --profile), csv (None or a path whose folder exists) and the profile's warnings."""

    def __init__(self, steps, dt, duration, profile, csv, warnings):
        self.steps = steps
        self.dt = dt
        self.duration = duration
        self.profile = profile
        self.csv = csv
        self.warnings = warnings


def run_settings(args, table):
    """Resolves add_run_arguments' options against the functions table: dt defaults
    to the table's timestep; --steps alone gives duration = steps dt, --duration alone
    steps = round(duration / dt), neither DEFAULT_STEPS steps; the limits of efc play
    (check_timing); --profile parsed. Raises EfcError whose `status` is the exit status:
    2 for usage (and an unreadable file), 1 for a bad line of a csv: profile (its
    message then starts FILE:LINE:)."""
    def usage(message):
        e = EfcError(message)
        e.status = 2
        return e

    dt = float(args.dt) if args.dt is not None else float(table["timestep"])
    if not 0 < dt <= 0.1:
        raise usage("--dt must be in (0, 0.1] seconds")
    steps, duration = args.steps, args.duration
    if steps is not None and steps < 1:
        raise usage("--steps must be at least 1")
    if steps is None and duration is None:
        steps = DEFAULT_STEPS
    if steps is None:
        check_timing_or_usage = duration > 0 and duration <= 1e5
        if not check_timing_or_usage:
            raise usage("--duration must be a positive number of seconds (at most 1e5)")
        steps = max(1, lround(duration / dt))
    if duration is None:
        duration = steps * dt
    try:
        check_timing(duration, dt)
    except EfcError as e:
        raise usage(e.message) from None
    if args.csv is not None:
        folder = os.path.dirname(os.path.abspath(args.csv))
        if not os.path.isdir(folder):
            raise usage("cannot write '%s': no folder '%s'" % (args.csv, folder))
    profile, warnings = None, []
    if args.profile is not None:
        try:
            profile = parse_profile(args.profile)
        except EfcError as e:
            if e.line > 0:  # a bad line in the profile's CSV file
                bad = EfcError("%s:%d: %s" % (args.profile[4:], e.line, e.message), line=e.line)
                bad.status = 1
                raise bad from None
            raise usage(e.message) from None
        if not profile_joints(table):
            warnings.append("--profile: this object has no receptor for a profile to drive")
        warnings += profile_warnings(table, profile)
    return RunSettings(steps, dt, duration, profile, args.csv, warnings)


def _say(message):
    print("%s: %s" % (PROG, message), file=sys.stderr)


def _parse_args(argv):
    parser = argparse.ArgumentParser(
        prog=PROG, description="Replay efc function templates with no simulator and write "
                               "the harness's CSV (measured = the effect's state).")
    parser.add_argument("functions", metavar="FUNCTIONS.json", help="<name>_functions.json")
    parser.add_argument("--profile", required=True, help="ramp, sweep, press:N, hold:V (lo/hi), csv:FILE")
    parser.add_argument("--duration", type=float, required=True, help="seconds")
    parser.add_argument("--dt", type=float, default=0.002, help="timestep in seconds (default 0.002)")
    parser.add_argument("--csv", required=True, help="write the log: t, F.s_R, F.s_E, F.measured")
    return parser.parse_args(argv)


def main(argv=None):
    """The command line (argv without the program name); returns the exit status."""
    try:
        args = _parse_args(argv)
    except SystemExit as e:  # argparse has printed usage or help
        return e.code if isinstance(e.code, int) else 2
    try:
        check_timing(args.duration, args.dt)
    except EfcError as e:
        _say(e.message)
        return 2
    try:
        profile = parse_profile(args.profile)
    except EfcError as e:
        if e.line > 0:
            _say("%s:%d: %s" % (args.profile[4:], e.line, e.message))
            return 1
        _say(e.message)
        return 2
    try:
        table = load_functions(args.functions)
        for warning in profile_warnings(table, profile, limited=False):
            _say("warning: " + warning)
        replay(table, profile, args.duration, args.dt).write(args.csv)
    except EfcError as e:
        _say(e.message)
        return 2 if e.io_error else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
