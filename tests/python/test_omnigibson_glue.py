"""Tests of the OmniGibson glue that run without OmniGibson (python3 -m unittest).

Pure helpers (frames, units, drives, cones, particles, the asset's metadata), the
command line, and a whole run against a small stand-in of the OmniGibson API (only the
names the glue uses, with the 3.7 signatures), so the glue's control loop is exercised.
"""

import json
import math
import os
import shutil
import sys
import tempfile
import types
import unittest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(REPO, "backends", "omnigibson")
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(REPO, "backends", "python"))

import efc_omnigibson as glue  # noqa: E402
import efc_templates as efc  # noqa: E402

FIXTURES = os.path.join(REPO, "tests", "python", "fixtures")


def close(a, b, tol=1e-12):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


class FrameTest(unittest.TestCase):
    def test_rpy_identity(self):
        self.assertTrue(close(glue.rpy_to_quat((0, 0, 0)), (0, 0, 0, 1)))

    def test_rpy_single_axes(self):
        for axis in range(3):
            rpy = [0.0, 0.0, 0.0]
            rpy[axis] = 0.7
            q = glue.rpy_to_quat(rpy)
            expect = [0.0, 0.0, 0.0, math.cos(0.35)]
            expect[axis] = math.sin(0.35)
            self.assertTrue(close(q, expect))

    def test_rpy_order_is_fixed_xyz(self):
        # URDF: R = Rz(yaw) Ry(pitch) Rx(roll); check by rotating vectors.
        r, p, y = 0.3, -0.4, 1.1
        q = glue.rpy_to_quat((r, p, y))

        def rx(v, a):
            return (v[0], math.cos(a) * v[1] - math.sin(a) * v[2], math.sin(a) * v[1] + math.cos(a) * v[2])

        def ry(v, a):
            return (math.cos(a) * v[0] + math.sin(a) * v[2], v[1], -math.sin(a) * v[0] + math.cos(a) * v[2])

        def rz(v, a):
            return (math.cos(a) * v[0] - math.sin(a) * v[1], math.sin(a) * v[0] + math.cos(a) * v[1], v[2])

        for v in ((1, 0, 0), (0, 1, 0), (0, 0, 1), (0.2, -0.5, 0.7)):
            self.assertTrue(close(glue.quat_rotate(q, v), rz(ry(rx(v, r), p), y), 1e-12))

    def test_site_plus_z_of_a_downward_emitter(self):
        # the faucet's site: rpy (pi, 0, 0) turns +z into -z
        q = glue.rpy_to_quat((math.pi, 0.0, 0.0))
        self.assertTrue(close(glue.quat_rotate(q, (0, 0, 1)), (0, 0, -1), 1e-12))

    def test_normalized(self):
        self.assertTrue(close(glue.normalized((3, 0, 4)), (0.6, 0, 0.8)))
        self.assertEqual(glue.normalized((0, 0, 0)), (0.0, 0.0, 0.0))


class UnitTest(unittest.TestCase):
    def test_lumens_round_trip(self):
        for r in (0.01, 0.05, 0.25):
            for lm in (0.0, 1.0, 450.0, 1e4):
                i = glue.lumens_to_intensity(lm, r)
                self.assertAlmostEqual(glue.intensity_to_lumens(i, r), lm, places=9)

    def test_lumens_photometry(self):
        # F = pi L * 4 pi r^2 for a Lambertian sphere
        r = 0.02
        self.assertAlmostEqual(glue.lumens_to_intensity(450.0, r) * math.pi * 4 * math.pi * r * r, 450.0)

    def test_enclosing_radius(self):
        # a 3 cm bulb centred on the site: sqrt(3) * 3 cm, 5 % margin
        r = glue.enclosing_radius((0, 0, 0), (-0.03,) * 3, (0.03,) * 3)
        self.assertAlmostEqual(r, math.sqrt(3) * 0.03 * 1.05)
        self.assertEqual(glue.enclosing_radius((0, 0, 0), (0, 0, 0), (0, 0, 0)), glue.LIGHT_MIN_RADIUS)
        self.assertEqual(glue.enclosing_radius((0, 0, 0), (-5,) * 3, (5,) * 3), glue.LIGHT_MAX_RADIUS)

    def test_sphere_area(self):
        self.assertAlmostEqual(glue.sphere_area(0.5), math.pi * 0.25)

    def test_blend(self):
        self.assertEqual(glue.blend_rgb((0, 0, 0), (1, 0.5, 0.25), 0.0), (0.0, 0.0, 0.0))
        self.assertEqual(glue.blend_rgb((0, 0, 0), (1, 0.5, 0.25), 1.0), (1.0, 0.5, 0.25))
        self.assertTrue(close(glue.blend_rgb((0.2, 0.4, 0.6), efc.HOT_RGB, 0.5),
                              [(0.2 + efc.HOT_RGB[0]) / 2, (0.4 + efc.HOT_RGB[1]) / 2, (0.6 + efc.HOT_RGB[2]) / 2]))


