#!/usr/bin/env python3
"""Validates examples/*.json against grammar/efc-spec-v1.schema.json and checks that
the schema rejects a set of shape-invalid documents built inline.

Usage: schema_validate.py REPO_ROOT
Prints one line per check and ends with `N passed, M failed`; exit 0 only if all pass.
Needs only the Python standard library and jsonschema (Debian's python3-jsonschema).
"""
import copy
import glob
import json
import os
import sys

import jsonschema

SCHEMA_PATH = os.path.join("grammar", "efc-spec-v1.schema.json")


def strict_load(path):
    """json.load that also rejects NaN/Infinity and duplicate keys (both invalid in a spec)."""

    def no_constant(name):
        raise ValueError("non-finite number %s" % name)

    def no_duplicates(pairs):
        obj = {}
        for k, v in pairs:
            if k in obj:
                raise ValueError("duplicate key %r" % k)
            obj[k] = v
        return obj

    with open(path, encoding="utf-8") as f:
        return json.load(f, parse_constant=no_constant, object_pairs_hook=no_duplicates)


def errors_of(validator, doc):
    out = []
    for e in sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path)):
        ptr = "/" + "/".join(str(p) for p in e.absolute_path)
        out.append("%s: %s" % (ptr, e.message[:200]))
    return out


# A small valid document (the spec page's example); the bad cases mutate it.
BASE = {
    "efc": 1,
    "name": "desk_lamp",
    "parts": [
        {"name": "base", "role": "base", "geometry": {"box": {"size": [0.15, 0.15, 0.03]}}},
        {"name": "switch", "role": "receptor",
         "geometry": {"box": {"size": [0.02, 0.01, 0.01], "center": [0.05, 0, 0.02]}},
         "joint": {"type": "prismatic", "parent": "base", "axis": [0, 0, -1], "range": [0, 0.004],
                   "spring": {"stiffness": 50, "rest": 0}}},
        {"name": "bulb", "role": "effector",
         "geometry": {"sphere": {"radius": 0.03, "center": [0, 0, 0.35]}},
         "joint": {"type": "fixed", "parent": "base"}},
    ],
    "functions": [
        {"name": "light", "receptor": "switch", "effector": "bulb",
         "mapping": {"type": "binary", "latching": True},
         "effect": {"type": "illumination", "range": [0, 450]}},
    ],
}


def mutated(fn):
    doc = copy.deepcopy(BASE)
    fn(doc)
    return doc


def _set(path, value):
    def f(doc):
        node = doc
        for k in path[:-1]:
            node = node[k]
        node[path[-1]] = value
    return f


def _del(path):
    def f(doc):
        node = doc
        for k in path[:-1]:
            node = node[k]
        del node[path[-1]]
    return f


BAD = [
    ("unknown top-level key", _set(["colour"], "red")),
    ("unknown key in a joint", _set(["parts", 1, "joint", "limit"], 1.0)),
    ("unknown key in an effect", _set(["functions", 0, "effect", "brightness"], 3)),
    ("name starting with a digit", _set(["parts", 0, "name"], "1base")),
    ("name with a quote", _set(["parts", 2, "name"], 'bu"lb')),
    ("name with a space", _set(["functions", 0, "name"], "the light")),
    ("name longer than 64", _set(["name"], "a" * 65)),
    ("reserved efc_ prefix", _set(["parts", 2, "name"], "efc_bulb")),
    ("missing efc", _del(["efc"])),
    ("efc: 2", _set(["efc"], 2)),
    ("efc as a string", _set(["efc"], "1")),
    ("no parts", _set(["parts"], [])),
    ("part without geometry", _del(["parts", 0, "geometry"])),
    ("box and sphere together", _set(["parts", 0, "geometry"],
                                     {"box": {"size": [1, 1, 1]}, "sphere": {"radius": 0.1}})),
    ("empty geometry", _set(["parts", 0, "geometry"], {})),
    ("box with 2-number size", _set(["parts", 0, "geometry"], {"box": {"size": [1, 1]}})),
    ("compound with a bad piece", _set(["parts", 0, "geometry"],
                                       {"compound": [{"sphere": {"radius": 0.1}},
                                                     {"compound": [{"box": {"size": [1, 1, 1]},
                                                                    "cylinder": {"radius": 1, "length": 1}}]}]})),
    ("zero cylinder axis", _set(["parts", 0, "geometry"],
                                {"cylinder": {"radius": 0.1, "length": 0.2, "axis": [0, 0.0, 0]}})),
    ("mesh that is not OBJ/STL/PLY", _set(["parts", 0, "geometry"], {"mesh": "meshes/base.fbx"})),
    ("rgba out of [0,1]", _set(["parts", 0, "rgba"], [1.2, 0, 0, 1])),
    ("axis on a fixed joint", _set(["parts", 2, "joint", "axis"], [0, 0, 1])),
    ("range on a continuous joint", _set(["parts", 1, "joint", "type"], "continuous")),
    ("prismatic without range", _del(["parts", 1, "joint", "range"])),
    ("unknown joint type", _set(["parts", 1, "joint", "type"], "ball")),
    ("joint without parent", _del(["parts", 1, "joint", "parent"])),
    ("unknown role", _set(["parts", 0, "role"], "handle")),
    ("negative mass", _set(["parts", 0, "mass"], -1)),
    ("binary mapping with gain", _set(["functions", 0, "mapping", "gain"], 2.0)),
    ("linear mapping with threshold", _set(["functions", 0, "mapping"], {"type": "linear", "threshold": 0.1})),
    ("linear mapping with zero gain", _set(["functions", 0, "mapping"], {"type": "linear", "gain": 0})),
    ("cumulative without delta", _set(["functions", 0, "mapping"], {"type": "cumulative"})),
    ("cumulative with zero delta", _set(["functions", 0, "mapping"], {"type": "cumulative", "delta": 0.0})),
    ("latching as a string", _set(["functions", 0, "mapping", "latching"], "yes")),
    ("unknown mapping type", _set(["functions", 0, "mapping", "type"], "sigmoid")),
    ("illumination with negative lumens", _set(["functions", 0, "effect", "range"], [-10, 450])),
    ("illumination with a temperature parameter",
     _set(["functions", 0, "effect", "time_constant"], 10)),
    ("airflow with an emitter", _set(["functions", 0, "effect"],
                                     {"type": "airflow", "emitter": {"position": [0, 0, 0]}})),
    ("temperature below absolute zero", _set(["functions", 0, "effect"],
                                             {"type": "temperature", "range": [-300, 20]})),
    ("function without mapping", _del(["functions", 0, "mapping"])),
]

