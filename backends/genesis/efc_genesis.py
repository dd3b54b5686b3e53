# ---------------------------------------------------------------------------
# efc glue for Genesis 0.4.x (backends/genesis/efc_genesis.py in the efc repository).
#
# Builds a Genesis scene with the object (URDF, fixed base), runs the function
# templates (efc_templates.py, next to this script) every step and realises each
# effect with what Genesis 0.4.5 offers:
#   geometry      the effector dof's PD position control (kp/kv from the JSON)
#   illumination  a point light at the site added before build (Genesis cannot change a
#                 light after build: it is on or off for the whole run, --lamp-light) and,
#                 in the viewer, a marker at the site whose opacity follows the output
#   temperature   script state; in the viewer, a red-hot translucent box over the part
#   fluid         an SPH emitter at the site: the droplets the templates ask for, one
#                 particle each; measured = flow of the particles actually emitted
#   airflow       drag forces through the rigid solver on every free rigid body whose
#                 centre is in the outlet cone (plus a few floating props to see it)
# Names from the spec reach this code only through <name>_functions.json, as strings.
# Genesis is imported inside main(), so this file imports and runs --help anywhere.
# ---------------------------------------------------------------------------
import argparse
import math
import os
import sys
import time
from typing import TYPE_CHECKING

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:  # efc_templates.py sits next to this script
    sys.path.insert(0, _HERE)

import efc_templates as efc  # noqa: E402

if TYPE_CHECKING:  # for API checkers and type checkers only; never imported here at run time
    import genesis as gs
    from genesis.engine.entities import Emitter, RigidEntity
    from genesis.engine.entities.rigid_entity import RigidGeom, RigidJoint, RigidLink
    from genesis.engine.solvers import RigidSolver

GENESIS_VERSION = "0.4.5"
INSTALL_HINT = "pip install genesis-world==0.4.5 (after installing PyTorch)"

# Realisation constants (NOTES.md says where each comes from).
SPH_VOLUME_FACTOR = 0.8        # Genesis' SPH particle volume = 0.8 * particle_size^3
SPH_DEFAULT_MU = 0.005         # gs.materials.SPH.Liquid's default viscosity
SPH_REF_SUBSTEP = 4e-4         # substep (s) of Genesis' SPH examples at particle_size 0.01 m
SPH_REF_SIZE = 0.01
SPH_MARGIN = 1.5               # m of SPH domain around the emitters (horizontally, and up)
DROPLET_LIFETIME = 3.0         # s; sizes the particle pool as the MuJoCo target's droplets live
MAX_PARTICLES = 50000          # default cap of one emitter's pool
OMEGA_DT_MAX = 0.4             # stiff drives stay stable while omega * dt <= 0.4 (MuJoCo target's rule)
PROP_RADIUS = 0.015            # m, the floating props in an airflow cone
PROP_DENSITY = 50.0            # kg/m^3 (foam)
PROP_RGBA = (1.0, 0.55, 0.1, 1.0)
WATER_RGBA = (0.35, 0.6, 1.0, 0.9)
MARKER_RADIUS = 0.02           # m, the illumination marker
MARKER_LEVELS = 20             # redraw a marker when its level (1/20 steps) changes
MARKER_MOVE = 0.002            # or when its part moved this far (m)
GLOW_ALPHA = 0.75              # opacity of a fully glowing part's box
GLOW_PAD = 0.002               # m added around the glowing part's bounding box


# ---------------------------------------------------------------------------
# Pure helpers (no Genesis): unit-tested in test_efc_genesis.py.

