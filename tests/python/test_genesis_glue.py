"""Tests of the Genesis glue (efc_genesis.py) that run without Genesis.

    python3 -m unittest backends/genesis/test_efc_genesis.py      (from the repository root)

Three kinds: the pure helpers (math, units, cones, SPH sizing); the command line
(--help and user errors with no simulator installed); and a run of main() against a
small stand-in for the `genesis` package (StubGenesis below). The stand-in keeps the
parameter names of the Genesis 0.4.5 methods the glue calls (a wrong keyword fails
here as it would there) and realises joints as ideal servos, so the run's s_R and s_E
must equal efc_templates' replay. What only the real Genesis can show (dynamics, SPH,
rendering) is listed in NOTES.md.
"""
import contextlib
import importlib.util
import io
import json
import math
import os
import sys
import tempfile
import types
import unittest
import xml.etree.ElementTree as ET

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(REPO, "backends", "genesis")
sys.path.insert(0, os.path.join(REPO, "backends", "python"))

import efc_templates as efc  # noqa: E402


def load_glue():
    spec = importlib.util.spec_from_file_location("efc_genesis", os.path.join(HERE, "efc_genesis.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


G = load_glue()


# ---------------------------------------------------------------------------
# A small object with all five effects (URDF + functions file), written to a temp dir.

URDF = """<?xml version="1.0"?>
<robot name="gadget">
  <link name="base"><visual><geometry><box size="0.3 0.2 0.2"/></geometry></visual></link>
  <joint name="button" type="prismatic">
    <parent link="base"/><child link="button"/>
    <origin xyz="0.1 0 0.2" rpy="0 0 0"/><axis xyz="0 0 -1"/>
    <limit lower="0" upper="0.01" effort="1000" velocity="100"/>
  </joint>
  <link name="button"/>
  <joint name="lid" type="revolute">
    <parent link="base"/><child link="lid"/>
    <origin xyz="0 0 0.2" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="1.5" effort="1000" velocity="100"/>
  </joint>
  <link name="lid"/>
  <joint name="bulb" type="fixed"><parent link="base"/><child link="bulb"/><origin xyz="0 0 0.3" rpy="0 0 0"/></joint>
  <link name="bulb"/>
  <joint name="light_site_joint" type="fixed"><parent link="bulb"/><child link="light_site"/><origin xyz="0 0 0.02" rpy="0 0 0"/></joint>
  <link name="light_site"/>
  <joint name="heat_site_joint" type="fixed"><parent link="base"/><child link="heat_site"/><origin xyz="0 0 0.1" rpy="0 0 0"/></joint>
  <link name="heat_site"/>
  <joint name="water_site_joint" type="fixed"><parent link="base"/><child link="water_site"/><origin xyz="0.2 0 0.25" rpy="3.141592653589793 0 0"/></joint>
  <link name="water_site"/>
  <joint name="air_site_joint" type="fixed"><parent link="base"/><child link="air_site"/><origin xyz="0 -0.1 0.2" rpy="1.5707963267948966 0 0"/></joint>
  <link name="air_site"/>
</robot>
"""


def mapping(kind, e_lo, e_hi, **over):
    m = {"kind": kind, "r_lo": 0.0, "r_hi": 0.01, "e_lo": e_lo, "e_hi": e_hi, "threshold": 0.008,
         "hysteresis": 0.0005, "latching": False, "gain": (e_hi - e_lo) / 0.01, "offset": e_lo,
         "delta": 2.0, "initial": e_lo}
    m.update(over)
    return m


def function(name, kind, effector, m, e_lo, e_hi, site=None, **fields):
    fn = {"name": name,
          "receptor": {"part": "button", "link": "button", "joint": "button"},
          "effector": {"part": effector, "link": effector, "joint": effector if kind == "geometry" else None},
          "mapping": m,
          "effect": {"kind": kind, "e_lo": e_lo, "e_hi": e_hi, "time_constant": 0.5 if kind == "temperature" else 0.0,
                     "droplet_volume_l": 2.68e-4 if kind == "fluid" else 0.0},
          "unit": {"geometry": "rad", "illumination": "lm", "temperature": "C", "fluid": "L/min",
                   "airflow": "m/s"}[kind],
          "site": site, "direction": None, "color": None, "speed": None, "droplet_radius": None,
          "droplet_pool": None, "cone_angle": None, "reach": None, "glow_max": None, "drive": None}
    fn.update(fields)
    return fn


def site(link, parent, xyz, rpy, point):
    return {"link": link, "parent_link": parent, "xyz": xyz, "rpy": rpy, "point": point}


TABLE = {
    "format": "efc-functions", "version": 1, "object": "gadget", "description": None,
    "urdf": "gadget.urdf", "root_link": "base", "timestep": 0.002,
    "joints": [
        {"part": "button", "joint": "button", "link": "button", "parent_link": "base", "type": "prismatic",
         "lo": 0.0, "hi": 0.01, "initial": 0.0, "axis": [0.0, 0.0, -1.0], "origin": [0.1, 0.0, 0.2],
         "drive_by": "profile", "drive": {"kp": 200.0, "kv": 2.0},
         "spring": {"stiffness": 50.0, "rest": 0.002}, "damping": 0.1, "friction": 0.0},
        {"part": "lid", "joint": "lid", "link": "lid", "parent_link": "base", "type": "revolute",
         "lo": 0.0, "hi": 1.5, "initial": 0.0, "axis": [0.0, 1.0, 0.0], "origin": [0.0, 0.0, 0.2],
         "drive_by": "function", "drive": {"kp": 100.0, "kv": 1.0}, "spring": None,
         "damping": 0.0, "friction": 0.2},
    ],
    "functions": [
        function("open", "geometry", "lid", mapping("step", 0.0, 1.2), 0.0, 1.2,
                 drive={"kp": 100.0, "kv": 1.0}),
        function("light", "illumination", "bulb", mapping("binary", 0.0, 450.0, latching=True), 0.0, 450.0,
                 site=site("light_site", "bulb", [0.0, 0.0, 0.02], [0.0, 0.0, 0.0], [0.0, 0.0, 0.32]),
                 color=[1.0, 0.9, 0.7]),
        function("heat", "temperature", "base", mapping("step", 20.0, 200.0), 20.0, 200.0,
                 site=site("heat_site", "base", [0.0, 0.0, 0.1], [0.0, 0.0, 0.0], [0.0, 0.0, 0.1]),
                 glow_max=300.0),
        function("water", "fluid", "base", mapping("linear", 0.0, 6.0), 0.0, 6.0,
                 site=site("water_site", "base", [0.2, 0.0, 0.25], [math.pi, 0.0, 0.0], [0.2, 0.0, 0.25]),
                 direction=[0.0, 0.0, -1.0], speed=1.0, droplet_radius=0.004, droplet_pool=100),
        function("air", "airflow", "base", mapping("cumulative", 0.0, 6.0, initial=0.0), 0.0, 6.0,
                 site=site("air_site", "base", [0.0, -0.1, 0.2], [math.pi / 2, 0.0, 0.0], [0.0, -0.1, 0.2]),
                 direction=[0.0, -1.0, 0.0], cone_angle=0.5, reach=1.0),
    ],
}


def write_object(folder):
    with open(os.path.join(folder, "gadget.urdf"), "w") as f:
        f.write(URDF)
    with open(os.path.join(folder, "gadget_functions.json"), "w") as f:
        json.dump(TABLE, f)
    return os.path.join(folder, "gadget.urdf"), os.path.join(folder, "gadget_functions.json")


# ---------------------------------------------------------------------------
# A stand-in for the genesis package: the calls the glue makes, with Genesis 0.4.5's
# parameter names, ideal servos and a record of what was asked.

class GenesisException(Exception):
    pass


class Options:
    def __init__(self, **kw):
        self.__dict__.update(kw)


def options_class(name, fields):
    def __init__(self, **kw):
        for k in kw:
            if k not in fields:
                raise TypeError("%s has no field '%s'" % (name, k))
        Options.__init__(self, **kw)
    return type(name, (Options,), {"__init__": __init__})


class StubGenesis:
    """Builds the fake `genesis` modules; `record` holds what the glue asked for."""

    def __init__(self, close_viewer_after=None):
        self.record = {"scenes": [], "init": None}
        self.close_viewer_after = close_viewer_after  # steps after which the "user" closes the viewer

    def modules(self):
        rec = self.record
        gs = types.ModuleType("genesis")
        gs.__version__ = "0.4.5"
        gs.cpu, gs.gpu = "cpu", "gpu"
        gs.GenesisException = GenesisException

        def init(*, backend=None, precision="32", logging_level=None, debug=False, seed=None, eps=1e-15,
                 theme="dark", logger_verbose_time=False, performance_mode=False):
            rec["init"] = dict(backend=backend, precision=precision, logging_level=logging_level)
        gs.init = init

        options = types.ModuleType("genesis.options")
        options.SimOptions = options_class("SimOptions", {"dt", "substeps", "gravity"})
        options.RigidOptions = options_class("RigidOptions", {"enable_self_collision", "dt", "gravity"})
        options.SPHOptions = options_class("SPHOptions", {"particle_size", "lower_bound", "upper_bound"})
        options.VisOptions = options_class("VisOptions", {"lights", "shadow"})
        options.ViewerOptions = options_class("ViewerOptions", {"camera_pos", "camera_lookat", "camera_fov",
                                                                "max_FPS", "res"})
        vis = types.ModuleType("genesis.options.vis")
        vis.DirectionalLight = options_class("DirectionalLight", {"dir", "color", "intensity"})
        vis.PointLight = options_class("PointLight", {"pos", "color", "intensity"})
        options.vis = vis
        gs.options = options

        morphs = types.ModuleType("genesis.morphs")
        morphs.Plane = options_class("Plane", {"pos"})
        morphs.URDF = options_class("URDF", {"file", "fixed", "links_to_keep", "default_armature",
                                             "merge_fixed_links", "pos"})
        morphs.Sphere = options_class("Sphere", {"pos", "radius", "fixed"})
        gs.morphs = morphs
        materials = types.ModuleType("genesis.materials")
        materials.Rigid = options_class("Rigid", {"rho", "gravity_compensation", "friction"})
        sph = types.ModuleType("genesis.materials.SPH")
        sph.Liquid = options_class("Liquid", {"sampler", "mu", "rho", "stiffness"})
        materials.SPH = sph
        gs.materials = materials
        surfaces = types.ModuleType("genesis.surfaces")
        surfaces.Default = options_class("Default", {"color", "vis_mode"})
        gs.surfaces = surfaces

        stub = self

        class Scene:
            def __init__(self, sim_options=None, coupler_options=None, tool_options=None, rigid_options=None,
                         kinematic_options=None, mpm_options=None, sph_options=None, fem_options=None,
                         sf_options=None, pbd_options=None, vis_options=None, viewer_options=None,
                         profiling_options=None, renderer=None, show_viewer=None, show_FPS=None):
                self.sim_options, self.rigid_options, self.sph_options = sim_options, rigid_options, sph_options
                self.vis_options, self.viewer_options, self.show_viewer = vis_options, viewer_options, show_viewer
                self._entities, self.emitters_list, self.built = [], [], False
                self.debug, self.cleared, self.steps = [], [], 0
                self.solver = RigidSolver(self)
                rec["scenes"].append(self)

            def add_entity(self, morph, material=None, surface=None, visualize_contact=False, vis_mode=None,
                           name=None):
                assert not self.built
                e = Entity(self, morph, material)
                self._entities.append(e)
                return e

            def add_emitter(self, material, max_particles=20000, surface=None):
                assert not self.built
                em = Emitter(max_particles, material)
                self.emitters_list.append(em)
                return em

            def build(self, n_envs=0, env_spacing=(0.0, 0.0), n_envs_per_row=None, center_envs_at_origin=True,
                      compile_kernels=None):
                self.built = True
                self.solver.links = [l for e in self._entities for l in e.links]
                for n, l in enumerate(self.solver.links):
                    l.idx = n

            def step(self, update_visualizer=True, refresh_visualizer=True):
                assert self.built
                if self.show_viewer and stub.close_viewer_after is not None and self.steps >= stub.close_viewer_after:
                    raise GenesisException("Viewer closed.")
                self.steps += 1
                self.solver.forces = {}

            @property
            def entities(self):
                return self._entities

            @property
            def rigid_solver(self):
                return self.solver

            def draw_debug_sphere(self, pos, radius=0.01, color=(1.0, 0.0, 0.0, 0.5)):
                node = ("sphere", tuple(pos), radius, tuple(color))
                self.debug.append(node)
                return node

            def draw_debug_box(self, bounds, color=(1.0, 0.0, 0.0, 1.0), wireframe=True, wireframe_radius=0.0015):
                node = ("box", tuple(map(tuple, bounds)), tuple(color), wireframe)
                self.debug.append(node)
                return node

            def clear_debug_object(self, obj):
                self.cleared.append(obj)

        class RigidSolver:
            def __init__(self, scene):
                self.scene, self.links, self.forces, self.applied = scene, [], {}, []

            def get_links_pos(self, links_idx=None, envs_idx=None, *, ref="link_origin"):
                assert ref in ("link_origin", "link_com", "root_com")
                return [list(self.links[i].pos) for i in links_idx]

            def apply_links_external_force(self, force, links_idx=None, envs_idx=None, *, ref="link_origin",
                                           local=False):
                assert len(force) == len(links_idx)
                for f, i in zip(force, links_idx):
                    self.forces[i] = f
                self.applied.append((list(links_idx), [list(f) for f in force], ref))

        class Geom:
            def __init__(self, link, half):
                self.link, self.half = link, half

            def get_AABB(self):
                return [[c - self.half for c in self.link.pos], [c + self.half for c in self.link.pos]]

        class Link:
            def __init__(self, name, pos, fixed, geoms=0.0):
                self.name, self.pos, self._fixed, self.idx = name, list(pos), fixed, -1
                self._geoms = [Geom(self, geoms)] if geoms else []

            @property
            def is_fixed(self):
                return self._fixed

            @property
            def geoms(self):
                return self._geoms

            def get_pos(self, envs_idx=None):
                return list(self.pos)

            def get_quat(self, envs_idx=None):
                return [1.0, 0.0, 0.0, 0.0]

        class Joint:
            def __init__(self, name, dof):
                self.name, self.dof = name, dof

            @property
            def dofs_idx_local(self):
                return [self.dof]

        class Entity:
            def __init__(self, scene, morph, material):
                self.morph, self.material = morph, material
                self.joints_, self.links_ = [], []
                kind = type(morph).__name__
                if kind == "URDF":
                    self._load_urdf(morph.file, morph)
                elif kind == "Sphere":
                    self.links_ = [Link("sphere", morph.pos, False, geoms=morph.radius)]
                else:
                    self.links_ = [Link("plane", (0, 0, 0), True)]
                n = len(self.joints_)
                self.q = [0.0] * n
                self.mode = ["force"] * n
                self.target = [0.0] * n
                self.force = [0.0] * n
                self.info = {}

            def _load_urdf(self, path, morph):
                root = ET.parse(path).getroot()
                children = {j.find("child").get("link") for j in root.findall("joint")}
                base = [l.get("name") for l in root.findall("link") if l.get("name") not in children][0]
                origin = {base: (0.0, 0.0, 0.0)}
                fixed_child = {}
                for j in root.findall("joint"):
                    child = j.find("child").get("link")
                    parent = j.find("parent").get("link")
                    xyz = [float(v) for v in j.find("origin").get("xyz").split()]
                    origin[child] = tuple(a + b for a, b in zip(origin[parent], xyz))
                    fixed_child[child] = j.get("type") == "fixed"
                    if j.get("type") != "fixed":
                        self.joints_.append(Joint(j.get("name"), len(self.joints_)))
                keep = set(morph.links_to_keep)
                for l in root.findall("link"):
                    name = l.get("name")
                    if fixed_child.get(name) and name not in keep and getattr(morph, "merge_fixed_links", True):
                        continue  # merged into its parent, as Genesis does
                    self.links_.append(Link(name, origin[name], True, geoms=0.05 if name == base else 0.0))

            @property
            def links(self):
                return self.links_

            @property
            def base_link(self):
                return self.links_[0]

            def get_joint(self, name=None, uid=None):
                for j in self.joints_:
                    if j.name == name:
                        return j
                raise GenesisException("Joint not found for name: %s" % name)

            def get_link(self, name=None, uid=None):
                for l in self.links_:
                    if l.name == name:
                        return l
                raise GenesisException("Link not found for name: %s" % name)

            def _set(self, what, values, dofs_idx_local):
                for v, d in zip(values, dofs_idx_local):
                    self.info.setdefault(what, {})[d] = v

            def set_dofs_kp(self, kp, dofs_idx_local=None, envs_idx=None):
                self._set("kp", kp, dofs_idx_local)

            def set_dofs_kv(self, kv, dofs_idx_local=None, envs_idx=None):
                self._set("kv", kv, dofs_idx_local)

            def set_dofs_stiffness(self, stiffness, dofs_idx_local=None, envs_idx=None):
                self._set("stiffness", stiffness, dofs_idx_local)

            def set_dofs_damping(self, damping, dofs_idx_local=None, envs_idx=None):
                self._set("damping", damping, dofs_idx_local)

            def set_dofs_frictionloss(self, frictionloss, dofs_idx_local=None, envs_idx=None):
                self._set("frictionloss", frictionloss, dofs_idx_local)

            def set_dofs_armature(self, armature, dofs_idx_local=None, envs_idx=None):
                self._set("armature", armature, dofs_idx_local)

            def set_dofs_position(self, position, dofs_idx_local=None, envs_idx=None, *, zero_velocity=True):
                for v, d in zip(position, dofs_idx_local):
                    self.q[d] = v

            def control_dofs_position(self, position, dofs_idx_local=None, envs_idx=None):
                # An ideal servo: the dof is at its target at once.
                for v, d in zip(position, dofs_idx_local):
                    self.mode[d], self.target[d], self.q[d] = "position", v, v

            def control_dofs_force(self, force, dofs_idx_local=None, envs_idx=None):
                for v, d in zip(force, dofs_idx_local):
                    self.mode[d], self.force[d] = "force", v

            def get_dofs_position(self, dofs_idx_local=None, envs_idx=None):
                return [self.q[d] for d in dofs_idx_local]

        class Emitter:
            def __init__(self, max_particles, material):
                self._max, self.material, self._next, self.emitted = max_particles, material, 0, []

            @property
            def next_particle(self):
                return self._next

            @property
            def max_particles(self):
                return self._max

            def emit(self, droplet_shape, droplet_size, droplet_length=None, pos=(0.5, 0.5, 1.0),
                     direction=(0, 0, -1), theta=0.0, speed=1.0, p_size=None):
                assert droplet_shape in ("circle", "sphere", "square", "rectangle")
                self.emitted.append((tuple(pos), tuple(direction), speed, droplet_size, droplet_length))
                self._next += 1
                if self._next + 1 > self._max:
                    self._next = 0

        gs.Scene = Scene
        engine = types.ModuleType("genesis.engine")
        entities = types.ModuleType("genesis.engine.entities")
        entities.RigidEntity = Entity
        entities.Emitter = Emitter
        engine.entities = entities
        gs.engine = engine
        stub.Entity = Entity
        return {"genesis": gs, "genesis.options": options, "genesis.options.vis": vis,
                "genesis.engine": engine, "genesis.engine.entities": entities}


@contextlib.contextmanager
def stub_genesis(**kw):
    stub = StubGenesis(**kw)
    saved = {k: sys.modules.get(k) for k in ("genesis", "genesis.options", "genesis.options.vis",
                                             "genesis.engine", "genesis.engine.entities")}
    sys.modules.update(stub.modules())
    try:
        yield stub
    finally:
        for k, v in saved.items():
            if v is None:
                sys.modules.pop(k, None)
            else:
                sys.modules[k] = v


@contextlib.contextmanager
def no_genesis():
    saved = sys.modules.get("genesis")
    sys.modules["genesis"] = None  # import genesis raises ImportError
    try:
        yield
    finally:
        if saved is None:
            sys.modules.pop("genesis", None)
        else:
            sys.modules["genesis"] = saved


def run_main(argv, folder):
    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        rc = G.main(argv, object_name="gadget", urdf_file=os.path.join(folder, "gadget.urdf"),
                    functions_file=os.path.join(folder, "gadget_functions.json"))
    return rc, out.getvalue(), err.getvalue()


def read_csv(path):
    with open(path) as f:
        lines = f.read().splitlines()
    header = lines[0].split(",")
    rows = [[float(v) for v in line.split(",")] for line in lines[1:]]
    return header, rows


# ---------------------------------------------------------------------------

class PureHelpers(unittest.TestCase):
    def test_quat_rotate(self):
        self.assertEqual(G.quat_rotate([1.0, 0.0, 0.0, 0.0], [1.0, 2.0, 3.0]), [1.0, 2.0, 3.0])
        s = math.sqrt(0.5)
        r = G.quat_rotate([s, 0.0, 0.0, s], [1.0, 0.0, 0.0])  # 90 deg about z
        for a, b in zip(r, [0.0, 1.0, 0.0]):
            self.assertAlmostEqual(a, b, places=12)
        r = G.quat_rotate([s, s, 0.0, 0.0], [0.0, 0.0, 1.0])  # 90 deg about x: z -> -y
        for a, b in zip(r, [0.0, -1.0, 0.0]):
            self.assertAlmostEqual(a, b, places=12)

    def test_vectors(self):
        self.assertEqual(G.vnormalized([0.0, 3.0, 4.0]), [0.0, 0.6, 0.8])
        self.assertEqual(G.vnormalized([0.0, 0.0, 0.0]), [0.0, 0.0, 0.0])
        self.assertEqual(G.vadd([1, 2, 3], [1, 1, 1]), [2, 3, 4])
        self.assertEqual(G.vsub([1, 2, 3], [1, 1, 1]), [0, 1, 2])

    def test_light_units(self):
        self.assertAlmostEqual(G.lumens_to_candela(4 * math.pi * 10), 10.0)
        self.assertEqual(G.lumens_to_candela(-5), 0.0)
        self.assertEqual(G.light_rgb([1.5, -0.2, 0.5]), (1.0, 0.0, 0.5))
        self.assertEqual(G.light_rgb(None), (1.0, 1.0, 1.0))
        fn = TABLE["functions"][1]
        self.assertEqual(G.illumination_fraction(fn, 225.0), 0.5)
        self.assertEqual(G.illumination_fraction(fn, 900.0), 1.0)

    def test_level(self):
        self.assertEqual(G.level(0.0), 0)
        self.assertEqual(G.level(1e-6), 1)
        self.assertEqual(G.level(1.0), G.MARKER_LEVELS)
        self.assertEqual(G.level(0.5), G.MARKER_LEVELS // 2)

    def test_sph_particle_volume_is_the_droplet(self):
        for litres in (1.13e-4, 2.68e-4, 5e-3):
            p = G.sph_particle_size(litres)
            self.assertAlmostEqual(G.SPH_VOLUME_FACTOR * p ** 3, litres * 1e-3, delta=litres * 1e-15)
        with self.assertRaises(ValueError):
            G.sph_particle_size(0.0)

    def test_fluid_substeps_and_viscosity(self):
        p = G.sph_particle_size(1.131e-4)  # a 3 mm droplet
        n = G.fluid_substeps(0.002, p)
        h = 0.002 / n
        self.assertLessEqual(h, G.SPH_REF_SUBSTEP * p / G.SPH_REF_SIZE + 1e-15)
        self.assertEqual(G.fluid_substeps(4e-4, 0.01), 1)  # Genesis' own examples' ratio
        self.assertEqual(G.fluid_substeps(4e-3, 0.01), 10)
        mu = G.sph_viscosity(p, h)
        self.assertLessEqual(h, 0.01 * (2 * p) ** 2 / mu)  # Genesis' stability bound holds
        self.assertEqual(G.sph_viscosity(0.01, 4e-4), G.SPH_DEFAULT_MU)

    def test_sph_bounds(self):
        lo, hi = G.sph_bounds([[0.2, 0.0, 0.25], [-0.1, 0.3, 0.5]])
        self.assertEqual(lo, (-0.1 - G.SPH_MARGIN, -G.SPH_MARGIN, 0.0))
        self.assertEqual(hi, (0.2 + G.SPH_MARGIN, 0.3 + G.SPH_MARGIN, 0.5 + G.SPH_MARGIN))
        lo, _ = G.sph_bounds([[0.0, 0.0, -1.0]])
        self.assertEqual(lo[2], -1.5)

    def test_particle_pool(self):
        fn = TABLE["functions"][3]  # 6 L/min of 2.68e-4 L droplets: 373/s
        rate = 6.0 / 60.0 / 2.68e-4
        self.assertEqual(G.particle_pool(fn), int(math.ceil(rate * G.DROPLET_LIFETIME)))
        self.assertEqual(G.particle_pool(fn, hint=77), 77)
        self.assertEqual(G.particle_pool(fn, cap=500), 500)

    def test_armature(self):
        h = 0.002
        a = G.armature_for(1000.0, 0.0, 0.0, h)
        self.assertAlmostEqual(math.sqrt(1000.0 / a) * h, G.OMEGA_DT_MAX)  # omega h at the bound
        self.assertEqual(G.armature_for(0.0, 0.0, 0.0, h), 0.0)
        self.assertEqual(G.armature_for(0.0, 50.0, 0.0, h), 50.0 * h)

    def test_spring_target_offset(self):
        kp, ks, rest = 200.0, 50.0, 0.002
        off = G.spring_target_offset(kp, ks, rest)
        for x in (0.0, 0.004, 0.01):
            for q in (-0.01, 0.0, 0.003, 0.02):
                genesis = kp * (x + off - q) - ks * q  # Genesis: PD + spring to 0
                wanted = kp * (x - q) - ks * (q - rest)
                self.assertAlmostEqual(genesis, wanted, places=12)
        self.assertEqual(G.spring_target_offset(0.0, 50.0, 0.002), 0.0)
        self.assertEqual(G.spring_target_offset(200.0, 50.0, 0.0), 0.0)

    def test_props_are_inside_the_cone(self):
        fn = TABLE["functions"][4]
        outlet, axis = fn["site"]["point"], fn["direction"]
        props = G.prop_positions(outlet, axis, fn["reach"], 3)
        self.assertEqual(len(props), 3)
        for p in props:
            f = efc.airflow_force(fn, 6.0, outlet, axis, p, G.sphere_area(G.PROP_RADIUS))
            self.assertLess(f[1], 0.0)  # pushed along -y, the outlet's direction
            self.assertEqual(f[0], 0.0)
        # A downward outlet near the floor: props that would touch it are skipped.
        low = G.prop_positions([0.0, 0.0, 0.3], [0.0, 0.0, -1.0], 1.0, 3)
        self.assertEqual(len(low), 1)
        self.assertAlmostEqual(low[0][2], 0.05)

    def test_areas(self):
        self.assertAlmostEqual(G.sphere_area(0.1), math.pi * 0.01)
        self.assertAlmostEqual(G.aabb_area([0, 0, 0], [0.2, 0.0, 0.0]), 0.5 * math.pi * 0.01)
        lo, hi = G.union_aabb([[[0, 0, 0], [1, 1, 1]], [[-1, 0.5, 0], [0.5, 2, 0.5]]])
        self.assertEqual((lo, hi), ([-1, 0, 0], [1, 2, 1]))
        self.assertEqual(G.padded([0, 0, 0], [1, 1, 1], 0.5), ([-0.5, -0.5, -0.5], [1.5, 1.5, 1.5]))

    def test_camera_pose(self):
        pos, lookat = G.camera_pose([[0.0, 0.0, 0.0], [0.0, 0.0, 0.4]])
        self.assertEqual(lookat, (0.0, 0.0, 0.2))
        self.assertGreaterEqual(G.vnorm(G.vsub(pos, lookat)), 0.8 - 1e-12)
        pos, lookat = G.camera_pose([])
        self.assertEqual(len(pos), 3)

    def test_droplet_leads(self):
        self.assertEqual(G.droplet_leads(1.0, 0.002, 2), [0.0, 0.001])
        self.assertEqual(G.droplet_leads(1.0, 0.002, 0), [])

    def test_kept_links(self):
        keep = G.kept_links(TABLE)
        for name in ("button", "lid", "base", "bulb", "light_site", "heat_site", "water_site", "air_site"):
            self.assertIn(name, keep)
        self.assertEqual(len(keep), len(set(keep)))

    def test_conversions(self):
        self.assertEqual(G.to_floats([1, 2]), [1.0, 2.0])
        self.assertEqual(G.to_rows([[1, 2, 3]]), [[1.0, 2.0, 3.0]])


class CommandLine(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        write_object(self.dir.name)

    def tearDown(self):
        self.dir.cleanup()

    def test_help_without_genesis(self):
        with no_genesis():
            rc, out, _ = run_main(["--help"], self.dir.name)
        self.assertEqual(rc, 0)
        self.assertIn("--profile", out)
        self.assertIn("--headless", out)

    def test_missing_genesis_is_a_clear_error(self):
        with no_genesis():
            rc, _, err = run_main(["--headless", "--steps", "5"], self.dir.name)
        self.assertEqual(rc, 2)
        self.assertIn("pip install genesis-world==0.4.5", err)
        self.assertNotIn("Traceback", err)

    def test_user_errors(self):
        cases = [(["--steps", "0"], "--steps"), (["--dt", "0"], "--dt"), (["--duration", "-1"], "--duration"),
                 (["--profile", "wiggle"], "unknown profile"), (["--substeps", "0"], "--substeps"),
                 (["--csv", os.path.join(self.dir.name, "no", "x.csv")], "cannot write"),
                 (["--dt", "0.5"], "--dt")]
        with no_genesis():
            for argv, text in cases:
                rc, _, err = run_main(argv, self.dir.name)
                self.assertEqual(rc, 2, argv)
                self.assertIn(text, err, argv)
                self.assertNotIn("Traceback", err)
            rc, _, err = run_main(["--bogus"], self.dir.name)
            self.assertEqual(rc, 2)

    def test_bad_functions_file(self):
        path = os.path.join(self.dir.name, "gadget_functions.json")
        with open(path, "w") as f:
            f.write("{}")
        with no_genesis():
            rc, _, err = run_main(["--headless"], self.dir.name)
        self.assertEqual(rc, 1)
        self.assertIn("format", err)

    def test_missing_urdf(self):
        os.remove(os.path.join(self.dir.name, "gadget.urdf"))
        with no_genesis():
            rc, _, err = run_main(["--headless"], self.dir.name)
        self.assertEqual(rc, 2)
        self.assertIn("URDF", err)


class StubRun(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        write_object(self.dir.name)
        self.csv = os.path.join(self.dir.name, "log.csv")

    def tearDown(self):
        self.dir.cleanup()

    def run_stub(self, argv):
        with stub_genesis() as stub:
            rc, out, err = run_main(argv, self.dir.name)
        self.assertEqual(rc, 0, err)
        return stub.record["scenes"][-1], stub, err

    def test_templates_match_the_replay(self):
        # The spring's rest at 0: no target offset, so the ideal servo is at the profile.
        table = json.loads(json.dumps(TABLE))
        table["joints"][0]["spring"]["rest"] = 0.0
        with open(os.path.join(self.dir.name, "gadget_functions.json"), "w") as f:
            json.dump(table, f)
        scene, stub, err = self.run_stub(["--headless", "--profile", "press:3", "--duration", "1.2",
                                          "--csv", self.csv])
        header, rows = read_csv(self.csv)
        table = efc.load_functions(os.path.join(self.dir.name, "gadget_functions.json"))
        replay = efc.replay(table, efc.parse_profile("press:3"), 1.2, 0.002)
        self.assertEqual(header, replay.columns)
        self.assertEqual(len(rows), len(replay.rows))
        # The stub's servo is ideal, so s_R and s_E are the replay's to the bit.
        for col in range(1, len(header)):
            if header[col].endswith(".s_R") or header[col].endswith(".s_E"):
                self.assertEqual([r[col] for r in rows], [float(efc.format_value(r[col])) for r in replay.rows],
                                 header[col])
        self.assertEqual(scene.steps, 600)
        self.assertIn("600 steps", err)

    def test_scene_setup(self):
        scene, stub, _ = self.run_stub(["--headless", "--steps", "3", "--profile", "ramp"])
        self.assertEqual(stub.record["init"]["backend"], "cpu")
        self.assertFalse(scene.show_viewer)
        self.assertEqual(scene.sim_options.dt, 0.002)
        self.assertGreater(scene.sim_options.substeps, 1)  # a fluid: SPH's substeps
        self.assertFalse(scene.rigid_options.enable_self_collision)
        urdf = [e for e in scene.entities if type(e.morph).__name__ == "URDF"][0]
        self.assertTrue(urdf.morph.fixed)
        self.assertIsNone(urdf.morph.default_armature)
        self.assertIn("water_site", urdf.morph.links_to_keep)
        # lights: the default directional light and the lamp's point light at its site
        lights = scene.vis_options.lights
        self.assertEqual(type(lights[0]).__name__, "DirectionalLight")
        self.assertEqual(type(lights[1]).__name__, "PointLight")
        self.assertEqual(tuple(lights[1].pos), (0.0, 0.0, 0.32))
        self.assertAlmostEqual(lights[1].intensity, 450.0 / (4 * math.pi))
        # SPH domain holds the emitter; one particle per droplet
        lo, hi = scene.sph_options.lower_bound, scene.sph_options.upper_bound
        for k, c in enumerate((0.2, 0.0, 0.25)):
            self.assertTrue(lo[k] < c < hi[k])
        self.assertAlmostEqual(scene.sph_options.particle_size, G.sph_particle_size(2.68e-4))
        # gains: the profile's receptor and the geometry effector
        dof_button = urdf.get_joint("button").dof
        dof_lid = urdf.get_joint("lid").dof
        self.assertEqual(urdf.info["kp"], {dof_button: 200.0, dof_lid: 100.0})
        self.assertEqual(urdf.info["kv"], {dof_button: 2.0, dof_lid: 1.0})
        self.assertEqual(urdf.info["stiffness"][dof_button], 50.0)
        self.assertEqual(urdf.info["frictionloss"][dof_lid], 0.2)
        self.assertGreater(urdf.info["armature"][dof_button], 0.0)
        # three props in the airflow cone, floating
        props = [e for e in scene.entities if type(e.morph).__name__ == "Sphere"]
        self.assertEqual(len(props), 3)
        self.assertTrue(all(p.material.gravity_compensation == 1.0 for p in props))

    def test_without_profile_the_receptor_is_free(self):
        scene, stub, _ = self.run_stub(["--headless", "--steps", "3", "--no-props", "--lamp-light", "off"])
        urdf = [e for e in scene.entities if type(e.morph).__name__ == "URDF"][0]
        dof_button = urdf.get_joint("button").dof
        self.assertNotIn(dof_button, urdf.info["kp"])
        # its spring's rest (2 mm) as a constant force: Genesis' springs pull to 0
        self.assertEqual(urdf.mode[dof_button], "force")
        self.assertAlmostEqual(urdf.force[dof_button], 50.0 * 0.002)
        self.assertEqual(len(scene.vis_options.lights), 1)
        self.assertEqual([e for e in scene.entities if type(e.morph).__name__ == "Sphere"], [])

    def test_effects_are_realised(self):
        scene, stub, _ = self.run_stub(["--profile", "hold:hi", "--duration", "1.0", "--csv", self.csv])
        header, rows = read_csv(self.csv)
        col = {name: k for k, name in enumerate(header)}
        last = rows[-1]
        # geometry: the lid's position read back (an ideal servo at the output)
        self.assertAlmostEqual(last[col["open.measured"]], 1.2)
        # fluid: the particles emitted in the last 0.5 s, as L/min
        self.assertAlmostEqual(last[col["water.measured"]], 6.0, delta=0.05)
        emitter = scene.emitters_list[0]
        self.assertGreater(len(emitter.emitted), 0)
        pos, direction, speed, size, length = emitter.emitted[-1]
        self.assertEqual(direction, (0.0, 0.0, -1.0))
        self.assertEqual(size, length)
        # airflow: one press (hold:hi) gives 2 m/s; forces along -y on the props
        self.assertEqual(last[col["air.measured"]], 2.0)
        links, forces, ref = scene.solver.applied[-1]
        self.assertEqual(ref, "link_com")
        self.assertEqual(len(links), 3)
        self.assertTrue(all(f[1] < 0 and f[0] == 0 and f[2] == 0 for f in forces))
        # temperature: the lag's state; illumination: the output
        self.assertEqual(last[col["heat.measured"]], last[col["heat.measured"]])
        self.assertGreater(last[col["heat.measured"]], 20.0)
        self.assertEqual(last[col["light.measured"]], 450.0)
        # the viewer's markers: the lamp's sphere and the glowing box
        kinds = {node[0] for node in scene.debug}
        self.assertEqual(kinds, {"sphere", "box"})
        self.assertTrue(scene.show_viewer)
        self.assertEqual(scene.viewer_options.max_FPS, 500)

    def test_headless_draws_nothing(self):
        scene, _, _ = self.run_stub(["--headless", "--profile", "hold:hi", "--duration", "0.2"])
        self.assertEqual(scene.debug, [])

    def test_closing_the_viewer_stops_the_run(self):
        with stub_genesis(close_viewer_after=10):
            rc, _, err = run_main(["--profile", "ramp", "--steps", "100", "--csv", self.csv], self.dir.name)
        self.assertEqual(rc, 0, err)
        self.assertIn("viewer closed", err)
        _, rows = read_csv(self.csv)
        self.assertEqual(len(rows), 11)

    def test_genesis_errors_are_reported(self):
        path = os.path.join(self.dir.name, "gadget_functions.json")
        table = json.loads(json.dumps(TABLE))
        table["functions"][1]["site"]["link"] = "nowhere_site"
        with open(path, "w") as f:
            json.dump(table, f)
        with stub_genesis():
            rc, _, err = run_main(["--headless", "--steps", "2", "--csv", self.csv], self.dir.name)
        self.assertEqual(rc, 1)
        self.assertIn("Genesis: Link not found", err)
        self.assertNotIn("Traceback", err)


if __name__ == "__main__":
    unittest.main()
