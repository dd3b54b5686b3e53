# The fixed code of <name>_omnigibson.py: runs an efc object in OmniGibson 3.7
# (BEHAVIOR-1K). The C++ backend prepends a generated docstring and appends
#     if __name__ == "__main__": sys.exit(main(sys.argv[1:], object_name=...,
#         urdf_file=..., functions_file=...))
# Everything the spec names reaches this file only through <name>_functions.json
# (read at run time), as strings and dict keys. OmniGibson is imported inside
# main(), after the command line is parsed, so --help works without it.
# API facts and their source lines: backends/omnigibson/NOTES.md.

import argparse
import collections
import hashlib
import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys
import typing
import xml.etree.ElementTree as ET

import efc_templates as efc

if typing.TYPE_CHECKING:  # annotation names only: these modules exist only inside Isaac Sim
    from isaacsim.core.api import SimulationContext  # base of OmniGibson's Simulator (og.sim)
    from pxr import Usd

PROG = os.path.basename(__file__)
GLUE_VERSION = "1"  # part of the asset fingerprint: bump when the import changes

# The imported asset: a dataset folder next to the script (OmniGibson's layout
# <root>/objects/<category>/<model>/usd/<model>.usd). Fixed names, never spec names.
ASSET_DIR = "omnigibson_asset"
CATEGORY = "efc_object"
MODEL = "efcobj"
OBJECT_PRIM = "/efc_object"

# Illumination: a sphere light of radius r whose surface is a Lambertian emitter of
# luminance L (USD inputs:intensity, exposure 0) emits F = pi L (4 pi r^2) lumens.
LIGHT_MIN_RADIUS = 0.01
LIGHT_MAX_RADIUS = 0.25
# Temperature: neighbours within HEAT_DISTANCE of the site are heated towards the
# part's temperature at HEAT_RATE (OmniGibson's HeatSourceOrSink defaults).
HEAT_DISTANCE = 0.2
HEAT_RATE = 0.04
# Fluid: as the MuJoCo binding (efc_mujoco.h): flow window, particle lifetime.
FLOW_WINDOW = 0.5
PARTICLE_LIFETIME = 3.0
# Airflow props: small light spheres in each outlet cone.
PROP_RADIUS = 0.015
PROP_MASS = 0.002
PROP_RGBA = (0.95, 0.95, 0.2, 1.0)

EXIT_OK, EXIT_BAD_INPUT, EXIT_USAGE, EXIT_SIM = 0, 1, 2, 3


class GlueError(Exception):
    """A user-facing error: printed as one line, no traceback."""

    def __init__(self, message, code=EXIT_BAD_INPUT):
        super().__init__(message)
        self.message = message
        self.code = code


def say(message):
    print("%s: %s" % (PROG, message), file=sys.stderr)


# ---------------------------------------------------------------------------
# Pure helpers (no simulator; unit-tested in test_efc_omnigibson.py).

def rpy_to_quat(rpy):
    """URDF roll-pitch-yaw (fixed axes X, Y, Z: R = Rz(y) Ry(p) Rx(r)) -> (x, y, z, w)."""
    r, p, y = (0.5 * float(a) for a in rpy)
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def quat_rotate(q, v):
    """Rotates the 3-vector v by the unit quaternion q = (x, y, z, w)."""
    x, y, z, w = (float(c) for c in q)
    vx, vy, vz = (float(c) for c in v)
    # t = 2 q_vec x v; v' = v + w t + q_vec x t
    tx = 2.0 * (y * vz - z * vy)
    ty = 2.0 * (z * vx - x * vz)
    tz = 2.0 * (x * vy - y * vx)
    return (vx + w * tx + (y * tz - z * ty),
            vy + w * ty + (z * tx - x * tz),
            vz + w * tz + (x * ty - y * tx))


def normalized(v):
    n = math.sqrt(sum(float(c) * float(c) for c in v))
    return tuple(float(c) / n for c in v) if n > 0 else tuple(float(c) for c in v)


def lumens_to_intensity(lumens, radius):
    """USD sphere light inputs:intensity (luminance, nits) that emits `lumens`."""
    return float(lumens) / (4.0 * math.pi * math.pi * radius * radius)


def intensity_to_lumens(intensity, radius):
    return float(intensity) * 4.0 * math.pi * math.pi * radius * radius


