"""Tests of extract_api.py and check_api.py.

    python3 -m unittest discover -s tests/sim_api

A tiny fake simulator package is written to a temporary folder, extracted with
extract_api.py (as a subprocess, the way the indices are made) and scripts are checked
against it. The last tests use the committed Genesis index.
"""

import json
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import check_api  # noqa: E402

FAKE = {
    "fakesim/__init__.py": """
        from .core import Scene, make_scene
        from . import cfg
        from .entities import *
        import fakesim.utils as utils
        __version__ = "1.0"

        def init(*, backend=None, seed=None):
            pass
        """,
    "fakesim/core.py": """
        from typing import TYPE_CHECKING, overload
        from .entities import Entity

        if TYPE_CHECKING:
            from .entities.base import RigidEntity


        class Scene:
            default_dt = 0.01

            def __init__(self, dt=0.01, *, gravity=(0.0, 0.0, -9.81), show_viewer=False):
                self.dt = dt
                self._private = 1

            def add_entity(self, morph, name=None) -> "RigidEntity":
                pass

            def build(self):
                pass

            @overload
            def add(self, morph, material: None = None) -> "RigidEntity": ...

            @overload
            def add(self, morph, material: "Material" = None) -> "Entity": ...

            def add(self, morph, material=None) -> "Entity":
                pass

            def step(self, n=1):
                pass

            @property
            def sim(self):
                return self._sim

            def lookup(self, name):
                pass

            def copy(self) -> "Scene":
                pass

            @staticmethod
            def version():
                pass


        def make_scene(**kwargs) -> Scene:
            return Scene(**kwargs)
        """,
    "fakesim/entities/__init__.py": """
        from .base import *
        """,
    "fakesim/entities/base.py": """
        __all__ = ["Entity", "RigidEntity", "Joint"]


        class _Mixin:
            def helper(self, x, /, y=0):
                pass


        class Entity(_Mixin):
            def get_pos(self):
                pass


        class RigidEntity(Entity):
            def __init__(self, scene):
                self.n_dofs = 0

            def set_dofs_kp(self, kp, dofs_idx=None, *, envs_idx=None):
                pass

            def get_joint(self, name) -> "Joint":
                pass


        class DroneEntity(RigidEntity):
            def set_propellers_rpm(self, rpm):
                pass


        class Joint:
            def __getattr__(self, name):
                if name == "dof_idx":
                    return self.dofs_idx
                raise AttributeError(name)

            @property
            def dofs_idx(self):
                pass

        class NotExported:
            pass
        """,
    "fakesim/utils.py": """
        def configclass(cls):
            return cls
        """,
    "fakesim/cfg.py": """
        from dataclasses import dataclass, field
        from pydantic import BaseModel
        from fakesim.utils import configclass
        from .not_downloaded import Thing
        import missing_module

        MISSING = object()


        @configclass
        class AssetCfg:
            prim_path: str = MISSING
            scale = 1.0

            def validate(self):
                pass


        @configclass
        class ArticulationCfg(AssetCfg):
            init_pos: tuple = (0.0, 0.0, 0.0)
            spawn = None


        @dataclass
        class DC:
            a: int
            b: int = 2
            c: int = field(default=0, init=False)


        class Opts(BaseModel):
            dt: float = 0.01
            substeps: int = 1


        class Partial(missing_module.Base):
            def own(self):
                pass
        """,
}


def write_tree(root, files):
    for rel, text in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(textwrap.dedent(text))


def extract(root, out, packages, extra=()):
    cmd = [sys.executable, os.path.join(HERE, "extract_api.py"), "--root", root,
           "--name", "Fake", "--version", "1.0", "--source-url", "file://fake",
           "--commit", "0" * 40, "--out", out, "--date", "2000-01-01"] + list(extra)
    for p in packages:
        cmd += ["--package", p]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)


class FakeSimTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        write_tree(cls.tmp.name, FAKE)
        cls.index_path = os.path.join(cls.tmp.name, "fake.json")
        cls.index = extract(cls.tmp.name, cls.index_path, ["fakesim"],
                            ["--unchecked", "fakesim.cfg_usd=USD attributes are strings"])

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def check(self, src):
        return check_api.check_source(textwrap.dedent(src), "script.py", self.index)

    def assertErrors(self, src, *fragments):
        problems = self.check(src)
        text = "\n".join(map(str, problems))
        self.assertEqual(len(problems), len(fragments), text)
        for frag in fragments:
            self.assertIn(frag, text)
        return problems

    # ------------------------------------------------------------------ extractor
    def test_provenance(self):
        prov = self.index["provenance"]
        self.assertEqual(prov["simulator"], "Fake")
        self.assertEqual(prov["commit"], "0" * 40)
        self.assertEqual(prov["extracted"], "2000-01-01")
        self.assertIn("extract_api.py", prov["command"])
        self.assertEqual(self.index["unchecked_modules"], {"fakesim.cfg_usd": "USD attributes are strings"})

    def test_index_contents(self):
        mods = self.index["modules"]
        scene = mods["fakesim.core"]["cls"]["Scene"]
        self.assertEqual(scene["m"]["__init__"], {"a": ["self", "dt="], "ko": ["gravity=", "show_viewer="]})
        self.assertEqual(scene["m"]["sim"]["k"], "p")
        self.assertEqual(scene["m"]["version"]["k"], "s")
        self.assertEqual(scene["m"]["add_entity"]["rt"], "fakesim.entities.base.RigidEntity")
        self.assertEqual(scene["ia"], ["dt"])                       # self._private dropped
        self.assertNotIn("_private", json.dumps(scene))
        base = mods["fakesim.entities.base"]
        self.assertEqual(base["all"], ["Entity", "RigidEntity", "Joint"])
        self.assertIn("_Mixin", base["cls"])                        # kept: a base class
        self.assertEqual(base["cls"]["_Mixin"]["m"]["helper"], {"a": ["self", "x", "y="], "po": 2})
        self.assertEqual(base["cls"]["Joint"]["xa"], ["dof_idx"])   # closed __getattr__
        self.assertEqual(mods["fakesim.entities"]["star"], ["fakesim.entities.base"])
        cfg = mods["fakesim.cfg"]
        self.assertEqual(cfg["cls"]["AssetCfg"]["dc"], "configclass")
        self.assertEqual(cfg["cls"]["Partial"]["b"], ["missing_module.Base"])
        self.assertEqual(cfg["n"]["Thing"], {"a": "fakesim.not_downloaded.Thing"})
        self.assertNotIn("RigidEntity", mods["fakesim.core"].get("n", {}))  # TYPE_CHECKING only

    def test_partial_tree(self):
        # a tree with a missing __init__.py and dangling re-exports extracts and checks
        with tempfile.TemporaryDirectory() as d:
            write_tree(d, {"part/sub/mod.py": "from ..gone import Base\nclass C(Base):\n    pass\n",
                           "part/__init__.py": "from .sub.mod import C\nfrom .absent import *\n"})
            idx = extract(d, os.path.join(d, "p.json"), ["part"])
            self.assertIn("part.sub", idx["modules"])
            probs = check_api.check_source(
                "import part\nc = part.C(1, 2, x=3)\nc.anything\npart.whatever\nfrom part.sub.mod import C\n",
                "s.py", idx)
            self.assertEqual(probs, [])

    def test_lazy_loader_stub(self):
        # Isaac Lab style: __init__.py hands its names to lazy_loader, __init__.pyi lists them
        with tempfile.TemporaryDirectory() as d:
            write_tree(d, {
                "lz/__init__.py": "import lazy_loader as lazy\n"
                                  "__getattr__, __dir__, __all__ = lazy.attach_stub(__name__, __file__)\n",
                "lz/__init__.pyi": "from .impl import Foo\n__all__ = ['Foo']\n",
                "lz/impl.py": "class Foo:\n    def bar(self, x):\n        pass\n",
                "only_py/__init__.py": "import lazy_loader as lazy\n"
                                       "__getattr__, __dir__, __all__ = lazy.attach_stub(__name__, __file__)\n"})
            idx = extract(d, os.path.join(d, "l.json"), ["lz", "only_py"])
            probs = check_api.check_source(
                "import lz, only_py\nlz.Foo().bar(1)\nlz.Nope\nlz.Foo().bar(1, 2)\nonly_py.Anything\n", "s.py", idx)
            self.assertEqual([p.line for p in probs], [3, 4], "\n".join(map(str, probs)))

    # ------------------------------------------------------------------ errors
    def test_misspelt_method(self):
        self.assertErrors("""
            import fakesim as fs
            scene = fs.Scene()
            scene.add_entiy("m")
            """, "has no attribute 'add_entiy'")

    def test_misspelt_keyword(self):
        self.assertErrors("""
            import fakesim as fs
            scene = fs.Scene(dt=0.01, gravty=(0, 0, -1))
            scene.add_entity("m", nme="x")
            """, "unexpected keyword argument 'gravty'", "unexpected keyword argument 'nme'")

    def test_missing_module_attribute(self):
        self.assertErrors("""
            import fakesim
            from fakesim.entities import NotExported, Nope
            from fakesim import nothing
            import fakesim.nomodule
            s = fakesim.Scen()
            """, "cannot import name 'NotExported'",   # not in base.__all__: `import *` skips it
            "cannot import name 'Nope'", "cannot import name 'nothing'", "no module 'fakesim.nomodule'",
            "module 'fakesim' has no attribute 'Scen'")

    def test_too_many_positional(self):
        self.assertErrors("""
            import fakesim as fs
            scene = fs.Scene(0.01, (0, 0, -1))
            scene.step(1, 2)
            fs.Scene.version(1)
            """, "Scene() takes at most 1 positional argument, 2 given",
            "Scene.step() takes at most 1 positional argument, 2 given",
            "Scene.version() takes at most 0 positional arguments, 1 given")

    def test_unannotated_sim_object(self):
        self.assertErrors("""
            import fakesim as fs
            scene = fs.Scene()
            e = scene.lookup("x")
            e.get_pos()
            scene.sim.rigid_solver
            """, "'.get_pos' used on 'e' (the result of scene.lookup())", "'.rigid_solver' used on the result of property Scene.sim")

    def test_misspelt_configclass_field(self):
        self.assertErrors("""
            from fakesim import cfg
            a = cfg.ArticulationCfg(prim_pat="/World/x", spawn=None)
            d = cfg.DC(1, 2, c=3)
            o = cfg.Opts(dt=0.1, substep=2)
            cfg.Opts(0.1)
            """, "ArticulationCfg() has no field or keyword 'prim_pat'",
            "DC() has no field or keyword 'c'", "Opts() has no field or keyword 'substep'",
            "Opts() takes at most 0 positional arguments, 1 given")

    def test_annotation_and_positional_only(self):
        self.assertErrors("""
            def run(scene: "fs.Scene"):
                import fakesim as fs
                robot = scene.add_entity("m")
                robot.helper(x=1)
                robot.set_dofs_kp(1.0, envs_idx=None, dofs=[0])
                j: "fs.entities.Joint" = robot.get_joint("j")
                j.dof_idx
                j.dofs_idz
            """, "'x' is positional-only", "unexpected keyword argument 'dofs'",
            "'Joint' (fakesim.entities.base.Joint) has no attribute 'dofs_idz'")

    def test_overloads_and_declared_types(self):
        self.assertErrors("""
            import fakesim as fs
            scene = fs.Scene()
            a = scene.add("m")                   # first variant: material omitted -> RigidEntity
            a.set_dofs_kp(1.0)
            scene.add("m", None).set_dofs_kp(1.0)
            b = scene.add("m", material=object())   # second variant -> Entity
            b.get_pos()
            b.set_dofs_kp(1.0)                   # on subclasses of Entity only
            a.set_propellers_rpm(1.0)            # a DroneEntity, maybe: the source promises less
            d: "fs.entities.base.DroneEntity" = scene.add("drone")
            d.set_propellers_rpm(1.0)
            a.no_such_thing
            """, "'.set_dofs_kp' is not on 'Entity', the type scene.add() is declared to give",
            "'.set_propellers_rpm' is not on 'RigidEntity', the type scene.add() is declared to give",
            "'RigidEntity' (fakesim.entities.base.RigidEntity) has no attribute 'no_such_thing'")

    def test_self_attributes_of_script_classes(self):
        self.assertErrors("""
            import fakesim as fs
            class Runner:
                scene: "fs.Scene"
                def __init__(self):
                    self.scene = fs.Scene()
                    self.robot = self.scene.add_entity("m")
                    self.thing = self.scene.lookup("t")
                def go(self):
                    self.scene.stepp()
                    self.robot.get_pos()
                    self.robot.get_po()
                    self.thing.x
            """, "'Scene' (fakesim.core.Scene) has no attribute 'stepp'",
            "'RigidEntity' (fakesim.entities.base.RigidEntity) has no attribute 'get_po'",
            "'.x' used on the result of self.scene.lookup()")

    # ------------------------------------------------------------------ correct code
    def test_correct_code_passes(self):
        self.assertErrors("""
            import json

            def build(headless):
                import fakesim as fs
                from fakesim import RigidEntity, Entity, make_scene
                from fakesim.entities import Joint
                from fakesim.cfg import ArticulationCfg, DC, Opts, Partial, Thing
                fs.init(seed=1)
                scene = fs.Scene(0.01, gravity=(0, 0, -9.81), show_viewer=not headless)
                robot = scene.add_entity("m", name="r")           # typed by the return annotation
                robot.get_pos()                                   # inherited from Entity
                robot.helper(1, y=2)                              # from a private base class
                robot.set_dofs_kp([1.0], [0], envs_idx=None)
                robot.n_dofs                                      # self.n_dofs = ... in __init__
                j: "Joint" = robot.get_joint("a")
                j.dofs_idx, j.dof_idx                             # property; closed __getattr__
                s2 = scene.copy().copy()
                s2.build()
                scene.default_dt, scene.dt, fs.__version__
                fs.utils.configclass
                fs.entities.base.Entity                           # submodules
                make_scene(anything=1).step()
                cfg = ArticulationCfg(prim_path="/World/o", scale=2.0, init_pos=(0, 0, 1), spawn=None)
                cfg.validate()
                DC(1, b=3)
                Opts(dt=0.002, substeps=2).model_dump()
                p = Partial()
                p.whatever_from_the_missing_base()               # unresolved base: not checked
                Thing(1, 2, 3).x                                  # unresolved re-export
                data = json.loads("{}")
                data.get("x")
                fs.Scene.step(scene, 2)                           # unbound method
                return scene

            class Holder:
                def __init__(self, scene: "fakesim.Scene"):
                    self.scene = scene
                def tick(self):
                    self.scene.step(n=2)
            """)

    def test_unchecked_modules_and_fallbacks(self):
        self.assertErrors("""
            try:
                from fakesim.old_name import Scene
            except ImportError:
                from fakesim.older_name import Scene
            """, "no module 'fakesim.old_name'")
        self.assertErrors("""
            import fakesim.cfg_usd as u
            u.Anything(x=1).y
            import pxr
            pxr.Usd.Stage.Open("x").GetPrimAtPath("/x")
            """)

    def test_version_guards(self):
        self.assertErrors("""
            import fakesim as fs
            scene = fs.Scene()
            if hasattr(scene, "add_light") and True:
                scene.add_light((0, 0, 1))
            try:
                scene.add_mesh_light()
            except AttributeError:
                pass
            scene.add_light((0, 0, 1))
            """, "has no attribute 'add_light'")

    def test_command_line(self):
        bad = os.path.join(self.tmp.name, "bad.py")
        good = os.path.join(self.tmp.name, "good.py")
        with open(bad, "w") as f:
            f.write("import fakesim\nfakesim.Scene().stepp()\n")
        with open(good, "w") as f:
            f.write("import fakesim\nfakesim.Scene().step()\n")
        script = os.path.join(HERE, "check_api.py")
        r = subprocess.run([sys.executable, script, "--index", self.index_path, bad, good],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertRegex(r.stdout, r"bad\.py:2:1: error: 'Scene' .* has no attribute 'stepp'")
        r = subprocess.run([sys.executable, script, "--index", self.index_path, good],
                           capture_output=True, text=True)
        self.assertEqual((r.returncode, r.stdout), (0, ""))
        r = subprocess.run([sys.executable, script, good], capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)


GENESIS_INDEX = os.path.join(HERE, "genesis-0.4.5.json")

GENESIS_SNIPPET = """
import genesis as gs

def main(urdf, headless):
    gs.init(backend=gs.cpu, logging_level="warning")
    scene = gs.Scene(
        sim_options=gs.options.SimOptions(dt=0.002, substeps=1),
        vis_options=gs.options.VisOptions(show_world_frame=False),
        show_viewer=not headless,
    )
    scene.add_entity(gs.morphs.Plane())
    robot: "gs.engine.entities.RigidEntity" = scene.add_entity(gs.morphs.URDF(file=urdf, fixed=True))
    emitter: "gs.engine.entities.Emitter" = scene.add_emitter(material=gs.materials.SPH.Liquid(), max_particles=1000,
                                                              surface=gs.surfaces.Glass(color=(0.6, 0.8, 1.0, 1.0)))
    scene.add_entity(gs.morphs.Box(size=(0.1, 0.1, 0.1)), surface=gs.surfaces.Emission(emissive=(1.0, 0.5, 0.2)))
    scene.build()
    joint: "gs.engine.entities.rigid_entity.RigidJoint" = robot.get_joint("lever")
    dofs = [joint.dofs_idx_local[0]]
    robot.set_dofs_kp([100.0], dofs)
    robot.set_dofs_kv([1.0], dofs)
    for _ in range(10):
        robot.control_dofs_position([0.01], dofs)
        scene.step()
        q = robot.get_dofs_position(dofs)
    solver: "gs.engine.solvers.RigidSolver" = scene.sim.rigid_solver
    solver.apply_links_external_force([[0.0, 0.0, 1.0]], links_idx=[0])
    scene.sim.rigid_solver.apply_links_external_torque([[0.0, 0.0, 1.0]], links_idx=[0], local=True)
    emitter.emit(droplet_shape="circle", droplet_size=0.01, pos=(0.0, 0.0, 1.0), direction=(0.0, 0.0, -1.0), speed=1.0)
"""


@unittest.skipUnless(os.path.exists(GENESIS_INDEX), "genesis-0.4.5.json not present")
class GenesisIndexTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.index = check_api.load_index(GENESIS_INDEX)

    def test_correct_snippet_passes(self):
        problems = check_api.check_source(GENESIS_SNIPPET, "genesis_ok.py", self.index)
        self.assertEqual(problems, [], "\n".join(map(str, problems)))

    def test_misspelt_keyword_fails(self):
        bad = GENESIS_SNIPPET.replace("gs.morphs.URDF(file=urdf, fixed=True)",
                                      "gs.morphs.URDF(file=urdf, fix=True)")
        problems = check_api.check_source(bad, "genesis_bad.py", self.index)
        self.assertEqual(len(problems), 1, "\n".join(map(str, problems)))
        self.assertIn("URDF() has no field or keyword 'fix'", problems[0].message)
        self.assertEqual(problems[0].line, 12)

    def test_provenance(self):
        prov = self.index.data["provenance"]
        self.assertEqual(prov["simulator"], "Genesis")
        self.assertEqual(prov["version"], "0.4.5")
        self.assertEqual(len(prov["commit"]), 40)


if __name__ == "__main__":
    unittest.main()
