# efc glue for Isaac Lab 2.3 (isaac-sim/IsaacLab v2.3.0, Isaac Sim 5.1).
#
# The fixed part of every generated <name>_isaaclab.py: the C++ backend writes a
# docstring header, then this file, then a footer calling
# main(sys.argv[1:], object_name=..., urdf_file=..., functions_file=...).
# Everything a spec names reaches this code only through <name>_functions.json,
# read at run time and used as strings / dict keys.
#
# Isaac Lab is imported inside main(), after the command line is parsed, so the
# module imports, byte-compiles and answers --help without the simulator; the
# AppLauncher must start Isaac Sim before isaaclab.sim / isaaclab.assets load.
#
# API facts used here (file and line in isaac-sim/IsaacLab at v2.3.0) are listed
# in backends/isaaclab/NOTES.md.

import argparse
import math
import os
import re
import struct
import sys
import xml.etree.ElementTree as ET

import efc_templates as efc

ISAACLAB_VERSION = "2.3"

# Prim paths this script creates. None of them contains a name from the spec.
OBJECT_PRIM = "/World/efc_object"
DROPS_PRIM = "/World/efc_drops"
LOOKS_PRIM = "/World/Looks"

# Illumination: a USD SphereLight of this radius (m) under the effector link.
LIGHT_RADIUS = 0.02
# Fluid, as the MuJoCo binding (runtime/mujoco/efc_mujoco.h).
FLOW_WINDOW = 0.5        # s: measured flow counts the droplets spawned this long ago
DROPLET_LIFETIME = 3.0   # s: a droplet older than this is recycled
DROPLET_FALL = 1.0       # m: a droplet this far below the object's lowest point is recycled
PARK_Z = 50.0            # m: unused droplets wait on a grid at this height
WATER_DENSITY = 1000.0   # kg/m^3
# Airflow props: light spheres that float (gravity off) in each outlet cone.
PROP_RADIUS = 0.015      # m
PROP_DENSITY = 30.0      # kg/m^3 (foam): about 0.4 g each
PROP_ESCAPE = 1.5        # a prop farther than this many reaches from its home goes back
DEFAULT_RGB = (0.7, 0.7, 0.7)
DROP_RGB = (0.25, 0.5, 0.95)
PROP_RGB = (0.95, 0.85, 0.2)
RENDER_HZ = 60.0


class UsageError(Exception):
    """A bad command line or input file: message for the user, exit status."""

    def __init__(self, message, status=2):
        super().__init__(message)
        self.message = message
        self.status = status


# ---------------------------------------------------------------------------
# Pure helpers (no simulator): unit-tested in test_efc_isaaclab.py.

def lumens_to_intensity(lumens, radius=LIGHT_RADIUS):
    """USD `inputs:intensity` (nits, normalize off, exposure 0) of a sphere light of
    `radius` m emitting `lumens`: a Lambertian sphere of luminance L emits
    pi * L * 4 pi r^2 lm, so L = lm / (4 pi^2 r^2). An approximation: RTX's
    exposure and tone mapping decide how bright that looks."""
    return lumens / (4.0 * math.pi * math.pi * radius * radius)


def intensity_to_lumens(intensity, radius=LIGHT_RADIUS):
    """Inverse of lumens_to_intensity: what the light prim emits, in lm."""
    return intensity * (4.0 * math.pi * math.pi * radius * radius)


def quat_rotate(q, v):
    """Rotates vector v by the unit quaternion q = (w, x, y, z) (Isaac Lab's order)."""
    w, x, y, z = q
    # t = 2 (q_vec x v); v' = v + w t + q_vec x t
    tx = 2.0 * (y * v[2] - z * v[1])
    ty = 2.0 * (z * v[0] - x * v[2])
    tz = 2.0 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + (y * tz - z * ty),
            v[1] + w * ty + (z * tx - x * tz),
            v[2] + w * tz + (x * ty - y * tx))


def normalized(v):
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return (v[0] / n, v[1] / n, v[2] / n) if n > 0 else (0.0, 0.0, 1.0)


def site_world(link_pos, link_quat, xyz):
    """World position of a point given in a link's frame (link pose: pos, quat wxyz)."""
    r = quat_rotate(link_quat, xyz)
    return (link_pos[0] + r[0], link_pos[1] + r[1], link_pos[2] + r[2])


def combine_drive(servo, spring_k, rest, damping):
    """One PhysX joint drive realising a PD servo, a joint spring and a joint damper.

    servo: (kp, kv) or None. PhysX drives apply stiffness * (target - q) +
    damping * (0 - qdot); a servo kp (q* - q), a spring k (rest - q) and a damper
    -c qdot add up to (kp + k) (target - q) - (kv + c) qdot with
    target = (kp q* + k rest) / (kp + k). Returns (stiffness, damping, blend) where
    blend(q_star) gives the drive target."""
    kp, kv = servo if servo is not None else (0.0, 0.0)
    k = spring_k if spring_k else 0.0
    stiffness = kp + k
    total_damping = kv + (damping if damping else 0.0)

    def blend(q_star):
        if stiffness <= 0.0:
            return rest if k > 0 else q_star
        return (kp * q_star + k * rest) / stiffness

    return stiffness, total_damping, blend