def enclosing_radius(point, lo, hi, min_radius=LIGHT_MIN_RADIUS, max_radius=LIGHT_MAX_RADIUS):
    """Radius of a sphere at `point` enclosing the box [lo, hi] (a light inside an opaque
    part would be blocked by it), clamped to [min_radius, max_radius]."""
    far = 0.0
    for cx in (lo[0], hi[0]):
        for cy in (lo[1], hi[1]):
            for cz in (lo[2], hi[2]):
                d = math.sqrt((cx - point[0]) ** 2 + (cy - point[1]) ** 2 + (cz - point[2]) ** 2)
                far = max(far, d)
    return min(max(far * 1.05, min_radius), max_radius)


def combined_drive(kp, kv, spring, damping, target):
    """One PD drive that realises a position servo (kp, kv -> target) plus a joint
    spring (stiffness k about rest) and viscous damping: the forces add up to
    (kp + k) (target' - q) - (kv + damping) qdot with
    target' = (kp target + k rest) / (kp + k). Returns (kp', kd', target')."""
    k = float(spring["stiffness"]) if spring else 0.0
    rest = float(spring["rest"]) if spring else 0.0
    total = float(kp) + k
    kd = float(kv) + float(damping)
    if total <= 0.0:
        return 0.0, kd, float(target)
    return total, kd, (float(kp) * float(target) + k * rest) / total


def blend_rgb(base, hot, f):
    return tuple(float(base[c]) * (1.0 - f) + float(hot[c]) * f for c in range(3))


def sphere_area(radius):
    """Silhouette of a sphere (m^2): the same from every direction."""
    return math.pi * radius * radius


def prop_positions(outlet, axis, reach, count):
    """Where airflow props start: on the outlet axis at (i + 1) / (count + 1) of the reach."""
    a = normalized(axis)
    return [tuple(outlet[k] + a[k] * reach * (i + 1) / (count + 1) for k in range(3))
            for i in range(count)]


def emit_positions(site, direction, speed, dt, count):
    """Droplets of one step spread along the stream as if emitted evenly during the
    step (as the MuJoCo binding): droplet e at site + direction * speed * dt * e / count."""
    d = normalized(direction)
    out = []
    for e in range(count):
        lead = speed * dt * (float(e) / count)
        out.append(tuple(site[k] + d[k] * lead for k in range(3)))
    return out


def expired_count(births, now, lifetime):
    """How many of the oldest particles (birth times in spawn order) are older than lifetime."""
    n = 0
    for t in births:
        if now - t > lifetime:
            n += 1
        else:
            break
    return n


def object_temperature(outputs, ambient):
    """The object's Temperature state when it has several temperature functions:
    OmniGibson keeps one temperature per object, so the hottest part."""
    return max(outputs) if outputs else ambient


def meta_links(table, toggle_radius=0.004):
    """The meta links to add to the asset's metadata.json: a 'togglebutton' (the
    ToggledOn state of the toggleable ability needs one) on the receptor link of the
    first illumination function. Returns {parent link: {meta type: {id: [info]}}}."""
    for fn in table["functions"]:
        if fn["effect"]["kind"] == "illumination":
            link = fn["receptor"]["link"]
            return {link: {"togglebutton": {"0": [{
                "position": [0.0, 0.0, 0.0], "orientation": [0.0, 0.0, 0.0, 1.0],
                "type": "sphere", "size": [toggle_radius] * 3}]}}}
    return {}


def abilities_for(table):
    """OmniGibson abilities of the object: toggleable (ToggledOn) when it lights up,
    heatable (Temperature, Heated) when a part gets hot."""
    kinds = {fn["effect"]["kind"] for fn in table["functions"]}
    abilities = {}
    if "illumination" in kinds:
        abilities["toggleable"] = {}
    if "temperature" in kinds:
        abilities["heatable"] = {}
    return abilities


def asset_fingerprint(urdf_path, table, collision):
    """Identifies an imported asset: the URDF and its meshes, the meta links, the
    collision method and this glue's import version."""
    h = hashlib.sha256()
    h.update(("efc-omnigibson-asset %s %s\n" % (GLUE_VERSION, collision)).encode())
    h.update(json.dumps(meta_links(table), sort_keys=True).encode())
    with open(urdf_path, "rb") as f:
        h.update(f.read())
    mesh_dir = os.path.join(os.path.dirname(os.path.abspath(urdf_path)), "meshes")
    if os.path.isdir(mesh_dir):
        for name in sorted(os.listdir(mesh_dir)):
            path = os.path.join(mesh_dir, name)
            if os.path.isfile(path):
                h.update(name.encode())
                with open(path, "rb") as f:
                    h.update(f.read())
    return h.hexdigest()


