#!/usr/bin/env python3
"""Tests of the Isaac Lab glue (efc_isaaclab.py) that run without Isaac Lab.

    python3 backends/isaaclab/test_efc_isaaclab.py     (or: python3 -m unittest ...)

1. The pure helpers (unit conversions, frames, drive blending, cone props, URDF/STL).
2. The command line: --help, usage errors, bad files, Isaac Lab missing.
3. A whole run against small stand-ins for torch, pxr and the Isaac Lab classes the
   glue uses (only the calls it makes; their real signatures are checked by
   tests/sim_api/check_api.py against the Isaac Lab 2.3 index). The stand-ins move
   joints to their drive targets and integrate the droplets and props, so the loop's
   bookkeeping (templates, lights, glow, droplet pool, flow meter, air forces, CSV)
   is exercised end to end. It says nothing about PhysX or RTX.
"""

import contextlib
import io
import json
import math
import os
import shutil
import struct
import sys
import tempfile
import types
import unittest
import xml.etree.ElementTree as ET

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(REPO, "backends", "isaaclab")
sys.path.insert(0, os.path.join(REPO, "backends", "python"))
sys.path.insert(0, HERE)

import efc_templates as efc  # noqa: E402
import efc_isaaclab as glue  # noqa: E402

FIXTURES = os.path.join(REPO, "tests", "python", "fixtures")


def fixture(name):
    return os.path.join(FIXTURES, name)


def load_fixture(name):
    return efc.load_functions(fixture(name))


def urdf_for(table, path):
    """A URDF with the links and joints a functions table names: a 4 cm box per link
    (the root one 10 cm, coloured), joints at their origins, site links fixed."""
    robot = ET.Element("robot", name=table["object"])
    mat = ET.SubElement(robot, "material", name="root_material")
    ET.SubElement(mat, "color", rgba="0.2 0.4 0.6 1")

    def link(name, size, material=None):
        el = ET.SubElement(robot, "link", name=name)
        inertial = ET.SubElement(el, "inertial")
        ET.SubElement(inertial, "mass", value="0.1")
        i = "%g" % (0.1 * size * size / 6)
        ET.SubElement(inertial, "inertia", ixx=i, ixy="0", ixz="0", iyy=i, iyz="0", izz=i)
        vis = ET.SubElement(el, "visual")
        geom = ET.SubElement(vis, "geometry")
        ET.SubElement(geom, "box", size="%g %g %g" % (size, size, size))
        if material:
            ET.SubElement(vis, "material", name=material)

    link(table["root_link"], 0.1, "root_material")
    for j in table["joints"]:
        link(j["link"], 0.04)
        el = ET.SubElement(robot, "joint", name=j["joint"], type=j["type"])
        ET.SubElement(el, "parent", link=j["parent_link"])
        ET.SubElement(el, "child", link=j["link"])
        ET.SubElement(el, "origin", xyz="%r %r %r" % tuple(j["origin"]), rpy="0 0 0")
        ET.SubElement(el, "axis", xyz="%r %r %r" % tuple(j["axis"]))
    known = {table["root_link"]} | {j["link"] for j in table["joints"]}
    for fn in table["functions"]:
        eff = fn["effector"]["link"]
        if eff not in known:
            known.add(eff)
            ET.SubElement(robot, "link", name=eff)
            el = ET.SubElement(robot, "joint", name=eff + "_fixed", type="fixed")
            ET.SubElement(el, "parent", link=table["root_link"])
            ET.SubElement(el, "child", link=eff)
        site = fn.get("site")
        if site:
            ET.SubElement(robot, "link", name=site["link"])
            el = ET.SubElement(robot, "joint", name=site["link"] + "_joint", type="fixed")
            ET.SubElement(el, "parent", link=site["parent_link"])
            ET.SubElement(el, "child", link=site["link"])
            ET.SubElement(el, "origin", xyz="%r %r %r" % tuple(site["xyz"]), rpy="0 0 0")
    ET.ElementTree(robot).write(path)


# ---------------------------------------------------------------------------
# 1. Pure helpers