class DriveTest(unittest.TestCase):
    def test_servo_alone(self):
        self.assertEqual(glue.combined_drive(100.0, 2.0, None, 0.0, 0.3), (100.0, 2.0, 0.3))

    def test_spring_alone(self):
        kp, kd, goal = glue.combined_drive(0.0, 0.0, {"stiffness": 60.0, "rest": 0.01}, 0.5, 0.3)
        self.assertEqual((kp, kd, goal), (60.0, 0.5, 0.01))

    def test_damping_alone(self):
        self.assertEqual(glue.combined_drive(0.0, 0.0, None, 0.5, 0.3), (0.0, 0.5, 0.3))

    def test_servo_plus_spring_is_the_same_force(self):
        kp, kv, k, rest, c, target = 120.5, 2.5, 60.0, -0.5, 0.1, 0.7
        gp, gd, goal = glue.combined_drive(kp, kv, {"stiffness": k, "rest": rest}, c, target)
        for q in (-1.0, 0.0, 0.3, 1.2):
            for qd in (-2.0, 0.0, 1.5):
                separate = kp * (target - q) - kv * qd + k * (rest - q) - c * qd
                combined = gp * (goal - q) - gd * qd
                self.assertAlmostEqual(separate, combined, places=9)


class AirflowTest(unittest.TestCase):
    def test_prop_positions_in_the_cone(self):
        fn = {"cone_angle": 0.35, "reach": 1.5}
        outlet, axis = (0.05, 0.0, 0.2), (0.0, 0.0, -2.0)
        spots = glue.prop_positions(outlet, axis, fn["reach"], 3)
        self.assertEqual(len(spots), 3)
        self.assertTrue(close(spots[0], (0.05, 0.0, 0.2 - 0.375)))
        self.assertTrue(close(spots[2], (0.05, 0.0, 0.2 - 1.125)))
        for p in spots:  # every prop is pushed when the air blows
            f = efc.airflow_force(fn, 4.0, outlet, axis, p, glue.sphere_area(glue.PROP_RADIUS))
            self.assertGreater(-f[2], 0.0)
            self.assertEqual(f[0], 0.0)

    def test_no_props(self):
        self.assertEqual(glue.prop_positions((0, 0, 0), (1, 0, 0), 1.0, 0), [])


class FluidTest(unittest.TestCase):
    def test_emit_positions_spread_along_the_stream(self):
        spots = glue.emit_positions((0, 0, 1), (0, 0, -1), 2.0, 0.01, 4)
        self.assertEqual(len(spots), 4)
        self.assertTrue(close(spots[0], (0, 0, 1)))
        self.assertTrue(close(spots[3], (0, 0, 1 - 2.0 * 0.01 * 0.75)))
        self.assertEqual(glue.emit_positions((0, 0, 0), (0, 0, 1), 1.0, 0.01, 0), [])

    def test_expired_count(self):
        births = [0.0, 0.0, 1.0, 2.5, 3.0]
        self.assertEqual(glue.expired_count(births, 3.0, 3.0), 0)
        self.assertEqual(glue.expired_count(births, 3.5, 3.0), 2)
        self.assertEqual(glue.expired_count(births, 10.0, 3.0), 5)
        self.assertEqual(glue.expired_count([], 10.0, 3.0), 0)