def prepare_urdf(urdf_path, work_dir):
    """Copies the URDF (robot renamed to MODEL, the USD prim name the import expects)
    and its meshes/ folder into work_dir; returns the copy's path."""
    os.makedirs(work_dir, exist_ok=True)
    try:
        tree = ET.parse(urdf_path)
    except (OSError, ET.ParseError) as e:
        raise GlueError("cannot read the URDF '%s': %s" % (urdf_path, e))
    tree.getroot().set("name", MODEL)
    out = os.path.join(work_dir, MODEL + ".urdf")
    tree.write(out, encoding="utf-8", xml_declaration=True)
    mesh_dir = os.path.join(os.path.dirname(os.path.abspath(urdf_path)), "meshes")
    if os.path.isdir(mesh_dir):
        shutil.copytree(mesh_dir, os.path.join(work_dir, "meshes"), dirs_exist_ok=True)
    return out


def add_meta_links(metadata_path, links):
    """Merges `links` into the meta_links of OmniGibson's misc/metadata.json."""
    with open(metadata_path, "r", encoding="utf-8") as f:
        metadata = json.load(f)
    metadata.setdefault("meta_links", {})
    for parent, types in links.items():
        metadata["meta_links"].setdefault(parent, {}).update(types)
    with open(metadata_path, "w", encoding="utf-8") as f:
        json.dump(metadata, f)


def asset_paths(script_dir):
    root = os.path.join(script_dir, ASSET_DIR)
    model_dir = os.path.join(root, "objects", CATEGORY, MODEL)
    return {"root": root, "model_dir": model_dir,
            "usd": os.path.join(model_dir, "usd", MODEL + ".usd"),
            "stamp": os.path.join(model_dir, "efc_import.json"),
            "work": os.path.join(model_dir, "urdf")}


def asset_is_current(paths, fingerprint):
    try:
        with open(paths["stamp"], "r", encoding="utf-8") as f:
            stamp = json.load(f)
    except (OSError, ValueError):
        return False
    return stamp.get("fingerprint") == fingerprint and os.path.isfile(paths["usd"])


def check_table(table):
    """What this target needs beyond efc_templates' checks."""
    for fn in table["functions"]:
        kind = fn["effect"]["kind"]
        if kind != "geometry" and fn.get("site") is None:
            raise GlueError("function '%s': a %s effect needs a site" % (fn["name"], kind))


# ---------------------------------------------------------------------------
# Command line.

def parse_args(argv):
    p = argparse.ArgumentParser(
        prog=PROG,
        description="Run this efc object in OmniGibson 3.7: the function templates step with "
                    "the simulation and every effect is realised in the scene.")
    efc.add_run_arguments(p, headless_help="no window (sets OMNIGIBSON_HEADLESS=1)")
    p.add_argument("--device", default=None, help="torch device for OmniGibson (e.g. cuda:0, cpu)")
    p.add_argument("--props", type=int, default=3,
                   help="light spheres placed in each airflow cone (default 3)")
    p.add_argument("--no-props", action="store_true", help="no airflow props")
    p.add_argument("--max-particles", type=int, default=5000,
                   help="fluid particles kept at most; the oldest go first (default 5000)")
    p.add_argument("--collision", choices=("urdf", "convex", "coacd"), default="urdf",
                   help="collision shapes of the imported asset: the URDF's own (default), "
                        "one convex hull per mesh, or a CoACD decomposition")
    p.add_argument("--reimport", action="store_true",
                   help="convert the URDF to an OmniGibson asset again even if it is current")
    p.add_argument("--import-only", action="store_true",
                   help="convert the URDF to an OmniGibson asset (%s/) and exit" % ASSET_DIR)
    try:
        args = p.parse_args(argv)
    except SystemExit as e:
        raise GlueError("", code=e.code if isinstance(e.code, int) else EXIT_USAGE) from None
    if args.props < 0:
        raise GlueError("--props must be 0 or more", EXIT_USAGE)
    if args.max_particles < 1:
        raise GlueError("--max-particles must be at least 1", EXIT_USAGE)
    return args


