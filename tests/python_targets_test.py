#!/usr/bin/env python3
"""The Python targets end to end, with the efc program the build made.

    python_targets_test.py EFC_BINARY SOURCE_DIR

- every example compiles for genesis, isaaclab and omnigibson; every emitted .py
  byte-compiles, and every script answers --help with no simulator installed (its
  module-level code runs);
- every script is checked against its simulator's API index (tests/sim_api/), and the
  check fails on a misspelt method or keyword (each target's mutants);
- `python3 efc_templates.py <name>_functions.json` replays every example under every
  profile to the same bytes as `efc replay` (the C++ runtime);
- no generated file names an absolute path;
- `--target all` writes all six targets at once, all or nothing;
- specs whose names and free text try to inject code produce files that byte-compile
  and execute nothing.
Exit 1 with every failure listed.
"""
import ast
import glob
import json
import os
import py_compile
import shutil
import subprocess
import sys
import tempfile
import unittest

EFC = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else "build/efc"
SOURCE = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else "."
sys.path.insert(0, os.path.join(SOURCE, "tests", "sim_api"))
import check_api  # noqa: E402

TARGETS = ("genesis", "isaaclab", "omnigibson")
INDEX = {t: os.path.join(SOURCE, "tests", "sim_api", f) for t, f in
         (("genesis", "genesis-0.4.5.json"), ("isaaclab", "isaaclab-2.3.json"),
          ("omnigibson", "omnigibson-3.7.json"))}
PROFILES = ("ramp", "sweep", "press:3", "hold:lo", "hold:hi", "hold:0.01", "csv")
# (original text in the glue, a misspelling the API check must catch)
MUTANTS = {
    "genesis": [("control_dofs_position(", "control_dof_position("),
                ("fixed=True, links_to_keep", "fix=True, links_to_keep")],
    "isaaclab": [("robot.set_joint_position_target(", "robot.set_joint_position_targets("),
                 ("fix_base=True,", "fixed_base=True,")],
    "omnigibson": [("water.generate_particles(", "water.generate_particle("),
                   ("velocities=th.tensor(", "velocity=th.tensor(")],
}


def efc(*args, cwd=None):
    return subprocess.run([EFC, *args], cwd=cwd, capture_output=True, text=True)


def examples():
    return sorted(glob.glob(os.path.join(SOURCE, "examples", "*.json")))