class HelperTest(unittest.TestCase):
    def test_lumens_intensity_round_trip(self):
        for lm in (0.0, 1.0, 450.0, 1600.0):
            self.assertAlmostEqual(glue.intensity_to_lumens(glue.lumens_to_intensity(lm)), lm, places=9)
        # a Lambertian sphere of radius r and luminance L emits 4 pi^2 r^2 L lumens
        r = 0.02
        self.assertAlmostEqual(glue.lumens_to_intensity(4 * math.pi ** 2 * r * r * 1000.0, r), 1000.0, places=9)

    def test_quat_rotate(self):
        q = (math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4))  # +90 deg about z
        v = glue.quat_rotate(q, (1.0, 0.0, 0.0))
        for a, b in zip(v, (0.0, 1.0, 0.0)):
            self.assertAlmostEqual(a, b)
        self.assertEqual(glue.quat_rotate((1.0, 0.0, 0.0, 0.0), (0.3, -2.0, 5.0)), (0.3, -2.0, 5.0))
        q = (math.cos(math.pi / 2), math.sin(math.pi / 2), 0.0, 0.0)  # 180 deg about x
        v = glue.quat_rotate(q, (0.0, 0.0, 1.0))
        for a, b in zip(v, (0.0, 0.0, -1.0)):
            self.assertAlmostEqual(a, b)

    def test_site_world(self):
        q = (math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4))
        p = glue.site_world((1.0, 2.0, 3.0), q, (0.1, 0.0, 0.2))
        for a, b in zip(p, (1.0, 2.1, 3.2)):
            self.assertAlmostEqual(a, b)

    def test_combine_drive_is_servo_plus_spring_plus_damper(self):
        kp, kv, k, rest, c = 120.0, 3.0, 60.0, 0.01, 0.5
        stiffness, damping, blend = glue.combine_drive((kp, kv), k, rest, c)
        self.assertEqual((stiffness, damping), (180.0, 3.5))
        for q_star in (0.0, 0.04, -0.2):
            target = blend(q_star)
            for q in (-0.1, 0.0, 0.03):
                for qd in (-1.0, 0.0, 2.0):
                    want = kp * (q_star - q) + k * (rest - q) - (kv + c) * qd
                    got = stiffness * (target - q) - damping * qd
                    self.assertAlmostEqual(got, want, places=9)
        # spring only: target is the rest position; nothing: no stiffness at all
        s, d, b = glue.combine_drive(None, 50.0, 0.2, 0.1)
        self.assertEqual((s, d, b(1.0)), (50.0, 0.1, 0.2))
        s, d, b = glue.combine_drive(None, 0.0, 0.0, 0.0)
        self.assertEqual((s, d, b(0.7)), (0.0, 0.0, 0.7))

    def test_joint_drive_plan(self):
        table = load_fixture("toaster_functions.json")
        off = {p["joint"]: p for p in glue.joint_drive_plan(table, False)}
        on = {p["joint"]: p for p in glue.joint_drive_plan(table, True)}
        # the lever (profile receptor, spring 60): only spring + damping without --profile
        self.assertFalse(off["lever"]["servo"])
        self.assertEqual(off["lever"]["stiffness"], 60.0)
        self.assertTrue(on["lever"]["servo"])
        self.assertEqual(on["lever"]["stiffness"], 120.5 + 60.0)
        self.assertAlmostEqual(on["lever"]["damping"], 2.5 + 0.1)
        # the carriage (geometry effector) is always servoed
        self.assertTrue(off["carriage"]["servo"])
        self.assertEqual(off["carriage"]["blend"](0.05), 0.05)

    def test_park_position_matches_mujoco_grid(self):
        self.assertEqual(glue.park_position(0, 0.004), (0.0, 0.0, 50.0))
        self.assertEqual(glue.park_position(21, 0.004), (0.2, 0.2, 50.0))
        self.assertEqual(glue.park_position(1, 0.1), (0.5, 0.0, 50.0))

    def test_prop_homes_are_inside_the_cone(self):
        for axis in ((0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.3, 0.4, 0.5)):
            outlet, reach, cone = (0.1, -0.2, 0.3), 0.6, 0.35
            homes = glue.prop_homes(outlet, axis, reach, cone, 3)
            self.assertEqual(len(homes), 3)
            a = glue.normalized(axis)
            for h in homes:
                v = [h[i] - outlet[i] for i in range(3)]
                along = sum(v[i] * a[i] for i in range(3))
                off = math.sqrt(max(0.0, sum(x * x for x in v) - along * along))
                self.assertGreater(efc.air_speed_at(5.0, along, math.atan2(off, along), cone, reach), 0.0)

    def test_glow_colors(self):
        base = (0.2, 0.4, 0.6)
        self.assertEqual(glue.glow_colors(base, 0.0), (base, (0.0, 0.0, 0.0)))
        self.assertEqual(glue.glow_colors(base, 1.0), (efc.HOT_RGB, efc.HOT_RGB))

    def test_lamp_colors(self):
        base, light = (0.2, 0.2, 0.2), (1.0, 0.9, 0.7)
        self.assertEqual(glue.lamp_colors(base, light, 0.0, 800.0), (base, (0.0, 0.0, 0.0)))
        self.assertEqual(glue.lamp_colors(base, light, 800.0, 800.0), (light, light))
        self.assertEqual(glue.lamp_colors(base, light, 2000.0, 800.0), (light, light))
        d, e = glue.lamp_colors(base, light, 400.0, 800.0)
        self.assertAlmostEqual(e[0], 0.5)
        self.assertAlmostEqual(d[1], 0.55)
        self.assertEqual(glue.lamp_colors(base, light, 5.0, 0.0), (base, (0.0, 0.0, 0.0)))

    def test_camera_and_render(self):
        eye, target = glue.camera_view((0, 0, 0), (0.2, 0.2, 0.2))
        self.assertEqual(target, (0.1, 0.1, 0.1))
        self.assertGreater(eye[0], 0.2)
        self.assertEqual(glue.render_every(0.002), 8)
        self.assertEqual(glue.render_every(0.05), 1)

    def test_start_position(self):
        j = {"type": "revolute", "lo": 0.0, "hi": 1.0}
        self.assertEqual(glue.start_position(j, 2.0), 1.0)
        self.assertEqual(glue.start_position(j, -1.0), 0.0)
        self.assertEqual(glue.start_position({"type": "continuous", "lo": 0.0, "hi": 6.28}, 9.0), 9.0)

    def test_stl_bounds(self):
        tmp = tempfile.mkdtemp()
        try:
            tris = [((0, 0, 0), (1, 0, 0), (0, 2, 0)), ((0, 0, -3), (1, 0, 0), (0, 2, 0))]
            with open(os.path.join(tmp, "b.stl"), "wb") as f:
                f.write(b"\0" * 80 + struct.pack("<I", len(tris)))
                for t in tris:
                    f.write(struct.pack("<3f", 0, 0, 1))
                    for v in t:
                        f.write(struct.pack("<3f", *v))
                    f.write(b"\0\0")
            self.assertEqual(glue.stl_bounds(os.path.join(tmp, "b.stl")), ((0, 0, -3), (1, 2, 0)))
            with open(os.path.join(tmp, "a.stl"), "w") as f:
                f.write("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                        "vertex 0 1 5\nendloop\nendfacet\nendsolid x\n")
            self.assertEqual(glue.stl_bounds(os.path.join(tmp, "a.stl")), ((0, 0, 0), (1, 1, 5)))
            self.assertIsNone(glue.stl_bounds(os.path.join(tmp, "none.stl")))
        finally:
            shutil.rmtree(tmp)

    def test_urdf_summary(self):
        tmp = tempfile.mkdtemp()
        try:
            table = load_fixture("toaster_functions.json")
            path = os.path.join(tmp, "t.urdf")
            urdf_for(table, path)
            s = glue.urdf_summary(path)
            self.assertEqual(s["colors"]["body"], (0.2, 0.4, 0.6))
            self.assertEqual(s["lo"], (-0.05, -0.05, -0.05))
            # the lever's 4 cm box at (0.152, 0, 0.16)
            self.assertAlmostEqual(s["hi"][0], 0.172)
            self.assertAlmostEqual(s["hi"][2], 0.18)
            with open(os.path.join(tmp, "bad.urdf"), "w") as f:
                f.write("<robot>")
            with self.assertRaises(glue.UsageError):
                glue.urdf_summary(os.path.join(tmp, "bad.urdf"))
        finally:
            shutil.rmtree(tmp)

    def test_urdf_summary_of_a_real_efc_urdf(self):
        efc_bin = os.path.join(REPO, "build", "efc")
        if not os.access(efc_bin, os.X_OK):
            self.skipTest("build/efc is not built")
        tmp = tempfile.mkdtemp()
        try:
            import subprocess
            r = subprocess.run([efc_bin, "compile", os.path.join(REPO, "examples", "kitchen_faucet.json"),
                                "--target", "urdf", "-o", tmp], capture_output=True)
            if r.returncode != 0:
                self.skipTest("efc compile failed: %s" % r.stderr.decode(errors="replace"))
            s = glue.urdf_summary(os.path.join(tmp, "urdf", "kitchen_faucet.urdf"))
            self.assertIsNotNone(s["lo"])
            for i in range(3):
                self.assertLess(s["lo"][i], s["hi"][i])
        finally:
            shutil.rmtree(tmp)

    def test_joint_inertia(self):
        tmp = tempfile.mkdtemp()
        try:
            path = os.path.join(tmp, "j.urdf")
            with open(path, "w") as f:
                f.write("""<robot name="j">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="0.5 0 0" rpy="0 0 0"/><mass value="2"/>
    <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.2" iyz="0" izz="0.3"/></inertial></link>
  <link name="tip"><inertial><origin xyz="0 0 0"/><mass value="1"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 1" rpy="0 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="fix" type="fixed"><parent link="arm"/><child link="tip"/>
    <origin xyz="1 0 0" rpy="0 0 0"/></joint>
</robot>""")
            s = glue.urdf_summary(path)
            hinge = {"link": "arm", "type": "revolute", "axis": [0.0, 0.0, 1.0], "origin": [0.0, 0.0, 1.0]}
            # izz + m r^2 of the arm (0.3 + 2 * 0.25) and the tip's point mass at 1 m
            self.assertAlmostEqual(glue.joint_inertia(s, hinge), 0.3 + 0.5 + 1.0)
            slide = dict(hinge, type="prismatic")
            self.assertAlmostEqual(glue.joint_inertia(s, slide), 3.0)
            tilted = dict(hinge, axis=[1.0, 0.0, 0.0])
            # ixx of the arm (its COM is on the x axis through the origin's height) + 0
            self.assertAlmostEqual(glue.joint_inertia(s, tilted), 0.1)
        finally:
            shutil.rmtree(tmp)

    def test_friction_effort(self):
        # fast: the full friction, against the motion
        self.assertEqual(glue.friction_effort(0.5, 2.0, 1.0, 0.002), -0.5)
        self.assertEqual(glue.friction_effort(0.5, -2.0, 1.0, 0.002), 0.5)
        # slow: only what removes half the velocity in one step
        self.assertAlmostEqual(glue.friction_effort(0.5, 1e-4, 1.0, 0.002), -0.025)
        self.assertEqual(glue.friction_effort(0.0, 1.0, 1.0, 0.002), 0.0)
        self.assertEqual(glue.friction_effort(0.5, 1.0, 0.0, 0.002), 0.0)


# ---------------------------------------------------------------------------
# 2. The command line (no Isaac Lab needed)

def run_main(argv, urdf, functions, object_name="toaster"):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = glue.main(argv, object_name=object_name, urdf_file=urdf, functions_file=functions)
    return code, out.getvalue(), err.getvalue()


class CommandLineTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.table = load_fixture("toaster_functions.json")
        self.urdf = os.path.join(self.tmp, "toaster.urdf")
        urdf_for(self.table, self.urdf)
        self.functions = fixture("toaster_functions.json")

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def test_help(self):
        code, out, _ = run_main(["--help"], self.urdf, self.functions)
        self.assertEqual(code, 0)
        for flag in ("--steps", "--dt", "--profile", "--duration", "--csv", "--headless", "--no-props"):
            self.assertIn(flag, out)

    def test_usage_errors(self):
        for argv in (["--steps", "0"], ["--dt", "-1"], ["--dt", "1"], ["--duration", "0"], ["--props", "-2"],
                     ["--steps", "x"]):
            code, _, err = run_main(argv, self.urdf, self.functions)
            self.assertEqual(code, 2, argv)
            self.assertTrue(err.strip(), argv)
            self.assertNotIn("Traceback", err)

    def test_bad_profile(self):
        code, _, err = run_main(["--profile", "wobble"], self.urdf, self.functions)
        self.assertEqual(code, 2)
        self.assertIn("profile", err)

    def test_bad_functions_file(self):
        bad = os.path.join(self.tmp, "bad_functions.json")
        with open(bad, "w") as f:
            f.write('{"format": "efc-functions"')
        code, _, err = run_main([], self.urdf, bad)
        self.assertEqual(code, 1)
        self.assertIn("bad_functions.json", err)
        code, _, err = run_main([], self.urdf, os.path.join(self.tmp, "missing.json"))
        self.assertEqual(code, 2)

    def test_csv_folder_missing(self):
        code, _, err = run_main(["--csv", os.path.join(self.tmp, "no", "log.csv")], self.urdf, self.functions)
        self.assertEqual(code, 2)
        self.assertIn("cannot write", err)

    def test_missing_urdf(self):
        code, _, err = run_main([], os.path.join(self.tmp, "nope.urdf"), self.functions)
        self.assertEqual(code, 2)
        self.assertIn("nope.urdf", err)

    def test_without_isaaclab(self):
        if "isaaclab" in sys.modules or _importable("isaaclab"):
            self.skipTest("Isaac Lab is installed here")
        code, _, err = run_main(["--steps", "5"], self.urdf, self.functions)
        self.assertEqual(code, 2)
        self.assertIn("Isaac Lab", err)


def _importable(name):
    import importlib.util
    return importlib.util.find_spec(name) is not None


# ---------------------------------------------------------------------------
# 3. A whole run against stand-ins

class FakeTensor:
    """Nested lists with the few tensor operations the glue uses."""

    def __init__(self, data):
        self.data = data

    def __getitem__(self, key):
        if isinstance(key, tuple):
            v = self.data
            for k in key:
                v = v[k]
            return FakeTensor(v) if isinstance(v, list) else v
        v = self.data[key]
        return FakeTensor(v) if isinstance(v, list) else v

    def __setitem__(self, key, value):
        key = key if isinstance(key, tuple) else (key,)
        v = self.data
        for k in key[:-1]:
            v = v[k]
        v[key[-1]] = float(value)

    def tolist(self):
        return json.loads(json.dumps(self.data))

    def clone(self):
        return FakeTensor(self.tolist())

    def any(self):
        def walk(v):
            return any(walk(x) for x in v) if isinstance(v, list) else v != 0
        return walk(self.data)


def _zeros(shape):
    if len(shape) == 1:
        return [0.0] * shape[0]
    return [_zeros(shape[1:]) for _ in range(shape[0])]


def _zeros_like(v):
    return [_zeros_like(x) for x in v] if isinstance(v, list) else 0.0


def make_fake_torch():
    torch = types.ModuleType("torch")
    torch.float32, torch.long = "float32", "long"
    torch.tensor = lambda data, dtype=None, device=None: FakeTensor(json.loads(json.dumps(data)))
    torch.zeros = lambda shape, dtype=None, device=None: FakeTensor(_zeros(list(shape)))
    torch.zeros_like = lambda t: FakeTensor(_zeros_like(t.data))
    return torch


class FakeAttr:
    def __init__(self, value=None):
        self.value = value
        self.sets = 0

    def Set(self, value):
        self.value = value
        self.sets += 1
        return True

    def Get(self):
        return self.value


class FakePrim:
    def __init__(self, stage, path, rigid=False):
        self.path, self.rigid, self.attrs = path, rigid, {}
        stage.prims[path] = self

    def GetPath(self):
        return self.path

    def GetName(self):
        return self.path.rsplit("/", 1)[-1]

    def HasAPI(self, api):
        return self.rigid and api == "RigidBodyAPI"

    def GetAttribute(self, name):
        return self.attrs.setdefault(name, FakeAttr())


class FakeWorld:
    """Everything the stand-ins share: prims, assets, and what the glue did."""

    def __init__(self):
        self.prims, self.assets, self.bindings, self.steps, self.renders = {}, [], [], 0, 0
        self.camera = None


def make_fake_isaaclab(world):
    def cfg_class(name, func=None, **defaults):
        def init(self, **kw):
            for k, v in defaults.items():
                setattr(self, k, v)
            for k, v in kw.items():
                setattr(self, k, v)
        attrs = {"__init__": init}
        if func is not None:
            attrs["func"] = staticmethod(func)
        return type(name, (), attrs)

    def spawn_light(path, cfg, translation=None, orientation=None, **kw):
        prim = FakePrim(world, path)
        prim.attrs["inputs:intensity"] = FakeAttr(float(cfg.intensity))
        prim.attrs["inputs:color"] = FakeAttr(tuple(cfg.color))
        prim.translation = translation
        return prim

    def spawn_surface(path, cfg):
        shader = FakePrim(world, path + "/Shader")
        shader.attrs["inputs:diffuseColor"] = FakeAttr(cfg.diffuse_color)
        shader.attrs["inputs:emissiveColor"] = FakeAttr(cfg.emissive_color)
        return shader

    def spawn_shape(path, cfg, translation=None, orientation=None, **kw):
        return FakePrim(world, path)

    sim = types.ModuleType("isaaclab.sim")
    sim.SimulationCfg = cfg_class("SimulationCfg", dt=1 / 60, device="cuda:0", render_interval=1)
    sim.DomeLightCfg = cfg_class("DomeLightCfg", spawn_light, intensity=1.0, color=(1.0, 1.0, 1.0))
    sim.SphereLightCfg = cfg_class("SphereLightCfg", spawn_light, intensity=1.0, color=(1.0, 1.0, 1.0))
    sim.PreviewSurfaceCfg = cfg_class("PreviewSurfaceCfg", spawn_surface, diffuse_color=(0.18, 0.18, 0.18),
                                      emissive_color=(0.0, 0.0, 0.0))
    sim.CuboidCfg = cfg_class("CuboidCfg", spawn_shape)
    sim.SphereCfg = cfg_class("SphereCfg", spawn_shape, rigid_props=None)
    sim.RigidBodyPropertiesCfg = cfg_class("RigidBodyPropertiesCfg", disable_gravity=None)
    sim.MassPropertiesCfg = cfg_class("MassPropertiesCfg")
    sim.CollisionPropertiesCfg = cfg_class("CollisionPropertiesCfg")
    sim.ArticulationRootPropertiesCfg = cfg_class("ArticulationRootPropertiesCfg")
    sim.UrdfFileCfg = cfg_class("UrdfFileCfg")
    pd = cfg_class("PDGainsCfg")
    drive = cfg_class("JointDriveCfg")
    drive.PDGainsCfg = pd
    sim.UrdfConverterCfg = type("UrdfConverterCfg", (), {"JointDriveCfg": drive})

    def get_all_matching_child_prims(path, predicate=lambda p: True, depth=None, stage=None,
                                     traverse_instance_prims=True):
        return [p for k, p in sorted(world.prims.items()) if k.startswith(path + "/") and predicate(p)]

    def bind_visual_material(prim_path, material_path, stage=None, stronger_than_descendants=True):
        world.bindings.append((prim_path, material_path, stronger_than_descendants))

    sim.get_all_matching_child_prims = get_all_matching_child_prims
    sim.bind_visual_material = bind_visual_material

    class SimulationContext:
        def __init__(self, cfg):
            self.cfg = cfg
            world.sim = self

        def set_camera_view(self, eye, target, camera_prim_path="/OmniverseKit_Persp"):
            world.camera = (eye, target)

        def reset(self, soft=False):
            for a in world.assets:
                a.initialize()

        def step(self, render=True):
            world.steps += 1
            for a in world.assets:
                a.physics(self.cfg.dt)

        def render(self, mode=None):
            world.renders += 1

        def has_gui(self):
            return True

    sim.SimulationContext = SimulationContext

    class ArticulationData:
        pass

    class Articulation:
        def __init__(self, cfg):
            self.cfg = cfg
            world.robot = self
            world.assets.append(self)
            root = ET.parse(cfg.spawn.asset_path).getroot()
            self.joint_names = [j.get("name") for j in root.findall("joint") if j.get("type") != "fixed"]
            self.body_names = [link.get("name") for link in root.findall("link")]
            self.origin = {}
            for j in root.findall("joint"):
                o = j.find("origin")
                xyz = [float(x) for x in o.get("xyz").split()] if o is not None else [0.0, 0.0, 0.0]
                self.origin[j.find("child").get("link")] = (j.find("parent").get("link"), xyz)
            for name in self.body_names:
                FakePrim(world, cfg.prim_path + "/" + name, rigid=True)
            self.device = "cuda:0"
            self.data = ArticulationData()
            self.targets = None

        def initialize(self):
            n = len(self.joint_names)
            self.data.joint_pos = FakeTensor([[0.0] * n])
            self.data.joint_vel = FakeTensor([[0.0] * n])
            self.efforts = None
            self.data.default_joint_pos = FakeTensor([[0.0] * n])
            self.stiffness = [0.0] * n
            for act in self.cfg.actuators.values():
                name = act.joint_names_expr[0].replace("\\", "")
                self.stiffness[self.joint_names.index(name)] = act.stiffness
            self.refresh()

        def refresh(self):
            pos = []
            for name in self.body_names:
                p, link = [0.0, 0.0, 0.0], name
                while link in self.origin:
                    parent, xyz = self.origin[link]
                    p = [p[i] + xyz[i] for i in range(3)]
                    link = parent
                pos.append(p)
            self.data.body_link_pos_w = FakeTensor([pos])
            self.data.body_link_quat_w = FakeTensor([[[1.0, 0.0, 0.0, 0.0] for _ in pos]])

        def write_joint_state_to_sim(self, position, velocity, joint_ids=None, env_ids=None):
            self.data.joint_pos = position.clone()

        def reset(self, env_ids=None):
            pass

        def set_joint_position_target(self, target, joint_ids=None, env_ids=None):
            self.targets = target.clone()

        def set_joint_effort_target(self, target, joint_ids=None, env_ids=None):
            self.efforts = target.clone()
            world.max_effort = max([getattr(world, "max_effort", 0.0)] + [abs(x) for x in target.data[0]])

        def write_data_to_sim(self):
            world.robot_writes = getattr(world, "robot_writes", 0) + 1

        def physics(self, dt):  # an ideal servo for every joint with a drive
            for k, s in enumerate(self.stiffness):
                if s > 0:
                    old = self.data.joint_pos[0, k]
                    self.data.joint_pos[0, k] = self.targets[0, k]
                    self.data.joint_vel[0, k] = (self.targets[0, k] - old) / dt

        def update(self, dt):
            self.refresh()

    class RigidObjectCfg:
        InitialStateCfg = cfg_class("InitialStateCfg", pos=(0.0, 0.0, 0.0))

        def __init__(self, prim_path, spawn=None, init_state=None):
            self.prim_path, self.spawn, self.init_state = prim_path, spawn, init_state

    class RigidObjectCollectionData:
        pass

    class RigidObjectCollection:
        def __init__(self, cfg):
            world.pool = self
            world.assets.append(self)
            self.names = list(cfg.rigid_objects)
            self.cfgs = list(cfg.rigid_objects.values())
            self.data = RigidObjectCollectionData()
            self.forces = None
            self.emitted = 0

        def initialize(self):
            self.pos = [list(c.init_state.pos) for c in self.cfgs]
            self.vel = [[0.0, 0.0, 0.0] for _ in self.cfgs]
            self.update(0.0)

        def write_object_link_pose_to_sim(self, object_pose, env_ids=None, object_ids=None):
            for row, n in zip(object_pose.data[0], object_ids.data):
                self.pos[n] = list(row[:3])

        def write_object_com_velocity_to_sim(self, object_velocity, env_ids=None, object_ids=None):
            for row, n in zip(object_velocity.data[0], object_ids.data):
                self.vel[n] = list(row[:3])
                if any(row[:3]):
                    self.emitted += 1

        def set_external_force_and_torque(self, forces, torques, positions=None, object_ids=None, env_ids=None,
                                          is_global=False):
            self.forces, self.is_global = forces.clone(), is_global
            peak = max(math.sqrt(sum(c * c for c in f)) for f in forces.data[0])
            self.max_force = max(getattr(self, "max_force", 0.0), peak)

        def write_data_to_sim(self):
            pass

        def physics(self, dt):
            for n, c in enumerate(self.cfgs):
                g = 0.0 if c.spawn.rigid_props.disable_gravity else -9.81
                f = self.forces.data[0][n] if self.forces is not None else [0.0, 0.0, 0.0]
                m = 1e-3
                acc = [f[0] / m, f[1] / m, f[2] / m + g]
                for i in range(3):
                    self.vel[n][i] += acc[i] * dt
                    self.pos[n][i] += self.vel[n][i] * dt

        def update(self, dt):
            self.data.object_link_pos_w = FakeTensor([[list(p) for p in self.pos]])

    assets = types.ModuleType("isaaclab.assets")
    assets.Articulation = Articulation
    assets.ArticulationCfg = cfg_class("ArticulationCfg")
    assets.ArticulationCfg.InitialStateCfg = cfg_class("InitialStateCfg")
    assets.RigidObjectCfg = RigidObjectCfg
    assets.RigidObjectCollection = RigidObjectCollection
    assets.RigidObjectCollectionCfg = cfg_class("RigidObjectCollectionCfg")

    actuators = types.ModuleType("isaaclab.actuators")
    actuators.ImplicitActuatorCfg = cfg_class("ImplicitActuatorCfg")

    class SimulationApp:
        def __init__(self):
            self.closed = False

        def is_running(self):
            return not self.closed

        def close(self):
            self.closed = True

    class AppLauncher:
        def __init__(self, launcher_args=None, **kwargs):
            world.launcher_args = launcher_args
            self.app = SimulationApp()
            world.app = self.app

        @staticmethod
        def add_app_launcher_args(parser):
            parser.add_argument("--headless", action="store_true")
            parser.add_argument("--device", default="cuda:0")
            parser.add_argument("--livestream", type=int, default=-1)

    app = types.ModuleType("isaaclab.app")
    app.AppLauncher = AppLauncher
    isaaclab = types.ModuleType("isaaclab")
    isaaclab.sim, isaaclab.assets, isaaclab.actuators, isaaclab.app = sim, assets, actuators, app

    pxr = types.ModuleType("pxr")
    pxr.Gf = types.SimpleNamespace(Vec3f=lambda *v: tuple(v))
    pxr.Usd = types.SimpleNamespace(Prim=FakePrim, Attribute=FakeAttr)
    pxr.UsdPhysics = types.SimpleNamespace(RigidBodyAPI="RigidBodyAPI")

    class ShadowAPI:
        def __init__(self, prim):
            self.prim = prim

        @staticmethod
        def Apply(prim):
            prim.attrs.setdefault("inputs:shadow:enable", FakeAttr(True))
            return ShadowAPI(prim)

        def CreateShadowEnableAttr(self, value):
            self.prim.attrs["inputs:shadow:enable"].Set(value)
            return self.prim.attrs["inputs:shadow:enable"]

    pxr.UsdLux = types.SimpleNamespace(ShadowAPI=ShadowAPI)
    return {"isaaclab": isaaclab, "isaaclab.sim": sim, "isaaclab.assets": assets,
            "isaaclab.actuators": actuators, "isaaclab.app": app, "pxr": pxr, "torch": make_fake_torch()}


@contextlib.contextmanager
def fake_simulator():
    world = FakeWorld()
    mods = make_fake_isaaclab(world)
    saved = {k: sys.modules.get(k) for k in mods}
    sys.modules.update(mods)
    try:
        yield world
    finally:
        for k, v in saved.items():
            if v is None:
                sys.modules.pop(k, None)
            else:
                sys.modules[k] = v


def read_csv(path):
    with open(path) as f:
        lines = f.read().splitlines()
    header = lines[0].split(",")
    return header, [[float(x) for x in line.split(",")] for line in lines[1:]]


class FakeRunTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def run_fixture(self, name, argv, stiff=False, friction=None):
        """Runs a fixture's table; stiff: receptor servos 1000x stiffer than the fixture's
        (its gains are test numbers that cannot hold the lever against its spring: the
        drive settles where servo and spring balance, as PhysX's would)."""
        with open(fixture(name)) as f:
            doc = json.load(f)
        if stiff:
            for j in doc["joints"]:
                if j["drive_by"] == "profile":
                    j["drive"]["kp"] *= 1000.0
        if friction is not None:
            for j in doc["joints"]:
                j["friction"] = friction
        functions = os.path.join(self.tmp, name)
        with open(functions, "w") as f:
            json.dump(doc, f)
        table = efc.load_functions(functions)
        urdf = os.path.join(self.tmp, table["object"] + ".urdf")
        urdf_for(table, urdf)
        csv = os.path.join(self.tmp, "log.csv")
        with fake_simulator() as world:
            code, out, err = run_main(argv + ["--csv", csv], urdf, functions, table["object"])
        self.assertEqual(code, 0, err)
        self.assertTrue(world.app.closed)
        header, rows = read_csv(csv)
        return table, world, header, rows, err

    def test_toaster_press(self):
        table, world, header, rows, _ = self.run_fixture(
            "toaster_functions.json", ["--steps", "3000", "--profile", "press:3", "--headless"], stiff=True)
        self.assertEqual(world.steps, 3000)
        self.assertEqual(len(rows), 3000)
        self.assertEqual(header, ["t", "lower.s_R", "lower.s_E", "lower.measured",
                                  "toast.s_R", "toast.s_E", "toast.measured"])
        self.assertEqual(world.launcher_args.device, "cuda:0")
        self.assertTrue(world.launcher_args.headless)
        col = {h: k for k, h in enumerate(header)}
        # the carriage follows s_E one step later (the stand-in is an ideal servo)
        self.assertGreater(max(r[col["lower.s_E"]] for r in rows), 0.0)
        for prev, row in zip(rows, rows[1:]):
            self.assertAlmostEqual(row[col["lower.measured"]], prev[col["lower.s_E"]], places=9)
        # three presses: the carriage went down and came back up three times
        downs = sum(1 for prev, row in zip(rows, rows[1:])
                    if prev[col["lower.s_E"]] == 0.0 and row[col["lower.s_E"]] > 0.0)
        self.assertEqual(downs, 3)
        # temperature: measured is the lagged state (rising while on), the glow material
        # was bound to the effector link and its colours set
        self.assertGreater(max(r[col["toast.measured"]] for r in rows), rows[0][col["toast.measured"]])
        self.assertEqual(len(world.bindings), 1)
        self.assertTrue(world.bindings[0][0].endswith("/elements"))
        shader = world.prims["/World/Looks/efc_glow_1/Shader"]
        self.assertGreater(shader.attrs["inputs:diffuseColor"].sets, 1)

    def test_all_kinds(self):
        table, world, header, rows, err = self.run_fixture(
            "all_kinds_functions.json", ["--steps", "2500", "--dt", "0.002", "--profile", "sweep", "--props", "2"],
            stiff=True)
        col = {h: k for k, h in enumerate(header)}
        fns = {fn["name"]: fn for fn in table["functions"]}
        # illumination: lumens read back from the light prim's inputs:intensity
        for name in ("binary_illumination", "linear_illumination"):
            for r in rows:
                self.assertAlmostEqual(r[col[name + ".measured"]], r[col[name + ".s_E"]], delta=1e-6)
        light = [p for k, p in world.prims.items() if k.endswith("/efc_light_1")][0]
        self.assertTrue(light.path.startswith("/World/efc_object/body/"))
        self.assertEqual(light.translation, (0.0, 0.0, 0.02))
        self.assertIs(light.attrs["inputs:shadow:enable"].value, False)
        # the lamp's effector part glows in the light's colour while it is on
        lamp = world.prims["/World/Looks/efc_glow_1/Shader"]
        self.assertGreater(lamp.attrs["inputs:emissiveColor"].sets, 0)
        self.assertIn(("/World/efc_object/body", "/World/Looks/efc_glow_1", True), world.bindings)
        # fluid: droplets were emitted and the flow measured from them
        self.assertGreater(world.pool.emitted, 0)
        self.assertGreater(max(r[col["linear_fluid.measured"]] for r in rows), 0.0)
        # airflow: measured is the outlet speed; the props got pushed along -z
        fn = fns["linear_airflow"]
        for r in rows:
            self.assertEqual(r[col["linear_airflow.measured"]],
                             efc.air_speed_at(r[col["linear_airflow.s_E"]], 0.0, 0.0, fn["cone_angle"], fn["reach"])
                             if fn["effect"]["time_constant"] == 0 else r[col["linear_airflow.measured"]])
        self.assertGreater(max(r[col["linear_airflow.measured"]] for r in rows), 0.0)
        self.assertTrue(world.pool.is_global)
        self.assertGreater(world.pool.max_force, 0.0)
        # flow counted from spawned droplets: on average the templates' flow (the replay's
        # measured is the effect's state, with ideal joints)
        replay = efc.replay(table, efc.parse_profile("sweep"), 2500 * 0.002, 0.002)
        k = replay.columns.index("linear_fluid.measured")
        want = sum(r[k] for r in replay.rows[500:2400]) / 1900
        got = sum(r[col["linear_fluid.measured"]] for r in rows[500:2400]) / 1900
        self.assertGreater(want, 0.0)
        self.assertAlmostEqual(got / want, 1.0, delta=0.05)
        pool_names = world.pool.names
        self.assertEqual(sum(1 for n in pool_names if n.startswith("efc_prop_")), 2 * 4)
        self.assertEqual(sum(1 for n in pool_names if n.startswith("efc_drop_")),
                         sum(fn["droplet_pool"] for fn in table["functions"] if fn["effect"]["kind"] == "fluid"))
        self.assertEqual(world.renders, 2500 // glue.render_every(0.002))

    def test_no_props_and_no_profile(self):
        table, world, header, rows, _ = self.run_fixture("all_kinds_functions.json", ["--steps", "20", "--no-props"])
        self.assertFalse(any(n.startswith("efc_prop_") for n in world.pool.names))
        # without --profile the receptors are not servoed: only their springs pull them
        self.assertEqual(len(rows), 20)

    def test_friction_is_an_effort(self):
        _, world, _, rows, err = self.run_fixture("toaster_functions.json", ["--steps", "300", "--profile", "sweep"],
                                                  stiff=True, friction=0.2)
        self.assertGreater(world.max_effort, 0.0)
        self.assertLessEqual(world.max_effort, 0.2)
        self.assertNotIn("warning", err)

    def test_chain(self):
        self.run_fixture("chain_functions.json", ["--steps", "500", "--profile", "ramp"], stiff=True)


if __name__ == "__main__":
    unittest.main()