def main(argv, object_name, urdf_file, functions_file):
    """The script's entry point (argv without the program name); returns the exit status."""
    script_dir = os.path.dirname(os.path.abspath(__file__))
    urdf_path = os.path.join(script_dir, urdf_file)
    functions_path = os.path.join(script_dir, functions_file)
    args = None
    try:
        args = parse_args(list(argv))
        table = load_table(functions_path)
        try:
            run = efc.run_settings(args, table)
        except efc.EfcError as e:
            raise GlueError(e.message, e.status) from None
        for w in run.warnings:
            say("warning: " + w)
        dt, duration, profile = run.dt, run.duration, run.profile
        args.steps = run.steps
        paths = asset_paths(script_dir)
        fingerprint = asset_fingerprint(urdf_path, table, args.collision)
        if args.import_only:
            import_asset(urdf_path, table, args.collision, paths, fingerprint)
            return EXIT_OK
        if importlib.util.find_spec("omnigibson") is None:
            raise GlueError("OmniGibson is not installed in this Python (%s); see the README"
                            % sys.executable, EXIT_SIM)
        if args.reimport or not asset_is_current(paths, fingerprint):
            run_import_subprocess(args.collision, paths, fingerprint)
        if args.headless:
            # Read by omnigibson.macros (gm.HEADLESS) when OmniGibson is imported.
            os.environ["OMNIGIBSON_HEADLESS"] = "1"
        return Runner(table, object_name, args, dt, duration, profile, paths).run()
    except GlueError as e:
        if e.message:
            say(e.message)
        return e.code
    except efc.EfcError as e:
        if e.line > 0 and args is not None and (args.profile or "").startswith("csv:"):
            say("%s:%d: %s" % (args.profile[4:], e.line, e.message))
        else:
            say(e.message)
        return EXIT_USAGE if e.io_error else EXIT_BAD_INPUT
    except OSError as e:
        say("%s: %s" % (getattr(e, "filename", None) or "I/O error", e.strerror or e))
        return EXIT_USAGE


def load_table(path):
    table = efc.load_functions(path)
    check_table(table)
    return table


# ---------------------------------------------------------------------------
# URDF -> OmniGibson asset (OmniGibson's asset conversion utilities).

def run_import_subprocess(collision, paths, fingerprint):
    """The conversion opens the asset's stage in place of the simulator's, so it runs
    in a child process (this script with --import-only), then this process starts a
    clean simulator."""
    env = dict(os.environ)
    env["OMNIGIBSON_HEADLESS"] = "1"
    say("importing the URDF into OmniGibson (%s/), once ..." % ASSET_DIR)
    cmd = [sys.executable, os.path.abspath(__file__), "--import-only", "--collision", collision]
    try:
        subprocess.run(cmd, env=env, check=False)
    except OSError as e:
        raise GlueError("cannot run the import: %s" % (e.strerror or e), EXIT_SIM)
    if not asset_is_current(paths, fingerprint):
        raise GlueError("the URDF import did not produce %s (see the messages above)" % paths["usd"],
                        EXIT_SIM)


def import_asset(urdf_path, table, collision, paths, fingerprint):
    """URDF -> USD with OmniGibson 3.7's asset conversion steps (the ones
    import_og_asset_from_urdf chains; that function itself passes dataset_root= to
    convert_urdf_to_usd, which takes dataset_name=, at 3.7.x)."""
    try:
        import omnigibson as og
        from omnigibson.utils.asset_conversion_utils import (
            convert_urdf_to_usd, find_all_prim_children_with_type,
            get_collision_approximation_for_urdf, import_obj_metadata,
            record_obj_metadata_from_urdf)
    except (ImportError, AssertionError) as e:
        raise GlueError("cannot import OmniGibson 3.7 (%s); install it and its datasets "
                        "(see the README)" % e, EXIT_SIM)
    shutil.rmtree(paths["model_dir"], ignore_errors=True)
    os.makedirs(paths["model_dir"])
    work_urdf = prepare_urdf(urdf_path, paths["work"])
    if collision in ("convex", "coacd"):
        get_collision_approximation_for_urdf(urdf_path=work_urdf, collision_method=collision)
    record_obj_metadata_from_urdf(urdf_path=work_urdf, obj_dir=paths["model_dir"],
                                  joint_setting="zero", overwrite=True)
    add_meta_links(os.path.join(paths["model_dir"], "misc", "metadata.json"), meta_links(table))
    og.launch()
    # dataset_name is joined to gm.DATA_PATH with os.path.join: an absolute path wins.
    _, usd_path = convert_urdf_to_usd(urdf_path=work_urdf, obj_category=CATEGORY, obj_model=MODEL,
                                      dataset_name=os.path.abspath(paths["root"]),
                                      use_omni_convex_decomp=False, use_usda=False,
                                      merge_fixed_joints=False)
    prim: "Usd.Prim" = import_obj_metadata(usd_path=usd_path, obj_category=CATEGORY, obj_model=MODEL,
                               dataset_root=os.path.abspath(paths["root"]))
    # Joint drives in force mode (N/m, N m/rad): the JSON's gains are forces.
    for joint_type, axis in (("PhysicsPrismaticJoint", "linear"), ("PhysicsRevoluteJoint", "angular")):
        for joint_prim in find_all_prim_children_with_type(prim_type=joint_type, root_prim=prim):
            attr = joint_prim.GetAttribute("drive:%s:physics:type" % axis)
            if attr:
                attr.Set("force")
    prim.GetStage().Save()
    with open(paths["stamp"], "w", encoding="utf-8") as f:
        json.dump({"fingerprint": fingerprint, "usd": os.path.relpath(usd_path, paths["model_dir"])}, f)
    say("imported: %s" % usd_path)
    og.shutdown()


