#!/usr/bin/env python3
"""The arrows of shared/design/architecture.md run one way: checks every
#include in the sources against the layers it may use.

    compiler/  names no backend, harness, CLI, evaluation or simulator
    runtime/   (but runtime/mujoco) includes only its own files: generated
               programs carry it
    backends/  (but mujoco/) never include MuJoCo, the MuJoCo target, the
               harness, eval or the CLI: URDF, Bullet and the Python targets
               must build without MuJoCo
    harness/, eval/ never include the CLI
    sequence/  the recording format: no simulator, backend, harness or CLI
    synth/     never includes the CLI or eval; synth/image and synth/suite
               (pixels and plans) use no simulator
    pipeline/  no backend, simulator, synth or CLI

Usage: layering_test.py SOURCE_DIR. Exit 1 listing every violation.
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
MUJOCO = re.compile(r'^(mujoco/|runtime/mujoco/|efc_mujoco|backends/mujoco/|harness/)')

RULES = [
    # (folder, files to skip, forbidden include pattern, why)
    ("compiler", re.compile(r"^(backends|harness|cli|eval|pipeline|runtime/mujoco)/|^mujoco/|^GL/|^osmesa"),
     "compiler/ names no backend, simulator, harness, evaluation or CLI"),
    ("runtime", re.compile(r"/|^mujoco"), "the runtime includes only its own files"),
    ("backends", MUJOCO, "only backends/mujoco may use MuJoCo or the harness"),
    ("backends", re.compile(r"^(cli|eval)/"), "backends do not know the CLI or eval"),
    ("harness", re.compile(r"^(cli|eval)/"), "the harness does not know the CLI or eval"),
    ("eval", re.compile(r"^cli/"), "eval does not know the CLI"),
    ("sequence", re.compile(r"^(backends|harness|cli|eval|synth|runtime)/|^mujoco/|^GL/"),
     "the sequence format knows no simulator, backend, harness or CLI"),
    ("synth", re.compile(r"^(cli|eval)/"), "synth does not know the CLI or eval"),
    ("pipeline", re.compile(r"^(cli|backends|harness|synth|runtime)/|^mujoco/|^GL/"),
     "the front-end talks to the compiler through the spec it writes: no backend, simulator or CLI"),
    ("synth/image", re.compile(r"^(backends|harness|runtime|synth/(?!image/|suite/))|^mujoco/|^GL/"),
     "synth/image is pixels only: no simulator"),
    ("synth/suite", re.compile(r"^(backends|harness|runtime|sequence|synth/(?!suite/))|^mujoco/|^GL/"),
     "synth/suite plans specs: no simulator"),
]


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    problems = []
    checked = 0
    for folder, forbidden, why in RULES:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".h", ".cc", ".cpp", ".hpp"):
                continue
            rel = path.relative_to(root).as_posix()
            if folder == "runtime" and rel.startswith("runtime/mujoco/"):
                continue  # the MuJoCo binding: its purpose is MuJoCo
            if folder == "backends" and rel.startswith("backends/mujoco/") and forbidden is MUJOCO:
                continue
            if rel == "backends/bullet/efc_bullet_engine.h":
                continue  # compiled only in an output folder, next to efc_runtime/
            text = path.read_text(encoding="utf-8", errors="replace")
            for m in INCLUDE.finditer(text):
                checked += 1
                if forbidden.search(m.group(1)):
                    line = text.count("\n", 0, m.start()) + 1
                    problems.append(f"{rel}:{line}: includes {m.group(1)}: {why}")
    for p in problems:
        print(p)
    print(f"layering: {checked} includes checked, {len(problems)} violations")
    return 1 if problems or checked < 100 else 0


if __name__ == "__main__":
    sys.exit(main())