class TableTest(unittest.TestCase):
    def setUp(self):
        self.table = efc.load_functions(os.path.join(FIXTURES, "all_kinds_functions.json"))

    def test_abilities(self):
        self.assertEqual(glue.abilities_for(self.table), {"toggleable": {}, "heatable": {}})
        toaster = efc.load_functions(os.path.join(FIXTURES, "toaster_functions.json"))
        self.assertEqual(glue.abilities_for(toaster), {"heatable": {}})

    def test_meta_links(self):
        links = glue.meta_links(self.table)
        self.assertEqual(list(links), ["knob"])  # receptor of the first illumination function
        info = links["knob"]["togglebutton"]["0"][0]
        self.assertEqual(info["type"], "sphere")
        self.assertEqual(info["orientation"], [0.0, 0.0, 0.0, 1.0])
        toaster = efc.load_functions(os.path.join(FIXTURES, "toaster_functions.json"))
        self.assertEqual(glue.meta_links(toaster), {})

    def test_object_temperature(self):
        self.assertEqual(glue.object_temperature([20.0, 180.0, 40.0], 23.0), 180.0)
        self.assertEqual(glue.object_temperature([], 23.0), 23.0)

    def test_check_table_needs_sites(self):
        bad = json.loads(json.dumps(self.table))
        bad["functions"][1]["site"] = None
        with self.assertRaises(glue.GlueError):
            glue.check_table(bad)
        glue.check_table(self.table)


class AssetTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        os.makedirs(os.path.join(self.dir, "meshes"))
        with open(os.path.join(self.dir, "meshes", "a.stl"), "wb") as f:
            f.write(b"solid a\nendsolid a\n")
        self.urdf = os.path.join(self.dir, "toaster.urdf")
        with open(self.urdf, "w") as f:
            f.write('<?xml version="1.0"?>\n<robot name="class"><link name="body"/></robot>\n')
        self.table = efc.load_functions(os.path.join(FIXTURES, "all_kinds_functions.json"))

    def tearDown(self):
        shutil.rmtree(self.dir)

    def test_prepare_urdf_renames_robot_and_copies_meshes(self):
        out = glue.prepare_urdf(self.urdf, os.path.join(self.dir, "work"))
        with open(out) as f:
            text = f.read()
        self.assertIn('name="%s"' % glue.MODEL, text)
        self.assertIn('<link name="body"', text)
        self.assertTrue(os.path.isfile(os.path.join(self.dir, "work", "meshes", "a.stl")))

    def test_fingerprint_follows_inputs(self):
        a = glue.asset_fingerprint(self.urdf, self.table, "urdf")
        self.assertEqual(a, glue.asset_fingerprint(self.urdf, self.table, "urdf"))
        self.assertNotEqual(a, glue.asset_fingerprint(self.urdf, self.table, "coacd"))
        with open(os.path.join(self.dir, "meshes", "a.stl"), "ab") as f:
            f.write(b" ")
        self.assertNotEqual(a, glue.asset_fingerprint(self.urdf, self.table, "urdf"))

    def test_add_meta_links_and_stamp(self):
        meta = os.path.join(self.dir, "metadata.json")
        with open(meta, "w") as f:
            json.dump({"meta_links": {}, "bbox_size": [1, 1, 1]}, f)
        glue.add_meta_links(meta, glue.meta_links(self.table))
        with open(meta) as f:
            data = json.load(f)
        self.assertIn("togglebutton", data["meta_links"]["knob"])
        self.assertEqual(data["bbox_size"], [1, 1, 1])
        paths = glue.asset_paths(self.dir)
        self.assertFalse(glue.asset_is_current(paths, "x"))
        os.makedirs(os.path.dirname(paths["usd"]))
        open(paths["usd"], "w").close()
        with open(paths["stamp"], "w") as f:
            json.dump({"fingerprint": "x"}, f)
        self.assertTrue(glue.asset_is_current(paths, "x"))
        self.assertFalse(glue.asset_is_current(paths, "y"))


class CommandLineTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        shutil.copy(os.path.join(FIXTURES, "toaster_functions.json"), self.dir)
        with open(os.path.join(self.dir, "toaster.urdf"), "w") as f:
            f.write('<robot name="toaster"><link name="body"/></robot>\n')
        self.old_file = glue.__file__
        glue.__file__ = os.path.join(self.dir, "toaster_omnigibson.py")

    def tearDown(self):
        glue.__file__ = self.old_file
        shutil.rmtree(self.dir)

    def run_main(self, argv):
        return glue.main(argv, object_name="toaster", urdf_file="toaster.urdf",
                         functions_file="toaster_functions.json")

    def test_help_works_without_the_simulator(self):
        with _Quiet():
            self.assertEqual(self.run_main(["--help"]), 0)

    def test_usage_errors(self):
        with _Quiet():
            self.assertEqual(self.run_main(["--steps", "0"]), glue.EXIT_USAGE)
            self.assertEqual(self.run_main(["--profile", "nonsense"]), glue.EXIT_USAGE)
            self.assertEqual(self.run_main(["--dt", "5"]), glue.EXIT_USAGE)
            self.assertEqual(self.run_main(["--bogus"]), glue.EXIT_USAGE)

    def test_bad_functions_file(self):
        with open(os.path.join(self.dir, "toaster_functions.json"), "w") as f:
            f.write("{")
        with _Quiet():
            self.assertEqual(self.run_main([]), glue.EXIT_BAD_INPUT)


# ---------------------------------------------------------------------------
# A stand-in for the part of OmniGibson 3.7 (and torch) the glue uses: same names and
# keywords as the 3.7 source (see NOTES.md), trivial behaviour: a joint reaches its
# drive's position target in one step.

class _Tensor(list):
    def tolist(self):
        return [x.tolist() if isinstance(x, _Tensor) else x for x in self]

    def __getitem__(self, i):
        v = list.__getitem__(self, i)
        return _Tensor(v) if isinstance(v, list) else v


def _tensor(data, dtype=None):
    if isinstance(data, (list, tuple)):
        return _Tensor(_tensor(x) if isinstance(x, (list, tuple)) else float(x) for x in data)
    return float(data)