def vadd(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def vsub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def vscale(a, s):
    return [a[0] * s, a[1] * s, a[2] * s]


def vdot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def vnorm(a):
    return math.sqrt(vdot(a, a))


def vnormalized(a):
    n = vnorm(a)
    return [a[0] / n, a[1] / n, a[2] / n] if n > 0 else [float(a[0]), float(a[1]), float(a[2])]


def quat_rotate(q, v):
    """Rotates v by the unit quaternion q = (w, x, y, z) (Genesis' convention)."""
    w, x, y, z = q
    # t = 2 (q_vec x v); v' = v + w t + q_vec x t
    tx = 2 * (y * v[2] - z * v[1])
    ty = 2 * (z * v[0] - x * v[2])
    tz = 2 * (x * v[1] - y * v[0])
    return [v[0] + w * tx + (y * tz - z * ty),
            v[1] + w * ty + (z * tx - x * tz),
            v[2] + w * tz + (x * ty - y * tx)]


def clamp01(v):
    return 0.0 if v < 0 else (1.0 if v > 1 else float(v))


def lumens_to_candela(lumens):
    """Luminous intensity (cd) of an isotropic source of `lumens` lm: lm / (4 pi).
    pyrender's (Genesis' rasterizer's) point lights take intensity in candela."""
    return max(0.0, float(lumens)) / (4.0 * math.pi)


def light_rgb(color):
    """A colour as Genesis' lights accept it (each channel in [0, 1])."""
    if color is None:
        return (1.0, 1.0, 1.0)
    return tuple(clamp01(c) for c in color[:3])


def illumination_fraction(fn, output):
    """0..1: the light's output relative to the brightest of its range."""
    e = fn["effect"]
    full = max(abs(e["e_lo"]), abs(e["e_hi"]))
    return clamp01(output / full) if full > 0 else 0.0


def level(fraction, levels=MARKER_LEVELS):
    """The fraction rounded to one of `levels` steps (0 stays 0, anything above 0 is >= 1)."""
    if fraction <= 0:
        return 0
    return max(1, int(round(clamp01(fraction) * levels)))


def sph_particle_size(droplet_volume_l):
    """SPH particle size (m) whose particle volume (Genesis: 0.8 size^3) equals one droplet."""
    volume_m3 = float(droplet_volume_l) * 1e-3
    if volume_m3 <= 0:
        raise ValueError("droplet volume must be positive")
    return (volume_m3 / SPH_VOLUME_FACTOR) ** (1.0 / 3.0)


def fluid_substeps(dt, particle_size):
    """Substeps per step that keep the SPH substep at the ratio of Genesis' SPH examples
    (4e-4 s at 0.01 m particles), scaled with the particle size."""
    target = SPH_REF_SUBSTEP * particle_size / SPH_REF_SIZE
    return max(1, int(math.ceil(dt / target - 1e-9)))


def sph_viscosity(particle_size, substep_dt, mu=SPH_DEFAULT_MU):
    """The liquid's viscosity, lowered (90% of the limit) where Genesis' SPH stability
    bound 0.01 (2 size)^2 / mu would fall below the substep."""
    limit = 0.01 * (2.0 * particle_size) ** 2 / substep_dt
    return min(mu, 0.9 * limit)


def sph_bounds(points, margin=SPH_MARGIN, floor_z=0.0):
    """SPH domain (lower, upper) around the emitter points: `margin` metres around them,
    the floor (z = floor_z) below unless a point is lower."""
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    lower = (lo[0] - margin, lo[1] - margin, floor_z if lo[2] >= floor_z else lo[2] - 0.5)
    upper = (hi[0] + margin, hi[1] + margin, max(hi[2], floor_z) + margin)
    return lower, upper


def particle_pool(fn, hint=None, cap=MAX_PARTICLES):
    """Particles of a fluid function's emitter: what DROPLET_LIFETIME seconds of its
    fullest flow emit, at least its JSON droplet_pool, at most `cap`."""
    e = fn["effect"]
    top = max(e["e_lo"], e["e_hi"])
    rate = top / 60.0 / e["droplet_volume_l"] if e["droplet_volume_l"] > 0 and top > 0 else 0.0
    want = int(math.ceil(rate * DROPLET_LIFETIME))
    if hint is not None:
        return max(1, int(hint))
    pool = fn.get("droplet_pool") or 0
    return max(1, min(max(want, pool, 16), cap))


def armature_for(kp, kv, ks, h):
    """Rotor inertia for a joint whose servo (kp, kv) and spring ks must stay stable at
    substep h (the MuJoCo target's rule: omega h <= 0.4 and kv h <= inertia). An upper
    bound: the part's own inertia is not subtracted (Genesis adds it itself)."""
    k = max(0.0, kp) + max(0.0, ks)
    need = max(k * (h / OMEGA_DT_MAX) ** 2, max(0.0, kv) * h)
    return need


def spring_target_offset(kp, ks, rest):
    """Target shift that makes a PD drive plus Genesis' spring (pulling to 0) behave as
    the drive plus a spring pulling to `rest`: kp (x + ks rest / kp - q) - ks q
    = kp (x - q) - ks (q - rest)."""
    if kp <= 0 or ks == 0 or rest == 0:
        return 0.0
    return ks * rest / kp


def prop_positions(outlet, axis, reach, count, radius=PROP_RADIUS, floor_z=0.0):
    """Points on an airflow cone's axis for `count` props: evenly between the outlet and
    the reach, skipping any that would touch the floor."""
    a = vnormalized(axis)
    out = []
    for k in range(1, count + 1):
        d = reach * k / (count + 1)
        if d < 2 * radius:
            continue
        p = vadd(outlet, vscale(a, d))
        if p[2] < floor_z + radius:
            continue
        out.append(p)
    return out


def sphere_area(radius):
    return math.pi * radius * radius


def aabb_area(lower, upper):
    """Cross-section for a body known only by its bounding box: the bounding sphere's
    disc halved, as the MuJoCo target does for meshes."""
    r = 0.5 * vnorm(vsub(upper, lower))
    return 0.5 * math.pi * r * r


def union_aabb(boxes):
    lo = [min(b[0][k] for b in boxes) for k in range(3)]
    hi = [max(b[1][k] for b in boxes) for k in range(3)]
    return lo, hi


def padded(lower, upper, pad):
    return [c - pad for c in lower], [c + pad for c in upper]


def camera_pose(points):
    """(camera_pos, camera_lookat) that frame the given object-frame points."""
    if not points:
        return (1.0, -1.3, 0.9), (0.0, 0.0, 0.2)
    n = float(len(points))
    c = [sum(p[k] for p in points) / n for k in range(3)]
    extent = max([vnorm(vsub(p, c)) for p in points] + [0.15])
    d = max(0.8, 4.0 * extent)
    view = vnormalized([1.0, -1.3, 0.9])
    pos = vadd(c, vscale(view, d))
    return tuple(pos), tuple(c)


def droplet_leads(speed, dt, n):
    """Distances along the stream of a step's n droplets, as if emitted evenly during
    the step (the MuJoCo binding's spacing)."""
    return [speed * dt * (float(e) / n) for e in range(n)]


def kept_links(table):
    """Links the URDF loader must not merge away: every joint's link and every function's
    effector and site link (Genesis merges fixed-joint links by default)."""
    names = []
    for j in table["joints"]:
        names += [j["link"], j["parent_link"]]
    for fn in table["functions"]:
        names.append(fn["effector"]["link"])
        if fn.get("site"):
            names += [fn["site"]["link"], fn["site"]["parent_link"]]
    seen = []
    for n in names:
        if n not in seen:
            seen.append(n)
    return seen


def to_floats(values):
    """A 1-D tensor (or sequence) as a list of floats."""
    return [float(v) for v in values]


def to_rows(values):
    """A 2-D tensor (or sequence of sequences) as a list of lists of floats."""
    return [[float(v) for v in row] for row in values]


# ---------------------------------------------------------------------------
# Command line

def parse_args(argv, prog):
    parser = argparse.ArgumentParser(
        prog=prog,
        description="Run the object in Genesis %s with its efc function templates." % GENESIS_VERSION)
    efc.add_run_arguments(parser, headless_help="no viewer window")
    parser.add_argument("--backend", choices=("cpu", "gpu"), default="cpu",
                        help="Genesis backend (default cpu; gpu falls back to cpu when none is found)")
    parser.add_argument("--precision", choices=("32", "64"), default="32",
                        help="Genesis float precision (default 32)")
    parser.add_argument("--substeps", type=int, default=None,
                        help="physics substeps per step (default 1; with fluids, what keeps SPH stable)")
    parser.add_argument("--lamp-light", choices=("on", "off"), default="on",
                        help="a point light at each illumination site, at the range's brightest, for the "
                             "whole run (Genesis cannot switch lights after build; default on)")
    parser.add_argument("--no-props", action="store_true",
                        help="do not add floating props inside the airflow cones")
    parser.add_argument("--props", type=int, default=3, help="props per airflow cone (default 3)")
    parser.add_argument("--max-particles", type=int, default=None,
                        help="particles per fluid emitter (default: %g s of the fullest flow, at most %d)"
                             % (DROPLET_LIFETIME, MAX_PARTICLES))
    parser.add_argument("--fast", action="store_true",
                        help="viewer: run as fast as possible instead of at most real time")
    parser.add_argument("--log-level", default="warning",
                        choices=("debug", "info", "warning", "error"), help="Genesis' logging level")
    return parser.parse_args(argv)


class UsageError(Exception):
    pass


def check_args(args):
    if args.substeps is not None and args.substeps < 1:
        raise UsageError("--substeps must be >= 1")
    if args.props < 0:
        raise UsageError("--props must be >= 0")
    if args.max_particles is not None and args.max_particles < 1:
        raise UsageError("--max-particles must be >= 1")


# ---------------------------------------------------------------------------
# The run

class Say:
    def __init__(self, prog):
        self.prog = prog
        self.once = set()

    def __call__(self, message):
        print("%s: %s" % (self.prog, message), file=sys.stderr)

    def warn(self, message, key=None):
        if key is not None:
            if key in self.once:
                return
            self.once.add(key)
        self("warning: " + message)


def main(argv, object_name, urdf_file, functions_file):
    """The script's command line (argv without the program name); returns the exit status:
    0 ok, 1 the simulation or the functions file failed, 2 usage or I/O error."""
    prog = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "efc_genesis"
    say = Say(prog)
    try:
        args = parse_args(argv, prog)
    except SystemExit as e:  # argparse printed help or a usage error
        return e.code if isinstance(e.code, int) else 2
    try:
        check_args(args)
    except UsageError as e:
        say(str(e))
        return 2
    functions_path = os.path.join(_HERE, functions_file)  # the object's files sit next to the script
    urdf_path = os.path.join(_HERE, urdf_file)
    try:
        table = efc.load_functions(functions_path)
    except efc.EfcError as e:
        say(e.message)
        return 2 if e.io_error else 1
    if not os.path.isfile(urdf_path):
        say("cannot read the object's URDF '%s'" % urdf_path)
        return 2
    try:
        run = efc.run_settings(args, table)
    except efc.EfcError as e:
        say(e.message)
        return e.status
    for w in run.warnings:
        say.warn(w)
    dt, steps, duration, profile = run.dt, run.steps, run.duration, run.profile

    try:
        import genesis as gs
    except ImportError as e:
        say("cannot import Genesis (%s); install it: %s" % (e, INSTALL_HINT))
        return 2
    version = str(getattr(gs, "__version__", "?"))
    if not version.startswith("0.4."):
        say.warn("this script was written for Genesis %s; found %s" % (GENESIS_VERSION, version))

    run = Run(args, table, object_name, urdf_path, dt, steps, duration, profile, say)
    try:
        run.build()
        run.loop()
    except gs.GenesisException as e:
        if run.viewer and "viewer closed" in str(e).lower():  # the user closed the window: a normal stop
            say("viewer closed at t = %.4g s" % run.t)
            return 0 if run.write_csv() else 2
        hint = ""
        if run.viewer and "display" in str(e).lower():
            hint = " (run with --headless where there is no display)"
        say("Genesis: %s%s" % (e, hint))
        run.write_csv()
        return 1
    except efc.EfcError as e:
        say(e.message)
        return 2 if e.io_error else 1
    except KeyboardInterrupt:
        say("interrupted at t = %.4g s" % run.t)
        return 130 if run.write_csv() else 2
    return 0 if run.write_csv() else 2


class Run:
    """One Genesis scene with the object and its templates."""

    def __init__(self, args, table, object_name, urdf_path, dt, steps, duration, profile, say):
        self.args = args
        self.table = table
        self.object_name = object_name
        self.urdf_path = urdf_path
        self.dt = dt
        self.steps = steps
        self.duration = duration
        self.profile = profile
        self.say = say
        self.functions = table["functions"]
        self.joints = table["joints"]
        self.tpl = efc.Templates(table)
        self.log = efc.CsvLog(table, self.tpl)
        self.t = 0.0
        self.viewer = not args.headless
        self.meters = {}      # fluid function index -> efc.FlowMeter
        self.emitters = {}    # fluid function index -> Emitter
        self.markers = {}     # function index -> (debug node, level, position)
        self.prop_area = {}   # global link index -> cross-section (m^2) of the props we added
        self.csv_written = False

    # -- scene ------------------------------------------------------------------

    def build(self):
        import genesis as gs

        args, table = self.args, self.table
        gs.init(backend=gs.gpu if args.backend == "gpu" else gs.cpu, precision=args.precision,
                logging_level=args.log_level)

        fluid = [i for i, fn in enumerate(self.functions) if fn["effect"]["kind"] == "fluid"]
        self.particle_size = None
        substeps = args.substeps if args.substeps is not None else 1
        sph_options = None
        if fluid:
            # One SPH solver for the scene: its particle size from the smallest droplet.
            self.particle_size = sph_particle_size(
                min(self.functions[i]["effect"]["droplet_volume_l"] for i in fluid))
            if args.substeps is None:
                substeps = fluid_substeps(self.dt, self.particle_size)
            lower, upper = sph_bounds([self.functions[i]["site"]["point"] for i in fluid])
            sph_options = gs.options.SPHOptions(particle_size=self.particle_size,
                                                lower_bound=lower, upper_bound=upper)
        self.substeps = substeps
        self.substep_dt = self.dt / substeps

        lights = [gs.options.vis.DirectionalLight(dir=(-1.0, -1.0, -1.0), color=(1.0, 1.0, 1.0),
                                                  intensity=5.0)]
        if args.lamp_light == "on":
            for fn in self.functions:
                if fn["effect"]["kind"] == "illumination":
                    top = max(fn["effect"]["e_lo"], fn["effect"]["e_hi"])
                    lights.append(gs.options.vis.PointLight(
                        pos=tuple(fn["site"]["point"]), color=light_rgb(fn["color"]),
                        intensity=lumens_to_candela(top)))
        points = [j["origin"] for j in self.joints] + \
                 [fn["site"]["point"] for fn in self.functions if fn.get("site")]
        camera_pos, camera_lookat = camera_pose(points)
        max_fps = None if args.fast else max(1, int(round(1.0 / self.dt)))

        scene: "gs.Scene" = gs.Scene(
            sim_options=gs.options.SimOptions(dt=self.dt, substeps=substeps),
            rigid_options=gs.options.RigidOptions(enable_self_collision=False),
            sph_options=sph_options,
            vis_options=gs.options.VisOptions(lights=lights),
            viewer_options=gs.options.ViewerOptions(camera_pos=camera_pos, camera_lookat=camera_lookat,
                                                    camera_fov=40.0, max_FPS=max_fps),
            show_viewer=self.viewer,
        )
        self.scene = scene
        scene.add_entity(gs.morphs.Plane())
        # The object: its root welded to the world; fixed links named in the functions file
        # kept (Genesis merges fixed-joint links by default); no default rotor inertia (each
        # joint gets what its drive needs after build).
        obj: "RigidEntity" = scene.add_entity(gs.morphs.URDF(
            file=self.urdf_path, fixed=True, links_to_keep=kept_links(table), default_armature=None))
        self.obj = obj

        props = []
        if not args.no_props and args.props > 0:
            for fn in self.functions:
                if fn["effect"]["kind"] != "airflow":
                    continue
                for p in prop_positions(fn["site"]["point"], fn["direction"], fn["reach"], args.props):
                    prop: "RigidEntity" = scene.add_entity(
                        gs.morphs.Sphere(pos=tuple(p), radius=PROP_RADIUS),
                        material=gs.materials.Rigid(rho=PROP_DENSITY, gravity_compensation=1.0),
                        surface=gs.surfaces.Default(color=PROP_RGBA))
                    props.append(prop)

        for i in fluid:
            fn = self.functions[i]
            hint = args.max_particles
            emitter: "Emitter" = scene.add_emitter(
                material=gs.materials.SPH.Liquid(
                    sampler="regular", mu=sph_viscosity(self.particle_size, self.substep_dt)),
                max_particles=particle_pool(fn, hint),
                surface=gs.surfaces.Default(color=WATER_RGBA, vis_mode="particle"))
            self.emitters[i] = emitter
            self.meters[i] = efc.FlowMeter(window=0.5, dt=self.dt)

        scene.build()

        for prop in props:
            body: "RigidEntity" = prop
            for link in body.links:
                lk: "RigidLink" = link
                self.prop_area[lk.idx] = sphere_area(PROP_RADIUS)
        self._bind()
        self._set_gains()
        self._set_initial()

    def _bind(self):
        obj = self.obj
        self.dof = {}
        for j in self.joints:
            joint: "RigidJoint" = obj.get_joint(name=j["joint"])
            self.dof[j["joint"]] = joint.dofs_idx_local[0]
        self.joint_of = {j["joint"]: j for j in self.joints}
        self.all_joints = [j["joint"] for j in self.joints]
        self.all_dofs = [self.dof[n] for n in self.all_joints]
        self.effector_link = {}
        self.site_link = {}
        for i, fn in enumerate(self.functions):
            self.effector_link[i] = obj.get_link(name=fn["effector"]["link"])
            if fn.get("site"):
                self.site_link[i] = obj.get_link(name=fn["site"]["link"])
        # Bodies the air can push: every link of a rigid entity whose base is not welded
        # to the world (the props, anything a user adds); the object itself never.
        from genesis.engine.entities import RigidEntity

        self.air_links = []
        self.air_areas = []
        if any(fn["effect"]["kind"] == "airflow" for fn in self.functions):
            for entity in self.scene.entities:
                if not isinstance(entity, RigidEntity):
                    continue
                rigid: "RigidEntity" = entity
                base: "RigidLink" = rigid.base_link
                if base.is_fixed:
                    continue
                for link in rigid.links:
                    lk: "RigidLink" = link
                    area = self.prop_area.get(lk.idx)
                    if area is None:
                        area = self._link_area(lk)
                    if area > 0:
                        self.air_links.append(lk.idx)
                        self.air_areas.append(area)

    def _link_area(self, link: "RigidLink"):
        boxes = []
        for geom in link.geoms:
            g: "RigidGeom" = geom
            boxes.append(to_rows(g.get_AABB()))
        if not boxes:
            return 0.0
        lower, upper = union_aabb(boxes)
        return aabb_area(lower, upper)

    def _drive_of(self, name):
        """(kp, kv) of a joint's position servo, or None when nothing drives it."""
        j = self.joint_of[name]
        if j["drive_by"] == "function" or (j["drive_by"] == "profile" and self.profile is not None):
            if j["drive"] is not None:
                return j["drive"]["kp"], j["drive"]["kv"]
        return None

    def _set_gains(self):
        obj = self.obj
        names = self.all_joints
        self.target_offset = {}
        self.profile_joints = efc.profile_joints(self.table) if self.profile is not None else []
        self.profile_dofs = [self.dof[j["joint"]] for j in self.profile_joints]
        if not names:
            return
        dofs = self.all_dofs
        springs = [self.joint_of[n]["spring"] for n in names]
        ks = [s["stiffness"] if s else 0.0 for s in springs]
        obj.set_dofs_stiffness(stiffness=ks, dofs_idx_local=dofs)
        obj.set_dofs_damping(damping=[self.joint_of[n]["damping"] for n in names], dofs_idx_local=dofs)
        obj.set_dofs_frictionloss(frictionloss=[self.joint_of[n]["friction"] for n in names],
                                  dofs_idx_local=dofs)
        armature = []
        driven, kps, kvs = [], [], []
        for n, k in zip(names, ks):
            drive = self._drive_of(n)
            kp, kv = drive if drive is not None else (0.0, 0.0)
            armature.append(armature_for(kp, kv, k, self.substep_dt))
            rest = self.joint_of[n]["spring"]["rest"] if self.joint_of[n]["spring"] else 0.0
            if drive is not None:
                driven.append(self.dof[n])
                kps.append(kp)
                kvs.append(kv)
                self.target_offset[n] = spring_target_offset(kp, k, rest)
            elif k != 0 and rest != 0:
                # Genesis' joint springs pull to the joint's zero: a constant force moves
                # the rest position of an undriven joint.
                obj.control_dofs_force(force=[k * rest], dofs_idx_local=[self.dof[n]])
        obj.set_dofs_armature(armature=armature, dofs_idx_local=dofs)
        if driven:
            obj.set_dofs_kp(kp=kps, dofs_idx_local=driven)
            obj.set_dofs_kv(kv=kvs, dofs_idx_local=driven)

    def _profile_targets(self, t):
        return {j["joint"]: efc.profile_target(self.profile, j["part"], j["lo"], j["hi"], j["initial"],
                                               t, self.duration)
                for j in self.profile_joints}

    def _set_initial(self):
        obj = self.obj
        start = {j["joint"]: j["initial"] for j in self.joints}
        start.update(self._profile_targets(0.0))
        if self.all_joints:
            obj.set_dofs_position(position=[start[n] for n in self.all_joints],
                                  dofs_idx_local=self.all_dofs, zero_velocity=True)
        self.tpl.reset(self._read_positions())

    # -- per step ---------------------------------------------------------------

    def _read_positions(self):
        if not self.all_dofs:
            return {}
        q = to_floats(self.obj.get_dofs_position(dofs_idx_local=self.all_dofs))
        return dict(zip(self.all_joints, q))

    def _drive_profile(self, t):
        if not self.profile_joints:
            return
        targets = self._profile_targets(t)
        self.obj.control_dofs_position(
            position=[targets[j["joint"]] + self.target_offset.get(j["joint"], 0.0) for j in self.profile_joints],
            dofs_idx_local=self.profile_dofs)

    def loop(self):
        started = time.time()
        for k in range(self.steps + 1):
            t = k * self.dt  # exact grid, as efc play
            self.t = t
            self._drive_profile(t)
            positions = self._read_positions()
            emits = self.tpl.step(positions, self.dt)
            measured = self._realise(emits, positions)
            self.log.add(t, measured)
            if k == self.steps:
                break
            self.scene.step()
        wall = time.time() - started
        self.say("%d steps (%.4g s simulated) in %.3g s" % (self.steps, self.steps * self.dt, wall))

    def _realise(self, emits, positions):
        """Realises every function's output; returns measured per function."""
        measured = []
        targets, target_dofs = [], []
        forces = None
        for i, fn in enumerate(self.functions):
            kind = fn["effect"]["kind"]
            out = self.tpl.output[i]
            value = out
            if kind == "geometry":
                name = fn["effector"]["joint"]
                targets.append(out + self.target_offset.get(name, 0.0))
                target_dofs.append(self.dof[name])
                value = positions[name]
            elif kind == "illumination":
                if self.viewer:
                    self._light_marker(i, fn, out)
            elif kind == "temperature":
                if self.viewer:
                    self._glow(i, fn, out)
            elif kind == "fluid":
                value = self._fluid(i, fn, emits[i])
            elif kind == "airflow":
                value = efc.air_speed_at(out, 0.0, 0.0, fn["cone_angle"], fn["reach"])
                if out != 0 and self.air_links:
                    forces = self._airflow(i, fn, out, forces)
            measured.append(value)
        if targets:
            self.obj.control_dofs_position(position=targets, dofs_idx_local=target_dofs)
        if forces is not None:
            rows = [forces[n] for n in range(len(self.air_links))]
            solver: "RigidSolver" = self.scene.rigid_solver
            solver.apply_links_external_force(force=rows, links_idx=self.air_links, ref="link_com")
        return measured

    def _site_frame(self, i, fn):
        """(site point, unit direction) in the world: the site link's position and the
        functions file's direction turned with the effector link."""
        site: "RigidLink" = self.site_link[i]
        effector: "RigidLink" = self.effector_link[i]
        point = to_floats(site.get_pos())
        direction = fn.get("direction") or [0.0, 0.0, 1.0]
        axis = vnormalized(quat_rotate(to_floats(effector.get_quat()), direction))
        return point, axis

    def _fluid(self, i, fn, n):
        emitter: "Emitter" = self.emitters[i]
        spawned = 0
        if n > 0:
            point, axis = self._site_frame(i, fn)
            speed = fn["speed"]
            for lead in droplet_leads(speed, self.dt, n):
                before = emitter.next_particle
                try:
                    emitter.emit(droplet_shape="sphere", droplet_size=self.particle_size,
                                 droplet_length=self.particle_size, pos=tuple(vadd(point, vscale(axis, lead))),
                                 direction=tuple(axis), speed=speed)
                except Exception as e:  # gs.GenesisException: outside the SPH domain, pool too small
                    self.say.warn("fluid '%s': a droplet was not emitted: %s" % (fn["name"], e),
                                  key=("emit", i))
                    continue
                after = emitter.next_particle
                # One particle per droplet (sphere of one particle size, regular sampler);
                # the emitter restarts its pool at 0 when it wraps.
                spawned += after - before if after > before else 1
        meter = self.meters[i]
        meter.add(self.t, spawned)
        return meter.flow(self.t, fn["effect"]["droplet_volume_l"])

    def _airflow(self, i, fn, out, forces):
        if forces is None:
            forces = [[0.0, 0.0, 0.0] for _ in self.air_links]
        outlet, axis = self._site_frame(i, fn)
        solver: "RigidSolver" = self.scene.rigid_solver
        centres = to_rows(solver.get_links_pos(links_idx=self.air_links, ref="link_com"))
        for n, (c, area) in enumerate(zip(centres, self.air_areas)):
            f = efc.airflow_force(fn, out, outlet, axis, c, area)
            forces[n] = vadd(forces[n], f)
        return forces

    # -- what only the viewer shows ----------------------------------------------

    def _replace_marker(self, i, draw, lvl, where):
        old = self.markers.get(i)
        if old is not None and old[1] == lvl and vnorm(vsub(old[2], where)) < MARKER_MOVE:
            return
        scene: "gs.Scene" = self.scene
        if old is not None and old[0] is not None:
            scene.clear_debug_object(old[0])
        node = draw() if lvl > 0 else None
        self.markers[i] = (node, lvl, where)

    def _light_marker(self, i, fn, out):
        f = illumination_fraction(fn, out)
        lvl = level(f)
        site: "RigidLink" = self.site_link[i]
        where = to_floats(site.get_pos())
        rgb = light_rgb(fn["color"])
        color = (rgb[0], rgb[1], rgb[2], 0.2 + 0.8 * lvl / MARKER_LEVELS)
        scene: "gs.Scene" = self.scene
        self._replace_marker(i, lambda: scene.draw_debug_sphere(pos=where, radius=MARKER_RADIUS, color=color),
                             lvl, where)

    def _glow(self, i, fn, out):
        f = efc.glow_fraction(fn, out)
        lvl = level(f)
        link: "RigidLink" = self.effector_link[i]
        where = to_floats(link.get_pos())
        old = self.markers.get(i)
        if old is not None and old[1] == lvl and vnorm(vsub(old[2], where)) < MARKER_MOVE:
            return
        boxes = []
        for geom in link.geoms:
            g: "RigidGeom" = geom
            boxes.append(to_rows(g.get_AABB()))
        if not boxes:  # a part without collision geometry: glow at its site instead
            site: "RigidLink" = self.site_link[i]
            c = to_floats(site.get_pos())
            boxes = [[vsub(c, [0.02] * 3), vadd(c, [0.02] * 3)]]
        lower, upper = padded(*union_aabb(boxes), GLOW_PAD)
        color = (efc.HOT_RGB[0], efc.HOT_RGB[1], efc.HOT_RGB[2], GLOW_ALPHA * lvl / MARKER_LEVELS)
        scene: "gs.Scene" = self.scene
        self._replace_marker(i, lambda: scene.draw_debug_box(bounds=[lower, upper], color=color, wireframe=False),
                             lvl, where)

    # -- output -----------------------------------------------------------------

    def write_csv(self):
        """Writes the CSV (when asked) once; False on an I/O error."""
        if not self.args.csv or self.csv_written:
            return True
        self.csv_written = True
        try:
            self.log.write(self.args.csv)
        except efc.EfcError as e:
            self.say(e.message)
            return False
        return True