def joint_drive_plan(table, profile_on):
    """Per movable joint (table order): dict with the drive realising its servo
    (geometry effector; profile receptor when --profile is given), spring and
    damping. 'servo' says whether a position target is commanded each step."""
    plan = []
    for j in table["joints"]:
        servo = None
        if j["drive_by"] == "function" or (j["drive_by"] == "profile" and profile_on):
            d = j.get("drive")
            if d is not None:
                servo = (float(d["kp"]), float(d["kv"]))
        spring = j.get("spring")
        k = float(spring["stiffness"]) if spring else 0.0
        rest = float(spring["rest"]) if spring else float(j["initial"])
        stiffness, damping, blend = combine_drive(servo, k, rest, float(j.get("damping") or 0.0))
        plan.append({"joint": j["joint"], "stiffness": stiffness, "damping": damping,
                     "blend": blend, "servo": servo is not None})
    return plan


def start_position(joint, q):
    """A joint's initial position, inside its limits (Isaac Lab rejects a default joint
    position outside them); a continuous joint has none."""
    if joint["type"] == "continuous":
        return float(q)
    lo, hi = float(joint["lo"]), float(joint["hi"])
    return min(max(float(q), min(lo, hi)), max(lo, hi))


def park_position(serial, radius):
    """Where unused droplet `serial` waits (the MuJoCo backend's grid at z = 50 m)."""
    spacing = max(0.2, 5 * radius)
    return ((serial % 20) * spacing, (serial // 20) * spacing, PARK_Z)


def perpendicular(a):
    """A unit vector perpendicular to unit vector a."""
    helper = (1.0, 0.0, 0.0) if abs(a[0]) < 0.9 else (0.0, 1.0, 0.0)
    c = (a[1] * helper[2] - a[2] * helper[1],
         a[2] * helper[0] - a[0] * helper[2],
         a[0] * helper[1] - a[1] * helper[0])
    return normalized(c)


def prop_homes(outlet, axis, reach, cone_angle, count):
    """Home positions of `count` props inside an outlet cone: spread along the axis
    over (0, reach) and around it, well inside the cone."""
    a = normalized(axis)
    u = perpendicular(a)
    w = (a[1] * u[2] - a[2] * u[1], a[2] * u[0] - a[0] * u[2], a[0] * u[1] - a[1] * u[0])
    homes = []
    for k in range(count):
        d = reach * (k + 1) / (count + 1)
        off = 0.4 * d * math.tan(min(cone_angle, 1.2))
        phi = 2.0 * math.pi * k / max(count, 1)
        c, s = math.cos(phi), math.sin(phi)
        homes.append(tuple(outlet[i] + a[i] * d + off * (c * u[i] + s * w[i]) for i in range(3)))
    return homes


def glow_colors(base_rgb, f):
    """(diffuse, emissive) of a part glowing a fraction f: the MuJoCo binding's blend
    of its colour toward red-hot, plus an emission that grows with f."""
    hot = efc.HOT_RGB
    diffuse = tuple(base_rgb[c] * (1.0 - f) + hot[c] * f for c in range(3))
    emissive = tuple(hot[c] * f for c in range(3))
    return diffuse, emissive


def lamp_colors(base_rgb, light_rgb, lumens, top):
    """(diffuse, emissive) of a lamp's effector part at `lumens` of `top`: its colour
    blends toward the light's colour and it emits that colour, fully at `top`."""
    f = 0.0 if top <= 0 else max(0.0, min(1.0, lumens / top))
    diffuse = tuple(base_rgb[c] * (1.0 - f) + light_rgb[c] * f for c in range(3))
    emissive = tuple(light_rgb[c] * f for c in range(3))
    return diffuse, emissive


def camera_view(lo, hi):
    """(eye, target) framing the box [lo, hi]."""
    c = tuple(0.5 * (lo[i] + hi[i]) for i in range(3))
    r = 0.5 * math.sqrt(sum((hi[i] - lo[i]) ** 2 for i in range(3)))
    r = max(r, 0.1)
    return (c[0] + 2.2 * r, c[1] - 2.2 * r, c[2] + 1.6 * r), c


def render_every(dt, hz=RENDER_HZ):
    """Physics steps per rendered frame (about `hz` frames per simulated second)."""
    return max(1, int(round(1.0 / (hz * dt))))


# --- URDF: link colours and the object's bounds (for the camera, the glow's base
# colour and the droplets' recycling floor). Standard library only.

def _floats(text, n, default):
    if text is None:
        return default
    parts = text.split()
    if len(parts) != n:
        return default
    try:
        return tuple(float(p) for p in parts)
    except ValueError:
        return default


def rpy_matrix(rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


def _apply(m, v):
    return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))


def _matmul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def stl_bounds(path):
    """(lo, hi) of an STL file's vertices (binary or ASCII), or None."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return None
    points = []
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if 84 + 50 * count == len(data):
            for t in range(count):
                base = 84 + 50 * t + 12
                for v in range(3):
                    points.append(struct.unpack_from("<3f", data, base + 12 * v))
    if not points:
        for line in data.decode("ascii", "replace").splitlines():
            words = line.split()
            if len(words) == 4 and words[0] == "vertex":
                try:
                    points.append(tuple(float(w) for w in words[1:]))
                except ValueError:
                    pass
    if not points:
        return None
    lo = tuple(min(p[i] for p in points) for i in range(3))
    hi = tuple(max(p[i] for p in points) for i in range(3))
    return lo, hi


def _geometry_corners(geom, base_dir):
    """Corners of a visual geometry's box in its own frame, or None."""
    box = geom.find("box")
    if box is not None:
        s = _floats(box.get("size"), 3, None)
        if s is None:
            return None
        lo, hi = tuple(-0.5 * x for x in s), tuple(0.5 * x for x in s)
    elif geom.find("sphere") is not None:
        r = float(geom.find("sphere").get("radius", "0"))
        lo, hi = (-r, -r, -r), (r, r, r)
    elif geom.find("cylinder") is not None:
        c = geom.find("cylinder")
        r, length = float(c.get("radius", "0")), float(c.get("length", "0"))
        lo, hi = (-r, -r, -0.5 * length), (r, r, 0.5 * length)
    elif geom.find("mesh") is not None:
        m = geom.find("mesh")
        bounds = stl_bounds(os.path.join(base_dir, m.get("filename", "")))
        if bounds is None:
            return None
        scale = _floats(m.get("scale"), 3, (1.0, 1.0, 1.0))
        a = tuple(bounds[0][i] * scale[i] for i in range(3))
        b = tuple(bounds[1][i] * scale[i] for i in range(3))
        lo, hi = tuple(min(a[i], b[i]) for i in range(3)), tuple(max(a[i], b[i]) for i in range(3))
    else:
        return None
    return [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]


def urdf_summary(path):
    """Reads a URDF: {"colors": {link: (r, g, b)}, "lo": xyz, "hi": xyz} with the
    bounds of every visual at joint position 0 (None when there is none).
    Raises UsageError when the file cannot be read or parsed."""
    try:
        root = ET.parse(path).getroot()
    except OSError as e:
        raise UsageError("cannot read '%s': %s" % (path, e.strerror or e)) from None
    except ET.ParseError as e:
        raise UsageError("'%s' is not valid XML: %s" % (path, e), status=1) from None
    base_dir = os.path.dirname(os.path.abspath(path))
    named = {}
    for m in root.findall("material"):
        c = m.find("color")
        if m.get("name") and c is not None:
            named[m.get("name")] = _floats(c.get("rgba"), 4, None)
    parent_of = {}
    for j in root.findall("joint"):
        parent, child = j.find("parent"), j.find("child")
        if parent is None or child is None:
            continue
        o = j.find("origin")
        xyz = _floats(o.get("xyz") if o is not None else None, 3, (0.0, 0.0, 0.0))
        rpy = _floats(o.get("rpy") if o is not None else None, 3, (0.0, 0.0, 0.0))
        parent_of[child.get("link")] = (parent.get("link"), xyz, rpy_matrix(rpy))
    poses = {}

    def pose(link, depth=0):
        if link in poses:
            return poses[link]
        if link not in parent_of or depth > 1000:
            poses[link] = ((0.0, 0.0, 0.0), rpy_matrix((0.0, 0.0, 0.0)))
            return poses[link]
        parent, xyz, rot = parent_of[link]
        p_pos, p_rot = pose(parent, depth + 1)
        off = _apply(p_rot, xyz)
        poses[link] = (tuple(p_pos[i] + off[i] for i in range(3)), _matmul(p_rot, rot))
        return poses[link]

    colors, points, inertials = {}, [], {}
    for link in root.findall("link"):
        name = link.get("name")
        l_pos, l_rot = pose(name)
        inertial = link.find("inertial")
        if inertial is not None and inertial.find("mass") is not None:
            try:
                mass = float(inertial.find("mass").get("value", "0"))
            except ValueError:
                mass = 0.0
            o = inertial.find("origin")
            c_xyz = _floats(o.get("xyz") if o is not None else None, 3, (0.0, 0.0, 0.0))
            c_rot = _matmul(l_rot, rpy_matrix(_floats(o.get("rpy") if o is not None else None, 3,
                                                      (0.0, 0.0, 0.0))))
            el = inertial.find("inertia")
            vals = {}
            for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
                try:
                    vals[key] = float(el.get(key, "0")) if el is not None else 0.0
                except ValueError:
                    vals[key] = 0.0
            tensor = ((vals["ixx"], vals["ixy"], vals["ixz"]),
                      (vals["ixy"], vals["iyy"], vals["iyz"]),
                      (vals["ixz"], vals["iyz"], vals["izz"]))
            rt = tuple(tuple(c_rot[j][i] for j in range(3)) for i in range(3))
            com = _apply(l_rot, c_xyz)
            inertials[name] = (mass, tuple(l_pos[i] + com[i] for i in range(3)),
                               _matmul(_matmul(c_rot, tensor), rt))
        for visual in link.findall("visual"):
            mat = visual.find("material")
            if mat is not None and name not in colors:
                c = mat.find("color")
                rgba = _floats(c.get("rgba"), 4, None) if c is not None else named.get(mat.get("name"))
                if rgba is not None:
                    colors[name] = tuple(rgba[:3])
            geom = visual.find("geometry")
            if geom is None:
                continue
            corners = _geometry_corners(geom, base_dir)
            if corners is None:
                continue
            o = visual.find("origin")
            v_xyz = _floats(o.get("xyz") if o is not None else None, 3, (0.0, 0.0, 0.0))
            v_rot = rpy_matrix(_floats(o.get("rpy") if o is not None else None, 3, (0.0, 0.0, 0.0)))
            for corner in corners:
                p = _apply(v_rot, corner)
                p = tuple(p[i] + v_xyz[i] for i in range(3))
                q = _apply(l_rot, p)
                points.append(tuple(l_pos[i] + q[i] for i in range(3)))
    if points:
        lo = tuple(min(p[i] for p in points) for i in range(3))
        hi = tuple(max(p[i] for p in points) for i in range(3))
    else:
        lo = hi = None
    children = {}
    for child, (parent, _, _) in parent_of.items():
        children.setdefault(parent, []).append(child)
    return {"colors": colors, "lo": lo, "hi": hi, "inertials": inertials, "children": children}


def joint_inertia(summary, joint):
    """Inertia (kg, or kg m^2) the joint moves when alone: the mass of the links below
    it (prismatic) or their inertia about its axis (revolute, continuous), at q = 0,
    from the URDF's inertials. Ignores the coupling with other joints."""
    inertials, children = summary.get("inertials", {}), summary.get("children", {})
    stack, subtree = [joint["link"]], []
    while stack:
        link = stack.pop()
        if link in subtree:
            continue
        subtree.append(link)
        stack.extend(children.get(link, []))
    a = normalized(joint["axis"])
    o = joint["origin"]
    total = 0.0
    for link in subtree:
        if link not in inertials:
            continue
        mass, com, tensor = inertials[link]
        if joint["type"] == "prismatic":
            total += mass
            continue
        r = (com[0] - o[0], com[1] - o[1], com[2] - o[2])
        cross = (r[1] * a[2] - r[2] * a[1], r[2] * a[0] - r[0] * a[2], r[0] * a[1] - r[1] * a[0])
        ia = _apply(tensor, a)
        total += a[0] * ia[0] + a[1] * ia[1] + a[2] * ia[2] + mass * sum(c * c for c in cross)
    return total


FRICTION_STOP = 0.5  # fraction of a joint's velocity friction may remove per step


def friction_effort(friction, velocity, inertia, dt):
    """Coulomb joint friction as an explicit effort (N or N m): opposes the velocity
    with at most `friction`, and never more than would remove FRICTION_STOP of the
    velocity in one step (so a small joint does not chatter). A stand-in for a
    constraint-based friction: a joint under a load below `friction` creeps at
    load * dt / (FRICTION_STOP * inertia) instead of sticking."""
    if friction <= 0.0 or inertia <= 0.0:
        return 0.0
    stop = FRICTION_STOP * inertia * velocity / dt
    return -max(-friction, min(friction, stop))


def object_bounds(summary, table):
    """(lo, hi) of the object: the URDF's visuals, else the joint origins and sites."""
    if summary.get("lo") is not None:
        return summary["lo"], summary["hi"]
    points = [tuple(j["origin"]) for j in table["joints"]]
    points += [tuple(fn["site"]["point"]) for fn in table["functions"] if fn.get("site")]
    points.append((0.0, 0.0, 0.0))
    lo = tuple(min(p[i] for p in points) - 0.05 for i in range(3))
    hi = tuple(max(p[i] for p in points) + 0.05 for i in range(3))
    return lo, hi


def effect_functions(table, kind):
    """Indices (table order) of the functions whose effect is `kind`."""
    return [i for i, fn in enumerate(table["functions"]) if fn["effect"]["kind"] == kind]


# ---------------------------------------------------------------------------
# Command line.

APP_EPILOG = (
    "Other options of Isaac Lab's AppLauncher (--livestream, --enable_cameras, "
    "--experience, --rendering_mode, --kit_args, ...) are passed on to "
    "isaaclab.app.AppLauncher. Exit status: 0 ok; 1 a bad input file; 2 usage, I/O or "
    "Isaac Lab missing; 3 the simulation failed.")


def build_parser(prog, object_name):
    p = argparse.ArgumentParser(
        prog=prog, epilog=APP_EPILOG, allow_abbrev=False,
        description="Simulate '%s' with its function templates in Isaac Lab %s (Isaac Sim 5.1)."
                    % (object_name, ISAACLAB_VERSION))
    efc.add_run_arguments(p, headless_help="run without a window (AppLauncher's --headless)")
    p.add_argument("--device", default="cuda:0", help="simulation device: cuda:N or cpu (default cuda:0)")
    p.add_argument("--props", type=int, default=3,
                   help="light props floating in each airflow cone to show the air (default 3)")
    p.add_argument("--no-props", action="store_true", help="no airflow props (same as --props 0)")
    return p


def parse_command_line(argv, object_name):
    """(args, rest): our options and the ones left for the AppLauncher.
    Raises SystemExit (argparse: --help, usage errors) or UsageError."""
    prog = "%s_isaaclab.py" % object_name
    parser = build_parser(prog, object_name)
    args, rest = parser.parse_known_args(argv)
    if args.props < 0:
        parser.error("--props must be 0 or more")
    if args.no_props:
        args.props = 0
    return args, rest


# ---------------------------------------------------------------------------
# The simulation.

def say(message):
    print("efc_isaaclab: %s" % message, file=sys.stderr)


def main(argv, object_name, urdf_file, functions_file):
    """The script's command line (argv without the program name) -> exit status."""
    try:
        args, rest = parse_command_line(list(argv), object_name)
    except SystemExit as e:  # argparse printed the help or a usage error
        return e.code if isinstance(e.code, int) else 2
    here = os.path.dirname(os.path.abspath(__file__))
    urdf_path = os.path.join(here, urdf_file)
    functions_path = os.path.join(here, functions_file)
    try:
        table = efc.load_functions(functions_path)
        if not os.path.isfile(urdf_path):
            raise UsageError("cannot read '%s': no such file" % urdf_path)
        summary = urdf_summary(urdf_path)
    except efc.EfcError as e:
        say(e.message)
        return 2 if e.io_error else 1
    except UsageError as e:
        say(e.message)
        return e.status
    try:
        settings = efc.run_settings(args, table)
    except efc.EfcError as e:
        say(e.message)
        return e.status
    for w in settings.warnings:
        say("warning: " + w)
    dt, duration, profile = settings.dt, settings.duration, settings.profile
    args.steps = settings.steps

    try:
        from isaaclab.app import AppLauncher
    except ImportError as e:
        say("Isaac Lab %s is not importable here (%s). Install Isaac Sim 5.1 and Isaac Lab %s "
            "(see README.md) and run this script with Isaac Lab's Python." % (ISAACLAB_VERSION, e, ISAACLAB_VERSION))
        return 2
    app_parser = argparse.ArgumentParser(prog="%s_isaaclab.py" % object_name, allow_abbrev=False)
    AppLauncher.add_app_launcher_args(app_parser)
    app_argv = list(rest) + ["--device", args.device] + (["--headless"] if args.headless else [])
    try:
        app_args = app_parser.parse_args(app_argv)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else 2
    app_launcher: "AppLauncher" = AppLauncher(app_args)
    simulation_app = app_launcher.app
    try:
        return run(simulation_app, args, table, profile, dt, duration, urdf_path, summary)
    except efc.EfcError as e:  # writing the CSV
        say(e.message)
        return 2 if e.io_error else 1
    except UsageError as e:
        say(e.message)
        return e.status
    except (RuntimeError, ValueError) as e:  # Isaac Lab refused the scene or failed in a step
        say("the simulation failed: %s" % e)
        return 3
    finally:
        simulation_app.close()


def run(simulation_app, args, table, profile, dt, duration, urdf_path, summary):
    """Builds the scene, runs args.steps physics steps, writes the CSV. Exit status."""
    import torch

    import isaaclab.sim as sim_utils
    from isaaclab.actuators import ImplicitActuatorCfg
    from isaaclab.assets import (Articulation, ArticulationCfg, RigidObjectCfg, RigidObjectCollection,
                                 RigidObjectCollectionCfg)
    from pxr import Gf, Usd, UsdLux, UsdPhysics

    functions = table["functions"]
    tpl = efc.Templates(table)
    log = efc.CsvLog(table, tpl) if args.csv else None
    frame_every = render_every(dt)

    # -- simulation context (physics dt; rendering every frame_every steps)
    sim_cfg = sim_utils.SimulationCfg(dt=dt, device=args.device, render_interval=frame_every)
    sim: "sim_utils.SimulationContext" = sim_utils.SimulationContext(sim_cfg)
    lo, hi = object_bounds(summary, table)
    eye, target = camera_view(lo, hi)
    sim.set_camera_view(eye=eye, target=target)

    # -- scene light (dim, so the object's own lights show) and a visual-only floor,
    #    as the MuJoCo target's (droplets fall through it and are recycled)
    dome_cfg = sim_utils.DomeLightCfg(intensity=600.0, color=(0.9, 0.9, 0.9))
    dome_cfg.func("/World/efc_dome_light", dome_cfg)
    size = max(1.0, 4.0 * max(hi[i] - lo[i] for i in range(3)))
    floor_cfg = sim_utils.CuboidCfg(size=(size, size, 0.002),
                                    visual_material=sim_utils.PreviewSurfaceCfg(diffuse_color=(0.85, 0.85, 0.82)))
    floor_cfg.func("/World/efc_floor", floor_cfg,
                   translation=(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), lo[2] - 0.002))

    # -- the object: URDF converted to USD at start, root fixed, every movable joint
    #    on one implicit (PhysX) PD drive realising its servo, spring and damping
    profile_on = profile is not None
    plan = joint_drive_plan(table, profile_on)
    q_start = {}
    for j in table["joints"]:
        q0 = float(j["initial"])
        if profile_on and j["drive_by"] == "profile":
            q0 = efc.profile_target(profile, j["part"], j["lo"], j["hi"], j["initial"], 0.0, duration)
        q_start[j["joint"]] = start_position(j, q0)
    actuators = {}
    for n, p in enumerate(plan):
        actuators["efc_joint_%d" % n] = ImplicitActuatorCfg(
            joint_names_expr=[re.escape(p["joint"])], stiffness=p["stiffness"], damping=p["damping"],
            friction=0.0)
    spawn = sim_utils.UrdfFileCfg(
        asset_path=os.path.abspath(urdf_path),
        fix_base=True,
        merge_fixed_joints=False,      # keep every link (effectors, *_site links) as a body
        make_instanceable=False,       # visuals stay editable (the glow binds a material)
        force_usd_conversion=True,
        self_collision=False,
        joint_drive=sim_utils.UrdfConverterCfg.JointDriveCfg(
            drive_type="force", target_type="position",
            gains=sim_utils.UrdfConverterCfg.JointDriveCfg.PDGainsCfg(stiffness=0.0, damping=0.0)),
        articulation_props=sim_utils.ArticulationRootPropertiesCfg(enabled_self_collisions=False),
    )
    robot_cfg = ArticulationCfg(
        prim_path=OBJECT_PRIM,
        spawn=spawn,
        init_state=ArticulationCfg.InitialStateCfg(
            pos=(0.0, 0.0, 0.0), joint_pos={re.escape(name): q for name, q in q_start.items()}),
        actuators=actuators,
    )
    robot: "Articulation" = Articulation(robot_cfg)

    def link_prim(link):
        """The USD prim of a link of the imported object (a rigid body named link)."""

        def is_link(prim: "Usd.Prim") -> bool:
            return prim.GetName() == link and prim.HasAPI(UsdPhysics.RigidBodyAPI)

        found = sim_utils.get_all_matching_child_prims(OBJECT_PRIM, predicate=is_link)
        if not found:
            raise UsageError("the imported object has no link '%s' (URDF importer renamed or "
                             "merged it)" % link, status=3)
        prim: "Usd.Prim" = found[0]
        return prim

    def glow_material(i, link):
        """A preview-surface material bound to a link (stronger than its visuals' own):
        returns its shader's (diffuse, emissive) attributes and the link's URDF colour."""
        base = tuple(float(c) for c in summary["colors"].get(link, DEFAULT_RGB))
        mat_path = "%s/efc_glow_%d" % (LOOKS_PRIM, i)
        mat_cfg = sim_utils.PreviewSurfaceCfg(diffuse_color=base, emissive_color=(0.0, 0.0, 0.0), roughness=0.5)
        shader: "Usd.Prim" = mat_cfg.func(mat_path, mat_cfg)
        target_prim: "Usd.Prim" = link_prim(link)
        sim_utils.bind_visual_material(str(target_prim.GetPath()), mat_path, stronger_than_descendants=True)
        diffuse_attr: "Usd.Attribute" = shader.GetAttribute("inputs:diffuseColor")
        emissive_attr: "Usd.Attribute" = shader.GetAttribute("inputs:emissiveColor")
        return diffuse_attr, emissive_attr, base

    # -- illumination: a sphere light under the effector link, at the site, its
    #    intensity set every step; shadows off, since the site is usually inside the
    #    bulb's own geometry; the effector part glows in the light's colour
    light_attrs = {}
    lamp_attrs = {}
    for i in effect_functions(table, "illumination"):
        fn = functions[i]
        site = fn["site"]
        parent: "Usd.Prim" = link_prim(site["parent_link"])
        color = tuple(float(c) for c in (fn["color"] or (1.0, 1.0, 1.0)))
        light_cfg = sim_utils.SphereLightCfg(radius=LIGHT_RADIUS, intensity=0.0, color=color,
                                             normalize=False, exposure=0.0, treat_as_point=False)
        light: "Usd.Prim" = light_cfg.func(str(parent.GetPath()) + "/efc_light_%d" % i, light_cfg,
                                           translation=tuple(float(x) for x in site["xyz"]))
        shadow: "UsdLux.ShadowAPI" = UsdLux.ShadowAPI.Apply(light)
        shadow.CreateShadowEnableAttr(False)
        intensity: "Usd.Attribute" = light.GetAttribute("inputs:intensity")
        light_attrs[i] = intensity
        lamp_attrs[i] = glow_material(i, fn["effector"]["link"]) + (color,)

    # -- temperature: a preview-surface material bound to the effector link whose
    #    diffuse and emissive colours follow the temperature (glow)
    glow_attrs = {}
    for i in effect_functions(table, "temperature"):
        glow_attrs[i] = glow_material(i, functions[i]["effector"]["link"])

    # -- fluid droplets (a recycled pool per function) and airflow props: one
    #    collection of small rigid spheres
    objects = {}
    bodies = []  # per collection object: {"kind", "fn", "radius", "home"/"park"}
    serial = 0
    for i in effect_functions(table, "fluid"):
        fn = functions[i]
        radius = float(fn["droplet_radius"] or 0.004)
        for k in range(int(fn["droplet_pool"] or 0)):
            park = park_position(serial, radius)
            serial += 1
            key = "efc_drop_%d_%d" % (i, k)
            objects[key] = RigidObjectCfg(
                prim_path="%s/%s" % (DROPS_PRIM, key),
                spawn=sim_utils.SphereCfg(
                    radius=radius,
                    rigid_props=sim_utils.RigidBodyPropertiesCfg(),
                    mass_props=sim_utils.MassPropertiesCfg(density=WATER_DENSITY),
                    collision_props=sim_utils.CollisionPropertiesCfg(),
                    visual_material=sim_utils.PreviewSurfaceCfg(diffuse_color=DROP_RGB)),
                init_state=RigidObjectCfg.InitialStateCfg(pos=park))
            bodies.append({"kind": "drop", "fn": i, "radius": radius, "park": park})
    if args.props > 0:
        for i in effect_functions(table, "airflow"):
            fn = functions[i]
            outlet = tuple(fn["site"]["point"])
            homes = prop_homes(outlet, tuple(fn["direction"]), float(fn["reach"]), float(fn["cone_angle"]),
                               args.props)
            for k, home in enumerate(homes):
                key = "efc_prop_%d_%d" % (i, k)
                objects[key] = RigidObjectCfg(
                    prim_path="%s/%s" % (DROPS_PRIM, key),
                    spawn=sim_utils.SphereCfg(
                        radius=PROP_RADIUS,
                        rigid_props=sim_utils.RigidBodyPropertiesCfg(disable_gravity=True),
                        mass_props=sim_utils.MassPropertiesCfg(density=PROP_DENSITY),
                        collision_props=sim_utils.CollisionPropertiesCfg(),
                        visual_material=sim_utils.PreviewSurfaceCfg(diffuse_color=PROP_RGB)),
                    init_state=RigidObjectCfg.InitialStateCfg(pos=home))
                bodies.append({"kind": "prop", "fn": i, "radius": PROP_RADIUS, "home": home,
                               "reach": float(fn["reach"])})
    pool = None
    if objects:
        pool_cfg = RigidObjectCollectionCfg(rigid_objects=objects)
        pool: "RigidObjectCollection" = RigidObjectCollection(pool_cfg)

    # -- start physics
    sim.reset()
    robot.update(0.0)
    names = list(robot.joint_names)
    joint_index = {}
    for j in table["joints"]:
        if j["joint"] not in names:
            raise UsageError("the imported object has no joint '%s' (joints: %s)"
                             % (j["joint"], ", ".join(names)), status=3)
        joint_index[j["joint"]] = names.index(j["joint"])
    body_names = list(robot.body_names)

    def body_of(link):
        if link not in body_names:
            raise UsageError("the imported object has no link '%s' (links: %s)" % (link, ", ".join(body_names)),
                             status=3)
        return body_names.index(link)

    # fluid and airflow: the site's parent (the effector link) carries the outlet
    effector_body = {i: body_of(fn["site"]["parent_link"]) for i, fn in enumerate(functions)
                     if fn["effect"]["kind"] in ("fluid", "airflow")}
    device = robot.device
    n_joints = len(names)
    q0 = robot.data.default_joint_pos.clone()
    for name, q in q_start.items():
        q0[0, joint_index[name]] = q
    robot.write_joint_state_to_sim(q0, torch.zeros_like(q0))
    robot.reset()

    # joint friction (N or N m): an explicit effort each step (PhysX's own joint friction
    # is a unitless coefficient of the transmitted force, not this)
    frictional = []
    for j in table["joints"]:
        f = float(j.get("friction") or 0.0)
        if f > 0:
            inertia = joint_inertia(summary, j)
            if inertia > 0:
                frictional.append((joint_index[j["joint"]], f, inertia))
            else:
                say("warning: joint '%s': friction not realised (no inertial in the URDF)" % j["joint"])

    # fluid / airflow state
    floor_z = lo[2] - DROPLET_FALL
    drop_ids = {}  # function -> collection indices of its droplets
    for n, b in enumerate(bodies):
        b["alive"] = False
        b["born"] = 0.0
        if b["kind"] == "drop":
            drop_ids.setdefault(b["fn"], []).append(n)
    next_drop = {i: 0 for i in drop_ids}
    meters = {i: efc.FlowMeter(window=FLOW_WINDOW, dt=dt) for i in effect_functions(table, "fluid")}
    airflow = effect_functions(table, "airflow")
    last_intensity = {}
    last_glow = {}

    def read_positions():
        q = robot.data.joint_pos[0].tolist()
        return {name: q[idx] for name, idx in joint_index.items()}

    positions = read_positions()
    tpl.reset(positions)
    is_rendering = sim.has_gui()

    for k in range(args.steps):
        if not simulation_app.is_running():
            break
        t = k * dt
        # joint drives: servo targets (profile receptors, geometry effectors), springs
        q_star = {p["joint"]: q_start[p["joint"]] for p in plan}
        if profile_on:
            for j in efc.profile_joints(table):
                q_star[j["joint"]] = efc.profile_target(profile, j["part"], j["lo"], j["hi"], j["initial"],
                                                        t, duration)
        positions = read_positions()
        emits = tpl.step(positions, dt)
        measured = [0.0] * len(functions)
        if effector_body:
            link_pos = robot.data.body_link_pos_w[0].tolist()
            link_quat = robot.data.body_link_quat_w[0].tolist()
        outlets = {}
        for i, fn in enumerate(functions):
            kind = fn["effect"]["kind"]
            out = tpl.output[i]
            if kind == "geometry":
                q_star[fn["effector"]["joint"]] = out
                measured[i] = positions[fn["effector"]["joint"]]
            elif kind == "illumination":
                attr: "Usd.Attribute" = light_attrs[i]
                value = lumens_to_intensity(out)
                if last_intensity.get(i) != value:
                    attr.Set(float(value))
                    last_intensity[i] = value
                    diffuse_attr, emissive_attr, base, color = lamp_attrs[i]
                    diffuse, emissive = lamp_colors(base, color, out, max(fn["effect"]["e_lo"], fn["effect"]["e_hi"]))
                    diffuse_attr.Set(Gf.Vec3f(*diffuse))
                    emissive_attr.Set(Gf.Vec3f(*emissive))
                measured[i] = intensity_to_lumens(float(attr.Get()))
            elif kind == "temperature":
                diffuse_attr, emissive_attr, base = glow_attrs[i]
                f = efc.glow_fraction(fn, out)
                if last_glow.get(i) != f:
                    diffuse, emissive = glow_colors(base, f)
                    diffuse_attr.Set(Gf.Vec3f(*diffuse))
                    emissive_attr.Set(Gf.Vec3f(*emissive))
                    last_glow[i] = f
                measured[i] = out
            elif kind in ("fluid", "airflow"):
                b = effector_body[i]
                origin = site_world(link_pos[b], link_quat[b], fn["site"]["xyz"])
                axis = normalized(quat_rotate(link_quat[b], fn["direction"]))
                outlets[i] = (origin, axis)
                if kind == "airflow":
                    measured[i] = efc.air_speed_at(out, 0.0, 0.0, fn["cone_angle"], fn["reach"])
        # fluid: recycle, park, emit (round robin over each function's pool)
        writes = {}
        if pool is not None:
            obj_pos = pool.data.object_link_pos_w[0].tolist()
            for n, b in enumerate(bodies):
                if b["kind"] == "drop":
                    if b["alive"] and (t - b["born"] > DROPLET_LIFETIME or obj_pos[n][2] < floor_z):
                        b["alive"] = False
                    if not b["alive"]:
                        writes[n] = (b["park"], (0.0, 0.0, 0.0))
                else:
                    home = b["home"]
                    away = math.sqrt(sum((obj_pos[n][c] - home[c]) ** 2 for c in range(3)))
                    if away > PROP_ESCAPE * max(b["reach"], 0.3):
                        writes[n] = (home, (0.0, 0.0, 0.0))
            for i, ids in drop_ids.items():
                fn = functions[i]
                n_emit = emits[i]
                if n_emit <= 0 or not ids:
                    continue
                origin, axis = outlets[i]
                speed = float(fn["speed"] or 0.0)
                for e in range(n_emit):
                    n = ids[next_drop[i]]
                    next_drop[i] = (next_drop[i] + 1) % len(ids)
                    lead = speed * dt * (float(e) / n_emit)
                    writes[n] = (tuple(origin[c] + axis[c] * lead for c in range(3)),
                                 tuple(speed * axis[c] for c in range(3)))
                    bodies[n]["alive"] = True
                    bodies[n]["born"] = t
        for i in meters:
            meters[i].add(t, emits[i] if drop_ids.get(i) else 0)
            measured[i] = meters[i].flow(t, functions[i]["effect"]["droplet_volume_l"])
        if pool is not None:
            if writes:
                ids = sorted(writes)
                poses = torch.tensor([[list(writes[n][0]) + [1.0, 0.0, 0.0, 0.0] for n in ids]],
                                     dtype=torch.float32, device=device)
                vels = torch.tensor([[list(writes[n][1]) + [0.0, 0.0, 0.0] for n in ids]],
                                    dtype=torch.float32, device=device)
                id_tensor = torch.tensor(ids, dtype=torch.long, device=device)
                pool.write_object_link_pose_to_sim(poses, object_ids=id_tensor)
                pool.write_object_com_velocity_to_sim(vels, object_ids=id_tensor)
                for n in ids:
                    obj_pos[n] = list(writes[n][0])
            # airflow: drag along the outlet axis on every pool body inside a cone
            forces = [[0.0, 0.0, 0.0] for _ in bodies]
            for i in airflow:
                out = tpl.output[i]
                if out == 0:
                    continue
                origin, axis = outlets[i]
                for n, b in enumerate(bodies):
                    area = math.pi * b["radius"] * b["radius"]
                    f = efc.airflow_force(functions[i], out, origin, axis, obj_pos[n], area)
                    for c in range(3):
                        forces[n][c] += f[c]
            force_tensor = torch.tensor([forces], dtype=torch.float32, device=device)
            pool.set_external_force_and_torque(force_tensor, torch.zeros_like(force_tensor), is_global=True)
            pool.write_data_to_sim()
        # joint targets for every joint, then step
        targets = torch.zeros((1, n_joints), dtype=torch.float32, device=device)
        for p in plan:
            targets[0, joint_index[p["joint"]]] = p["blend"](q_star[p["joint"]])
        robot.set_joint_position_target(targets)
        if frictional:
            qd = robot.data.joint_vel[0].tolist()
            efforts = torch.zeros((1, n_joints), dtype=torch.float32, device=device)
            for idx, f, inertia in frictional:
                efforts[0, idx] = friction_effort(f, qd[idx], inertia, dt)
            robot.set_joint_effort_target(efforts)
        robot.write_data_to_sim()
        if log is not None:
            log.add(t, measured)
        sim.step(render=False)
        if is_rendering and (k + 1) % frame_every == 0:
            sim.render()
        robot.update(dt)
        if pool is not None:
            pool.update(dt)
    if log is not None:
        log.write(args.csv)
    return 0