def _fake_modules(log):
    th = types.ModuleType("torch")
    th.tensor = _tensor
    th.float32 = "float32"
    th.Tensor = _Tensor
    th.arange = lambda n: _Tensor(range(int(n)))

    class ControlType:
        POSITION = 0

    class Prim:
        def __init__(self, pos=(0.0, 0.0, 0.0)):
            self.pos = list(pos)

        def get_position_orientation(self):
            return _Tensor(self.pos), _Tensor([0.0, 0.0, 0.0, 1.0])

        def set_position_orientation(self, position=None, orientation=None, frame="world"):
            if position is not None:
                self.pos = [float(c) for c in position]

    class VisualGeomPrim:
        def __init__(self):
            self.color = _Tensor([0.8, 0.35, 0.2])

    class RigidPrim(Prim):
        def __init__(self, pos=(0.0, 0.0, 0.0)):
            super().__init__(pos)
            self.visual_meshes = {"mesh_0": VisualGeomPrim()}
            self.visual_aabb = (_Tensor([-0.03] * 3), _Tensor([0.03] * 3))
            self.mass = 1.0

    class JointPrim:
        def __init__(self, index):
            self.dof_indices = [index]
            self.q = 0.0
            self.target = None
            self.friction = None

        def get_state(self, normalized=False):
            return _Tensor([self.q]), _Tensor([0.0]), _Tensor([0.0])

        def set_pos(self, pos, normalized=False, drive=False):
            self.q = float(pos)

        def set_control_type(self, control_type, kp=None, kd=None):
            log.append(("gains", self.dof_indices[0], kp, kd))

    class BaseState:
        def __init__(self):
            self.value = None

        def get_value(self):
            return self.value

        def set_value(self, v):
            self.value = v
            return True

    class Temperature(BaseState):
        heated = []

        @classmethod
        def update_temperature_from_heatsource_or_sink(cls, objs, temperature, rate):
            cls.heated.append((len(objs), temperature, rate))

    class ToggledOn(BaseState):
        pass

    class StatefulObject(Prim):
        def __init__(self, name, **kwargs):
            super().__init__()
            self.name = name
            self.kwargs = kwargs
            self.states = {}
            self.root_link = RigidPrim()
            self.velocity = [0.0, 0.0, 0.0]

        def get_linear_velocity(self):
            return _Tensor(self.velocity)

        def set_linear_velocity(self, velocity):
            self.velocity = [float(c) for c in velocity]

    class USDObject(StatefulObject):
        def __init__(self, name, usd_path, encrypted=False, relative_prim_path=None, category="object",
                     fixed_base=False, abilities=None, **kwargs):
            super().__init__(name)
            self.abilities = abilities
            self.joints = {}
            self.links = {}
            if "toggleable" in abilities:
                self.states[ToggledOn] = ToggledOn()
            if "heatable" in abilities:
                self.states[Temperature] = Temperature()

        def set_joint_positions(self, positions, indices=None, normalized=False, drive=False):
            assert drive
            for joint in self.joints.values():
                if joint.dof_indices == list(indices):
                    joint.target = float(positions[0])

    class LightObject(StatefulObject):
        def __init__(self, name, light_type, relative_prim_path=None, radius=1.0, intensity=50000.0,
                     fixed_base=False, **kwargs):
            super().__init__(name)
            self.intensity, self.radius, self.color = intensity, radius, None

    class PrimitiveObject(StatefulObject):
        def __init__(self, name, primitive_type, relative_prim_path=None, radius=None, rgba=None, **kwargs):
            super().__init__(name)

    class FluidSystem:
        def __init__(self):
            self.n_particles = 0

        def generate_particles(self, positions, velocities=None, **kwargs):
            assert len(positions) == len(velocities)
            self.n_particles += len(positions)

        def remove_particles(self, idxs, instancer_idn=None):
            self.n_particles -= len(idxs)

    class Scene:
        def __init__(self, use_floor_plane=True, floor_plane_visible=True, **kwargs):
            self.objects = []
            self.water = FluidSystem()

        def add_object(self, obj, register=True):
            self.objects.append(obj)

        def get_system(self, name, force_init=True):
            return self.water

        def get_objects_with_state(self, state):
            return [o for o in self.objects if state in o.states] + [log[0]]

    class Sim:
        def import_scene(self, scene):
            self.scene = scene

        def play(self):
            table = log[1]
            obj = next(o for o in self.scene.objects if isinstance(o, USDObject))
            for i, j in enumerate(table["joints"]):
                obj.joints[j["joint"]] = JointPrim(i)
            names = {table["root_link"]}
            for fn in table["functions"]:
                names.add(fn["effector"]["link"])
                if fn["site"] is not None:
                    names.add(fn["site"]["link"])
            for name in names:
                obj.links[name] = RigidPrim((0.05, 0.0, 0.2))

        def step(self):
            obj = next(o for o in self.scene.objects if isinstance(o, USDObject))
            for joint in obj.joints.values():
                if joint.target is not None:
                    joint.q = joint.target
            log.append(("step",))

    og = types.ModuleType("omnigibson")
    og.sim = None

    def launch(*args, **kwargs):
        log.append(("launch", kwargs))
        og.sim = Sim()
        return og.sim

    og.launch = launch
    og.shutdown = lambda due_to_signal=False: log.append(("shutdown",))
    mods = {"torch": th, "omnigibson": og}

    def mod(name, **names):
        m = types.ModuleType(name)
        m.__dict__.update(names)
        mods[name] = m

    mod("omnigibson.macros", gm=types.SimpleNamespace(USE_GPU_DYNAMICS=False))
    mod("omnigibson.scenes", Scene=Scene)
    mod("omnigibson.objects", USDObject=USDObject, LightObject=LightObject,
        PrimitiveObject=PrimitiveObject, StatefulObject=StatefulObject)
    mod("omnigibson.prims")
    mod("omnigibson.prims.rigid_prim", RigidPrim=RigidPrim)
    mod("omnigibson.prims.rigid_dynamic_prim", RigidDynamicPrim=RigidPrim)
    mod("omnigibson.prims.joint_prim", JointPrim=JointPrim)
    mod("omnigibson.prims.geom_prim", VisualGeomPrim=VisualGeomPrim)
    mod("omnigibson.controllers")
    mod("omnigibson.controllers.controller_base", ControlType=ControlType)
    mod("omnigibson.object_states", Temperature=Temperature, ToggledOn=ToggledOn)
    mod("omnigibson.systems", FluidSystem=FluidSystem)
    return mods, StatefulObject, Temperature


