#!/usr/bin/env python3
"""grammar/sequence-meta.schema.json accepts good meta.json documents (the
example of shared/spec/sequence.md among them) and rejects bad ones.

Usage: sequence_schema_test.py REPO_ROOT
Prints one line per check and ends with `N passed, M failed`; exit 0 only if all pass.
Needs only the Python standard library and jsonschema (Debian's python3-jsonschema).
"""
import copy
import json
import os
import sys

import jsonschema

SCHEMA_PATH = os.path.join("grammar", "sequence-meta.schema.json")

# The example of shared/spec/sequence.md, copied into tests/data (shared/ may
# be absent); sequence_format_test.cc reads the same file.
EXAMPLE_PATH = os.path.join("tests", "data", "sequence-meta-example.json")
SPEC_EXAMPLE = None  # its text, read in main()

MINIMAL = {
    "efc_sequence": 1,
    "fps": 15.5,
    "width": 64,
    "height": 48,
    "intrinsics": {"fx": 50, "fy": 50, "cx": 31.5, "cy": 23.5},
    "frames": 1,
}


DELETE = object()  # with_changes(doc, key=DELETE) removes the key


def with_changes(base, **changes):
    doc = copy.deepcopy(base)
    for key, value in changes.items():
        key = key.replace("__", "-")  # x__notes -> x-notes
        if value is DELETE:
            del doc[key]
        else:
            doc[key] = value
    return doc


def good_documents():
    example = json.loads(SPEC_EXAMPLE)
    yield "the example of sequence.md", example
    yield "the example as written in shared/ (if present)", shared_example() or example
    yield "minimal", MINIMAL
    yield "integral floats as sizes", with_changes(MINIMAL, width=64.0, frames=3.0)
    yield "x- extension keys", with_changes(example, x__efc_seed=7, x__notes={"any": ["thing", 1]})
    yield "every role", with_changes(
        example,
        parts={"lever": "receptor", "gear": "receptor+effector", "lid": "effector", "body": "object",
               "hand": "hand"},
        functions=[{"name": "a", "receptor": "lever", "effector": "gear"},
                   {"name": "b", "receptor": "gear", "effector": "lid"}])
    yield "no parts nor functions", with_changes(example, parts=DELETE, functions=DELETE, source=DELETE)


def bad_documents():
    example = json.loads(SPEC_EXAMPLE)
    yield "not an object", [example]
    for key in ("efc_sequence", "fps", "width", "height", "intrinsics", "frames"):
        yield "missing " + key, with_changes(example, **{key: DELETE})
    yield "version 2", with_changes(example, efc_sequence=2)
    yield "fps 0", with_changes(example, fps=0)
    yield "fps a string", with_changes(example, fps="30")
    yield "width a string", with_changes(example, width="640")
    yield "width not integral", with_changes(example, width=640.5)
    yield "height 0", with_changes(example, height=0)
    yield "frames 0", with_changes(example, frames=0)
    yield "negative depth_scale", with_changes(example, depth_scale=-0.001)
    yield "fx 0", with_changes(example, intrinsics={"fx": 0, "fy": 525, "cx": 1, "cy": 1})
    yield "intrinsics without cy", with_changes(example, intrinsics={"fx": 1, "fy": 525, "cx": 1})
    yield "intrinsics with k1", with_changes(example, intrinsics={"fx": 1, "fy": 1, "cx": 1, "cy": 1, "k1": 0})
    yield "gravity of 2", with_changes(example, gravity=[0, -1])
    yield "gravity not numbers", with_changes(example, gravity=["0", "0", "-1"])
    yield "unknown role", with_changes(example, parts={"handle": "knob"})
    yield "part name with a slash", with_changes(example, parts={"../x": "object"})
    yield "parts an array", with_changes(example, parts=["handle"])
    yield "function without effector", with_changes(example, functions=[{"name": "f", "receptor": "handle"}])
    yield "function with an extra key", with_changes(
        example, functions=[{"name": "f", "receptor": "handle", "effector": "spout", "mapping": "binary"}])
    yield "unknown top-level key", with_changes(example, framerate=30)
    yield "source a number", with_changes(example, source=1)


def shared_example():
    """The JSON block of shared/spec/sequence.md when that file is there."""
    path = os.path.join(sys.argv[1] if len(sys.argv) > 1 else ".", "..", "shared", "spec", "sequence.md")
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        text = f.read()
    start = text.find("```json\n")
    if start < 0:
        return None
    end = text.find("```", start + 8)
    return json.loads(text[start + 8:end])


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    global SPEC_EXAMPLE
    with open(os.path.join(root, EXAMPLE_PATH), encoding="utf-8") as f:
        SPEC_EXAMPLE = f.read()
    with open(os.path.join(root, SCHEMA_PATH), encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    passed = failed = 0
    for name, doc in good_documents():
        errors = [e.message for e in validator.iter_errors(doc)]
        ok = not errors
        print(("ok    " if ok else "FAIL  ") + "accepts " + name + ("" if ok else ": " + "; ".join(errors)))
        passed, failed = passed + ok, failed + (not ok)
    for name, doc in bad_documents():
        ok = not validator.is_valid(doc)
        print(("ok    " if ok else "FAIL  ") + "rejects " + name)
        passed, failed = passed + ok, failed + (not ok)
    # Every property is described: the schema is the documentation too.
    undocumented = [k for k, v in schema["properties"].items() if "description" not in v]
    ok = not undocumented
    print(("ok    " if ok else "FAIL  ") + "every top-level key has a description" +
          ("" if ok else ": " + ", ".join(undocumented)))
    passed, failed = passed + ok, failed + (not ok)
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