class PythonTargets(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="efc-python-targets-")
        cls.out = os.path.join(cls.tmp, "out")
        r = efc("compile", *examples(), "--target", "genesis", "--target", "isaaclab",
                "--target", "omnigibson", "-o", cls.out)
        assert r.returncode == 0, r.stderr
        cls.indices = {t: check_api.load_index(INDEX[t]) for t in TARGETS}

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def folders(self):
        for spec in examples():
            name = os.path.splitext(os.path.basename(spec))[0]
            for t in TARGETS:
                yield name, t, os.path.join(self.out, name, t)

    def test_every_example_has_every_file_and_byte_compiles(self):
        for name, t, folder in self.folders():
            with self.subTest(example=name, target=t):
                for f in (f"{name}.urdf", f"{name}_functions.json", "efc_templates.py",
                          f"{name}_{t}.py", "README.md"):
                    self.assertTrue(os.path.isfile(os.path.join(folder, f)), f)
                for py in glob.glob(os.path.join(folder, "*.py")):
                    py_compile.compile(py, cfile=os.path.join(self.tmp, "x.pyc"), doraise=True)

    def test_every_script_runs_its_help_without_the_simulator(self):
        for name, t, folder in self.folders():
            with self.subTest(example=name, target=t):
                r = subprocess.run([sys.executable, f"{name}_{t}.py", "--help"], cwd=folder,
                                   capture_output=True, text=True, timeout=60)
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertIn("--profile", r.stdout)
                self.assertIn("--csv", r.stdout)

    def test_every_script_uses_only_its_simulators_real_api(self):
        for name, t, folder in self.folders():
            with self.subTest(example=name, target=t):
                path = os.path.join(folder, f"{name}_{t}.py")
                with open(path, encoding="utf-8") as f:
                    problems = check_api.check_source(f.read(), path, self.indices[t])
                self.assertEqual([str(p) for p in problems], [])

    def test_the_api_check_catches_a_misspelt_method_or_keyword(self):
        for t in TARGETS:
            path = os.path.join(self.out, "toaster", t, f"toaster_{t}.py")
            with open(path, encoding="utf-8") as f:
                text = f.read()
            for good, bad in MUTANTS[t]:
                with self.subTest(target=t, mutant=bad):
                    self.assertIn(good, text, "the mutant no longer applies: pick another")
                    problems = check_api.check_source(text.replace(good, bad, 1), path, self.indices[t])
                    self.assertTrue(problems, f"{bad} was not caught")

    def test_python_replay_matches_the_cpp_runtime_on_every_example_and_profile(self):
        csv_profile = os.path.join(self.tmp, "profile.csv")
        with open(csv_profile, "w") as f:
            f.write("t,lever,handle,knob,button,door\n0,0,0,0,0,0\n1,0.02,0.3,1,0.004,0.5\n"
                    "2,0.01,0.6,3,0.001,1\n")
        compared = 0
        for spec in examples():
            name = os.path.splitext(os.path.basename(spec))[0]
            folder = os.path.join(self.out, name, "genesis")
            for profile in PROFILES:
                p = "csv:" + csv_profile if profile == "csv" else profile
                with self.subTest(example=name, profile=profile):
                    cpp, py = os.path.join(self.tmp, "cpp.csv"), os.path.join(self.tmp, "py.csv")
                    r = efc("replay", spec, "--profile", p, "--duration", "3", "--csv", cpp)
                    self.assertEqual(r.returncode, 0, r.stderr)
                    r = subprocess.run([sys.executable, "efc_templates.py", f"{name}_functions.json",
                                        "--profile", p, "--duration", "3", "--csv", py],
                                       cwd=folder, capture_output=True, text=True)
                    self.assertEqual(r.returncode, 0, r.stderr)
                    with open(cpp) as a, open(py) as b:
                        ta, tb = a.read(), b.read()
                    self.assertGreater(ta.count("\n"), 1000)
                    self.assertEqual(ta, tb)
                    compared += 1
        self.assertEqual(compared, len(examples()) * len(PROFILES))

    def test_no_generated_file_names_an_absolute_path(self):
        for name, t, folder in self.folders():
            for path in glob.glob(os.path.join(folder, "*")):
                if os.path.isdir(path):
                    continue
                with open(path, "rb") as f:
                    data = f.read()
                for absolute in (self.tmp.encode(), SOURCE.encode()):
                    self.assertNotIn(absolute, data, f"{path} names {absolute!r}")

    def test_aliases_write_the_folder_the_user_named(self):
        out = os.path.join(self.tmp, "aliases")
        r = efc("compile", os.path.join(SOURCE, "examples", "toaster.json"), "--target", "isaac",
                "--target", "behavior", "--target", "isaaclab", "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(os.listdir(out)), ["behavior", "isaac"])  # isaaclab: the same target
        self.assertTrue(os.path.isfile(os.path.join(out, "isaac", "toaster_isaaclab.py")))
        self.assertTrue(os.path.isfile(os.path.join(out, "behavior", "toaster_omnigibson.py")))

    def test_target_all_writes_all_six_targets_or_nothing(self):
        out = os.path.join(self.tmp, "all")
        toaster = os.path.join(SOURCE, "examples", "toaster.json")
        r = efc("compile", toaster, "--target", "all", "-o", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(os.listdir(out)),
                         ["bullet", "genesis", "isaaclab", "mujoco", "omnigibson", "urdf"])
        bad = os.path.join(self.tmp, "bad.json")
        with open(bad, "w") as f:
            f.write('{"efc": 1, "name": "bad", "parts": []}')
        fresh = os.path.join(self.tmp, "fresh")
        r = efc("compile", toaster, bad, "--target", "all", "-o", fresh)
        self.assertEqual(r.returncode, 1)
        self.assertFalse(os.path.exists(fresh))
        self.assertEqual([x for x in os.listdir(self.tmp) if x.startswith(".efc-staging")], [])


# A spec that tries every way into generated Python: Python keywords and dunder
# names (valid efc names), quotes, backslashes, triple quotes, newlines, code and
# unicode look-alikes in the free text and in the spec's own file name.
EVIL_TEXT = ("x\"\"\"; __import__('os').system('touch PWNED') #\n'''\\\n"
             "\u0435x\u0435c('touch PWNED')\u2028\u0000 \ufeff end\\")
EVIL_FILE = "evil\"\"\"__import__('os').system('touch PWNED')#\u0430.json"


def evil_spec():
    return {
        "efc": 1, "name": "__import__", "description": EVIL_TEXT,
        "parts": [
            {"name": "None", "role": "base", "geometry": {"box": {"size": [0.2, 0.2, 0.05]}}},
            {"name": "class", "role": "receptor",
             "geometry": {"box": {"size": [0.02, 0.02, 0.02], "center": [0, 0, 0.05]}},
             "joint": {"type": "prismatic", "parent": "None", "axis": [0, 0, -1], "range": [0, 0.01]}},
            {"name": "lambda", "role": "effector",
             "geometry": {"sphere": {"radius": 0.02, "center": [0, 0, 0.2]}},
             "joint": {"type": "fixed", "parent": "None"}},
            {"name": "exec", "role": "effector",
             "geometry": {"box": {"size": [0.05, 0.02, 0.02], "center": [0.1, 0, 0.1]}},
             "joint": {"type": "revolute", "parent": "None", "axis": [0, 1, 0], "origin": [0.1, 0, 0.1],
                       "range": [0, 1]}}],
        "functions": [
            {"name": "print", "receptor": "class", "effector": "lambda",
             "mapping": {"type": "binary"}, "effect": {"type": "illumination"},
             "x-note": EVIL_TEXT},
            {"name": "True", "receptor": "class", "effector": "exec",
             "mapping": {"type": "linear"}, "effect": {"type": "geometry"}},
            {"name": "sys", "receptor": "exec", "effector": "lambda",
             "mapping": {"type": "step"}, "effect": {"type": "fluid"}}]}


class Injection(unittest.TestCase):
    def test_names_and_text_from_the_spec_execute_nothing(self):
        tmp = tempfile.mkdtemp(prefix="efc-injection-")
        try:
            spec = os.path.join(tmp, EVIL_FILE)
            with open(spec, "w", encoding="utf-8") as f:
                json.dump(evil_spec(), f)
            out = os.path.join(tmp, "out")
            r = efc("compile", spec, "--target", "genesis", "--target", "isaaclab",
                    "--target", "omnigibson", "-o", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            for t in TARGETS:
                with self.subTest(target=t):
                    folder = os.path.join(out, t)
                    script = os.path.join(folder, f"__import___{t}.py")
                    for py in glob.glob(os.path.join(folder, "*.py")):
                        py_compile.compile(py, cfile=os.path.join(tmp, "x.pyc"), doraise=True)
                    with open(script, encoding="utf-8") as f:
                        text = f.read()
                    self.assertTrue(text.isascii(), "generated Python is pure ASCII")
                    # The spec's text is only ever inside string constants: the
                    # docstring (file name) and the footer's literals.
                    tree = ast.parse(text)
                    names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
                    self.assertNotIn("__import__", names)
                    holders = [n for n in ast.walk(tree)
                               if isinstance(n, ast.Constant) and "PWNED" in str(n.value)]
                    self.assertEqual(len(holders), 1, "only the docstring quotes the file name")
                    self.assertEqual(ast.get_docstring(tree, clean=False).count("PWNED"), 1)
                    r = subprocess.run([sys.executable, script, "--help"], cwd=tmp,
                                       capture_output=True, text=True, timeout=60)
                    self.assertEqual(r.returncode, 0, r.stderr)
                    # The names and text arrive as data, intact.
                    with open(os.path.join(folder, "__import___functions.json"), encoding="utf-8") as f:
                        table = json.load(f)
                    self.assertEqual(table["description"], EVIL_TEXT)
                    self.assertEqual([fn["name"] for fn in table["functions"]], ["print", "True", "sys"])
                    r = subprocess.run([sys.executable, "efc_templates.py", "__import___functions.json",
                                        "--profile", "press:2", "--duration", "2", "--csv", "r.csv"],
                                       cwd=folder, capture_output=True, text=True, timeout=60)
                    self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(glob.glob(os.path.join(tmp, "**", "PWNED"), recursive=True), [])
            self.assertFalse(os.path.exists(os.path.join(os.getcwd(), "PWNED")))
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"] + sys.argv[3:])