# ---------------------------------------------------------------------------
# The simulation.

class Runner:
    """Builds the scene, steps the templates with the simulation, realises the effects."""

    # og.sim is OmniGibson's Simulator, a class defined inside
    # omnigibson.simulator._launch_simulator (so not in the API index): typed by its
    # Isaac Sim base here; the methods used (import_scene, play, step) are in NOTES.md.
    sim: "SimulationContext"
    scene: "Scene"
    obj: "USDObject"
    water: "FluidSystem"

    def __init__(self, table, object_name, args, dt, duration, profile, paths):
        self.table = table
        self.object_name = object_name
        self.args = args
        self.dt = dt
        self.duration = duration
        self.profile = profile
        self.paths = paths
        self.functions = table["functions"]
        self.joint_info = {j["joint"]: j for j in table["joints"]}
        self.tpl = efc.Templates(table)
        self.log = efc.CsvLog(table, self.tpl)
        self.meters = [efc.FlowMeter(window=FLOW_WINDOW, dt=dt) for _ in self.functions]
        self.births = collections.deque()  # spawn times of our fluid particles, in order
        self.glow_base = {}                # function index -> [(mesh, base rgb)]
        self.lights = {}                   # function index -> (LightObject, radius)
        self.props = []                    # airflow props (PrimitiveObject)
        self.n_temperature = sum(1 for fn in self.functions if fn["effect"]["kind"] == "temperature")

    # -- set-up ----------------------------------------------------------------
    def run(self):
        try:
            import omnigibson as og
            import torch as th
            from omnigibson.macros import gm
            from omnigibson.scenes import Scene
        except (ImportError, AssertionError) as e:
            raise GlueError("cannot import OmniGibson 3.7 (%s); install it and its datasets "
                            "(see the README)" % e, EXIT_SIM)
        self.og = og
        self.th = th
        kinds = {fn["effect"]["kind"] for fn in self.functions}
        if "fluid" in kinds:
            # Fluids (FluidSystem) need PhysX GPU dynamics; read when the simulator starts.
            gm.USE_GPU_DYNAMICS = True
        og.launch(physics_dt=self.dt, rendering_dt=self.dt, sim_step_dt=self.dt, device=self.args.device)
        code = EXIT_OK
        try:
            self.sim = og.sim
            self.scene = Scene(use_floor_plane=True, floor_plane_visible=True)
            self.sim.import_scene(self.scene)
            self.load_object()
            self.add_lights()
            self.add_props()
            self.sim.play()
            self.bind()
            self.loop()
            if self.args.csv:
                self.log.write(self.args.csv)
        except (GlueError, efc.EfcError) as e:
            # said before the app closes: og.shutdown() may end the process
            say(e.message)
            code = e.code if isinstance(e, GlueError) else EXIT_USAGE
        finally:
            og.shutdown()
        return code

    def load_object(self):
        from omnigibson.objects import USDObject
        obj: "USDObject" = USDObject(
            name=self.object_name, usd_path=self.paths["usd"], encrypted=False,
            relative_prim_path=OBJECT_PRIM, category=CATEGORY, fixed_base=True,
            abilities=abilities_for(self.table))
        self.scene.add_object(obj)
        obj.set_position_orientation(position=self.th.tensor([0.0, 0.0, 0.0]),
                                     orientation=self.th.tensor([0.0, 0.0, 0.0, 1.0]))
        self.obj = obj

    def add_lights(self):
        from omnigibson.objects import LightObject
        for i, fn in enumerate(self.functions):
            if fn["effect"]["kind"] != "illumination":
                continue
            light: "LightObject" = LightObject(
                name="efc_light_%d" % i, light_type="Sphere", relative_prim_path="/efc_light_%d" % i,
                radius=LIGHT_MIN_RADIUS, intensity=0.0, fixed_base=True)
            self.scene.add_object(light)
            light.color = tuple(float(c) for c in fn["color"])
            self.lights[i] = [light, LIGHT_MIN_RADIUS]

    def add_props(self):
        if self.args.no_props or self.args.props == 0:
            return
        from omnigibson.objects import PrimitiveObject
        for i, fn in enumerate(self.functions):
            if fn["effect"]["kind"] != "airflow":
                continue
            outlet = fn["site"]["point"]
            for k, pos in enumerate(prop_positions(outlet, fn["direction"], fn["reach"], self.args.props)):
                prop: "PrimitiveObject" = PrimitiveObject(
                    name="efc_prop_%d_%d" % (i, k), relative_prim_path="/efc_prop_%d_%d" % (i, k),
                    primitive_type="Sphere", radius=PROP_RADIUS, rgba=PROP_RGBA)
                self.scene.add_object(prop)
                prop.set_position_orientation(position=self.th.tensor(pos, dtype=self.th.float32))
                self.props.append(prop)

    def link(self, name):
        from omnigibson.prims.rigid_prim import RigidPrim
        links: "dict" = self.obj.links
        link: "RigidPrim" = links.get(name)
        if link is None:
            raise GlueError("the imported object has no link '%s' (links: %s)"
                            % (name, ", ".join(sorted(links))), EXIT_SIM)
        return link

    def joint(self, name):
        from omnigibson.prims.joint_prim import JointPrim
        joints: "dict" = self.obj.joints
        joint: "JointPrim" = joints.get(name)
        if joint is None:
            raise GlueError("the imported object has no joint '%s' (joints: %s)"
                            % (name, ", ".join(sorted(joints))), EXIT_SIM)
        return joint

    def bind(self):
        """After play(): joints, drives, springs, initial positions, effect handles."""
        from omnigibson.object_states import Temperature, ToggledOn
        from omnigibson.objects import LightObject
        from omnigibson.objects import PrimitiveObject
        from omnigibson.prims.geom_prim import VisualGeomPrim
        from omnigibson.prims.joint_prim import JointPrim
        from omnigibson.prims.rigid_prim import RigidPrim
        self.joints = {name: self.joint(name) for name in self.joint_info}
        self.profile_joints = efc.profile_joints(self.table) if self.profile is not None else []
        self.profile_names = {j["joint"] for j in self.profile_joints}
        self.effector_of = {}
        for i, fn in enumerate(self.functions):
            if fn["effect"]["kind"] == "geometry":
                self.effector_of[fn["effector"]["joint"]] = i
        for name, info in self.joint_info.items():
            joint: "JointPrim" = self.joints[name]
            joint.friction = float(info["friction"])
            joint.set_pos(float(info["initial"]))
            self.set_drive(name, float(info["initial"]))
        self.has_temperature = Temperature in self.obj.states
        self.has_toggle = ToggledOn in self.obj.states
        if self.n_temperature and not self.has_temperature:
            say("warning: the object has no Temperature state; temperature is script state "
                "plus the glow")
        for i, fn in enumerate(self.functions):
            kind = fn["effect"]["kind"]
            if kind == "temperature":
                meshes = []
                effector: "RigidPrim" = self.link(fn["effector"]["link"])
                visual_meshes: "dict" = effector.visual_meshes
                for mesh in visual_meshes.values():
                    visual: "VisualGeomPrim" = mesh
                    base = visual.color
                    meshes.append((visual, tuple(float(c) for c in base) if base is not None
                                   else (0.5, 0.5, 0.5)))
                self.glow_base[i] = meshes
            elif kind == "illumination":
                site = self.site_pose(fn)[0]
                lamp: "RigidPrim" = self.link(fn["effector"]["link"])
                try:
                    lo, hi = lamp.visual_aabb
                    radius = enclosing_radius(site, lo.tolist(), hi.tolist())
                except (AssertionError, ValueError):
                    radius = LIGHT_MIN_RADIUS
                light: "LightObject" = self.lights[i][0]
                light.radius = radius
                self.lights[i][1] = radius
        self.water = None
        if any(fn["effect"]["kind"] == "fluid" for fn in self.functions):
            from omnigibson.systems import FluidSystem
            try:
                water: "FluidSystem" = self.scene.get_system("water")
            except AssertionError as e:
                raise GlueError("no 'water' particle system (%s); install the BEHAVIOR-1K assets"
                                % e, EXIT_SIM)
            self.water = water
        from omnigibson.prims.rigid_dynamic_prim import RigidDynamicPrim
        for item in self.props:
            prop: "PrimitiveObject" = item
            body: "RigidDynamicPrim" = prop.root_link
            body.mass = PROP_MASS

    def set_drive(self, name, target):
        """The joint's PD drive: servo (profile or geometry effect) plus its spring and damping."""
        from omnigibson.controllers.controller_base import ControlType
        info = self.joint_info[name]
        joint: "JointPrim" = self.joints[name]
        servo = info["drive"] if (name in self.profile_names or name in self.effector_of) else None
        kp = float(servo["kp"]) if servo else 0.0
        kv = float(servo["kv"]) if servo else 0.0
        gain_p, gain_d, goal = combined_drive(kp, kv, info["spring"], info["damping"], target)
        if gain_p == 0.0 and gain_d == 0.0:
            return
        joint.set_control_type(ControlType.POSITION, kp=gain_p, kd=gain_d)
        self.set_target(joint, goal)

    def set_target(self, joint: "JointPrim", goal):
        # JointPrim.set_pos(drive=True) asserts joint.driven, which is False for
        # non-controllable objects; EntityPrim.set_joint_positions(drive=True) sets the
        # articulation's position target directly.
        self.obj.set_joint_positions(self.th.tensor([goal], dtype=self.th.float32),
                                     indices=joint.dof_indices, drive=True)

    def update_target(self, name, target):
        info = self.joint_info[name]
        servo = info["drive"]
        _, _, goal = combined_drive(float(servo["kp"]), float(servo["kv"]), info["spring"],
                                    info["damping"], target)
        self.set_target(self.joints[name], goal)

    def site_pose(self, fn):
        """World position and orientation (x, y, z, w) of the function's site link."""
        site: "RigidPrim" = self.link(fn["site"]["link"])
        pos, quat = site.get_position_orientation()
        return tuple(float(c) for c in pos.tolist()), tuple(float(c) for c in quat.tolist())

    def outlet(self, fn):
        """World position of the site and the world emitter/outlet direction: the JSON's
        direction (object frame = the effector link's frame at rest) turned with the
        effector link, as the MuJoCo binding does."""
        pos = self.site_pose(fn)[0]
        effector: "RigidPrim" = self.link(fn["effector"]["link"])
        quat = effector.get_position_orientation()[1]
        return pos, normalized(quat_rotate(quat.tolist(), fn["direction"]))

    def position(self, name):
        from omnigibson.prims.joint_prim import JointPrim
        joint: "JointPrim" = self.joints[name]
        return float(joint.get_state()[0][0])

    # -- the loop --------------------------------------------------------------
    def loop(self):
        og = self.og
        for k in range(self.args.steps):
            t = k * self.dt
            for j in self.profile_joints:
                q = efc.profile_target(self.profile, j["part"], j["lo"], j["hi"], j["initial"], t,
                                       self.duration)
                self.update_target(j["joint"], q)
            positions = {name: self.position(name) for name in self.joints}
            if k == 0:
                self.tpl.reset(positions)
            emits = self.tpl.step(positions, self.dt)
            measured = self.realise(t, emits)
            self.log.add(t, measured)
            self.sim.step()

    def realise(self, t, emits):
        measured = [0.0] * len(self.functions)
        temperatures = []
        lit = False
        for i, fn in enumerate(self.functions):
            kind = fn["effect"]["kind"]
            out = self.tpl.output[i]
            if kind == "geometry":
                self.update_target(fn["effector"]["joint"], out)
                measured[i] = self.position(fn["effector"]["joint"])
            elif kind == "illumination":
                measured[i] = self.light(i, fn, out)
                lit = lit or out > 0.0
            elif kind == "temperature":
                temperatures.append(out)
                measured[i] = self.heat(i, fn, out)
            elif kind == "fluid":
                measured[i] = self.fluid(i, fn, t, emits[i])
            elif kind == "airflow":
                measured[i] = efc.air_speed_at(out, 0.0, 0.0, fn["cone_angle"], fn["reach"])
        self.push_props()
        from omnigibson.object_states import Temperature, ToggledOn
        if self.has_toggle:
            toggled: "ToggledOn" = self.obj.states[ToggledOn]
            if bool(toggled.get_value()) != lit:
                toggled.set_value(lit)
        if self.has_temperature and temperatures:
            state: "Temperature" = self.obj.states[Temperature]
            state.set_value(object_temperature(temperatures, temperatures[0]))
            if self.n_temperature == 1:
                for i, fn in enumerate(self.functions):
                    if fn["effect"]["kind"] == "temperature":
                        measured[i] = float(state.get_value())
        return measured

    def light(self, i, fn, lumens):
        from omnigibson.objects import LightObject
        light: "LightObject" = self.lights[i][0]
        radius = self.lights[i][1]
        pos, quat = self.site_pose(fn)
        light.set_position_orientation(position=self.th.tensor(pos), orientation=self.th.tensor(quat))
        light.intensity = lumens_to_intensity(lumens, radius)
        return intensity_to_lumens(float(light.intensity), radius)

    def heat(self, i, fn, temperature):
        from omnigibson.object_states import Temperature
        from omnigibson.prims.geom_prim import VisualGeomPrim
        f = efc.glow_fraction(fn, temperature)
        for mesh, base in self.glow_base.get(i, []):
            visual: "VisualGeomPrim" = mesh
            visual.color = self.th.tensor(blend_rgb(base, efc.HOT_RGB, f))
        if self.has_temperature and temperature > fn["effect"]["e_lo"]:
            from omnigibson.objects import StatefulObject
            site = self.site_pose(fn)[0]
            near = []
            for candidate in self.scene.get_objects_with_state(Temperature):
                other: "StatefulObject" = candidate
                if other is self.obj:
                    continue
                p = other.get_position_orientation()[0].tolist()
                if math.dist(p, site) <= HEAT_DISTANCE:
                    near.append(other)
            if near:
                Temperature.update_temperature_from_heatsource_or_sink(
                    objs=near, temperature=temperature, rate=HEAT_RATE)
        return temperature

    def fluid(self, i, fn, t, emit):
        water = self.water
        th = self.th
        # Retire particles that lived PARTICLE_LIFETIME s, and the oldest beyond the budget.
        old = expired_count(self.births, t, PARTICLE_LIFETIME)
        old = max(old, len(self.births) + emit - self.args.max_particles)
        old = min(old, len(self.births), int(water.n_particles))
        if old > 0:
            water.remove_particles(idxs=th.arange(old))
            for _ in range(old):
                self.births.popleft()
        if emit > 0:
            pos, direction = self.outlet(fn)
            speed = float(fn["speed"])
            spots = emit_positions(pos, direction, speed, self.dt, emit)
            water.generate_particles(
                positions=th.tensor(spots, dtype=th.float32),
                velocities=th.tensor([[speed * c for c in direction]] * emit, dtype=th.float32))
            self.births.extend([t] * emit)
        self.meters[i].add(t, emit)
        return self.meters[i].flow(t, fn["effect"]["droplet_volume_l"])

    def push_props(self):
        """Air drag on every prop from every airflow outlet, applied as the impulse
        F dt (a velocity change): OmniGibson 3.7's prims have no force API."""
        if not self.props:
            return
        outlets = []
        for i, fn in enumerate(self.functions):
            if fn["effect"]["kind"] == "airflow" and self.tpl.output[i] != 0.0:
                pos, axis = self.outlet(fn)
                outlets.append((fn, self.tpl.output[i], pos, axis))
        if not outlets:
            return
        from omnigibson.objects import PrimitiveObject
        area = sphere_area(PROP_RADIUS)
        for item in self.props:
            prop: "PrimitiveObject" = item
            point = prop.get_position_orientation()[0].tolist()
            force = [0.0, 0.0, 0.0]
            for fn, out, outlet, axis in outlets:
                f = efc.airflow_force(fn, out, outlet, axis, point, area)
                force = [force[k] + f[k] for k in range(3)]
            if force == [0.0, 0.0, 0.0]:
                continue
            velocity: "th.Tensor" = prop.get_linear_velocity()
            v = velocity.tolist()
            dv = [v[k] + force[k] / PROP_MASS * self.dt for k in range(3)]
            prop.set_linear_velocity(self.th.tensor(dv, dtype=self.th.float32))