class StandInRunTest(unittest.TestCase):
    """The whole control loop against the stand-in: every effect kind, a profile, the CSV."""

    def run_table(self, fixture, argv, tweak=None):
        table = efc.load_functions(os.path.join(FIXTURES, fixture))
        if tweak is not None:
            tweak(table)
        log = [None, table]
        mods, StatefulObject, Temperature = _fake_modules(log)
        neighbour = StatefulObject("pot")
        neighbour.states[Temperature] = Temperature()
        neighbour.pos = [0.05, 0.0, 0.1]  # 10 cm under the sites
        log[0] = neighbour
        saved = {name: sys.modules.get(name) for name in mods}
        sys.modules.update(mods)
        tmp = tempfile.mkdtemp()
        try:
            csv = os.path.join(tmp, "log.csv")
            args = glue.parse_args(argv + ["--csv", csv])
            dt = table["timestep"]
            duration = args.duration if args.duration is not None else args.steps * dt
            profile = efc.parse_profile(args.profile) if args.profile else None
            runner = glue.Runner(table, table["object"], args, dt, duration, profile,
                                 glue.asset_paths(tmp))
            self.assertEqual(runner.run(), glue.EXIT_OK)
            with open(csv) as f:
                rows = [line.split(",") for line in f.read().splitlines()]
            return table, runner, rows, log, Temperature
        finally:
            for name, m in saved.items():
                if m is None:
                    sys.modules.pop(name, None)
                else:
                    sys.modules[name] = m
            shutil.rmtree(tmp)

    def test_all_kinds(self):
        def stiff(table):  # the fixture's servos cannot hold the receptors against their springs
            for joint in table["joints"]:
                joint["drive"]["kp"] = 1e5

        table, runner, rows, log, Temperature = self.run_table(
            "all_kinds_functions.json", ["--steps", "3000", "--profile", "press:3"], stiff)
        names = [fn["name"] for fn in table["functions"]]
        self.assertEqual(rows[0], ["t"] + [n + c for n in names for c in (".s_R", ".s_E", ".measured")])
        self.assertEqual(len(rows), 3001)
        events = log[2:]
        self.assertEqual(sum(1 for e in events if e[0] == "step"), 3000)
        self.assertEqual(events[-1], ("shutdown",))
        launch = next(e for e in events if e[0] == "launch")[1]
        self.assertEqual(launch["physics_dt"], table["timestep"])
        col = {c: k for k, c in enumerate(rows[0])}
        values = [[float(v) for v in row] for row in rows[1:]]
        # illumination: the lumens read back from the light are the output
        lit = [r[col["step_illumination.measured"]] for r in values]
        self.assertGreater(max(lit), 700.0)
        for r in values:  # templates' s_E is the lumens (no lag): measured reads it back
            self.assertAlmostEqual(r[col["step_illumination.measured"]], r[col["step_illumination.s_E"]],
                                   places=6)
        # fluid: particles were emitted and the meter saw them
        self.assertGreater(max(r[col["binary_fluid.measured"]] for r in values), 0.0)
        self.assertLessEqual(runner.water.n_particles, runner.args.max_particles)
        self.assertEqual(runner.water.n_particles, len(runner.births))
        # geometry: the effector joint followed its target
        self.assertGreater(max(r[col["binary_geometry.measured"]] for r in values), 1.0)
        # temperature: several functions, so measured is the script state; the neighbour was heated
        self.assertGreater(len(Temperature.heated), 0)
        # airflow props were pushed along -z
        self.assertTrue(any(p.velocity[2] < 0 for p in runner.props))

    def test_toaster_single_temperature_reads_the_state(self):
        def stiff(table):  # the fixture's servo cannot hold the lever against its spring
            table["joints"][0]["drive"]["kp"] = 1e5

        table, runner, rows, log, Temperature = self.run_table(
            "toaster_functions.json", ["--steps", "500", "--profile", "hold:hi"], stiff)
        col = {c: k for k, c in enumerate(rows[0])}
        last = [float(v) for v in rows[-1]]
        self.assertGreater(last[col["toast.measured"]], 20.0)
        self.assertEqual(runner.obj.abilities, {"heatable": {}})


class _Quiet:
    """Silences stdout/stderr."""

    def __enter__(self):
        self.saved = sys.stdout, sys.stderr
        sys.stdout = sys.stderr = open(os.devnull, "w")

    def __exit__(self, *exc):
        sys.stdout.close()
        sys.stdout, sys.stderr = self.saved
        return False


if __name__ == "__main__":
    unittest.main()