GOOD = [
    ("the spec page's example", lambda doc: None),
    ("x- keys everywhere", lambda doc: (doc.update({"x-source": "test"}),
                                        doc["parts"][1]["joint"].update({"x-note": 1}),
                                        doc["parts"][0]["geometry"]["box"].update({"x-a": [1]}),
                                        doc["functions"][0]["mapping"].update({"x-b": None}))),
    ("continuous joint without range", lambda doc: (doc["parts"][1]["joint"].update({"type": "continuous"}),
                                                    doc["parts"][1]["joint"].pop("range"),
                                                    doc["functions"][0]["mapping"].update({"threshold": 3.0}))),
    ("every geometry kind", _set(["parts", 0, "geometry"], {"compound": [
        {"mesh": "meshes/a.obj", "scale": [1, 1, 1]}, {"box": {"size": [1, 1, 1], "rpy": [0, 0, 1]}},
        {"cylinder": {"radius": 1, "length": 1, "axis": [1, 0, 0]}}, {"sphere": {"radius": 1}},
        {"compound": [{"box": {"size": [1, 1, 1]}}]}]})),
]


def main():
    if len(sys.argv) != 2:
        print("usage: schema_validate.py REPO_ROOT", file=sys.stderr)
        return 2
    root = sys.argv[1]
    passed = failed = 0

    def report(ok, label, details=()):
        nonlocal passed, failed
        if ok:
            passed += 1
        else:
            failed += 1
        print("%s  %s" % ("PASS" if ok else "FAIL", label))
        for d in details:
            print("      " + d)

    try:
        schema = strict_load(os.path.join(root, SCHEMA_PATH))
        cls = jsonschema.validators.validator_for(schema)
        cls.check_schema(schema)
        validator = cls(schema)
        report(True, "%s is a valid %s schema" % (SCHEMA_PATH, cls.__name__))
    except Exception as e:  # noqa: BLE001 - any failure to load is a failed check
        report(False, "%s cannot be used: %s" % (SCHEMA_PATH, e))
        print("%d passed, %d failed" % (passed, failed))
        return 1

    examples = sorted(glob.glob(os.path.join(root, "examples", "*.json")))
    if not examples:
        report(False, "no examples/*.json found")
    for path in examples:
        rel = os.path.relpath(path, root)
        try:
            doc = strict_load(path)
        except Exception as e:  # noqa: BLE001
            report(False, "%s (valid): cannot parse: %s" % (rel, e))
            continue
        errs = errors_of(validator, doc)
        report(not errs, "%s (valid)" % rel, errs)

    for label, fn in GOOD:
        doc = mutated(fn)
        errs = errors_of(validator, doc)
        report(not errs, "inline accepted: %s" % label, errs)

    for label, fn in BAD:
        doc = mutated(fn)
        errs = errors_of(validator, doc)
        report(bool(errs), "inline rejected: %s" % label,
               () if errs else ["the schema accepted this shape-invalid document"])

    print("%d passed, %d failed" % (passed, failed))
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
