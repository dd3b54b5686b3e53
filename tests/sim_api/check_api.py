#!/usr/bin/env python3
"""Check Python scripts' use of a simulator against an API index made by extract_api.py.

    python3 check_api.py --index genesis-0.4.5.json SCRIPT.py [SCRIPT.py ...]
    python3 check_api.py --index genesis-0.4.5.json --show genesis.Scene   # what is known

prints `SCRIPT:line:col: error: <what>` for every problem; exit status 1 if there is one,
0 if none, 2 on a usage error (bad arguments, unreadable index or script, script with a
syntax error). Importable: `check_source(text, filename, index) -> list[Problem]`, where
`index` is the loaded JSON (or an `Index`).

What is checked (the contract of backends/python/README.md, "Checking scripts against the
simulators' real APIs"):
  * imports: every module and every name imported from an indexed package exists
    (imports anywhere in the file, also inside functions; the bodies of handlers of
    ImportError (or Exception) are fallbacks for other versions and are not checked);
  * attribute chains from those modules (`gs.morphs.URDF`) exist, through re-exports,
    `from .x import *` (honouring `__all__`) and submodules;
  * calls of indexed functions, methods and classes: every keyword is a parameter (or the
    callee takes **kwargs), no more positional arguments than parameters (unless *args);
    a class's keywords are its __init__'s (walking the bases), or its fields for
    dataclass-like classes (@dataclass, Isaac Lab @configclass, pydantic models);
  * attributes and methods used on simulator objects of known type exist on the class or
    a base (methods, properties, class attributes, annotated fields, `self.x =` in any
    method), bases in other modules of the index included;
  * a value from the simulator whose type cannot be told (a call without return
    annotation, an overloaded call, an unannotated property or attribute, a TypeVar)
    that is then used with `.attr` is an error: annotate the variable.

Types come from, in order: a variable or parameter annotation (a string or expression such
as "gs.Scene", resolved through the script's imports anywhere in the file), a class
construction, the callee's return annotation in the index (`Self` is the receiver's class).
`self.x` of the script's own classes is typed by an annotation in the class body or
`self.x: T = ...`, or by construction.

Deliberately NOT checked (what only a run inside the simulator would find), so that an
error always means a real misuse:
  * argument types and values, missing required arguments, return values, runtime
    behaviour; anything reached through a subscript (`scene.entities[0].x`), a loop
    variable, a container, `getattr` with a computed name, or an unannotated parameter;
  * names from modules listed in the index's `unchecked_modules`, from packages that are
    not indexed (numpy, torch, pxr, ...), and from modules or bases that the (possibly
    partial) source tree does not contain: these are unknown, never errors;
  * classes and modules whose attributes are dynamic (`__getattr__` that may answer any
    name, `setattr(self, computed, ...)`, `globals()[...] =`, star imports from a module
    that is not indexed) accept any attribute;
  * private names (leading `_`) and dunders are not indexed and never reported;
  * attributes guarded by `if hasattr(obj, "name"):` or used in a `try:` whose handler
    catches AttributeError (version-compatibility code) are not reported missing;
  * decorators are assumed to keep the signature of what they decorate
    (functools.wraps style), class decorators to return the class;
  * the flow of the script is followed in statement order without branches: the last
    assignment seen wins, a name assigned differently in two branches keeps the last type.
"""

import argparse
import ast
import json
import sys
from dataclasses import dataclass

# --------------------------------------------------------------------------- problems


@dataclass
class Problem:
    filename: str
    line: int
    col: int          # 1-based, as compilers print it
    message: str

    def __str__(self):
        return "%s:%d:%d: error: %s" % (self.filename, self.line, self.col, self.message)


# --------------------------------------------------------------------------- index values
# What an expression of the script evaluates to, as far as the simulator is concerned.
# `None` means "not a simulator object" (or one we do not track): nothing is checked on it.


class V:
    pass


class ModV(V):
    def __init__(self, name):
        self.name = name

    def describe(self):
        return "module '%s'" % self.name


class ClsV(V):
    """An indexed class (the class object itself)."""

    def __init__(self, qual, rec):
        self.qual = qual
        self.rec = rec

    @property
    def short(self):
        return self.qual.rsplit(".", 1)[-1]

    def describe(self):
        return "class '%s' (%s)" % (self.short, self.qual)


class InstV(V):
    """An instance of an indexed class. `declared` says where the class comes from when
    it is only what the simulator's source declares (a return or attribute annotation):
    the object may then be of a subclass."""

    def __init__(self, cls, declared=None):
        self.cls = cls
        self.declared = declared

    def describe(self):
        return "'%s' object (%s)" % (self.cls.short, self.cls.qual)


class FnV(V):
    """A function, or a method reached through an instance (bound) or a class."""

    def __init__(self, qual, sig, bound=False, owner=None):
        self.qual = qual
        self.sig = sig
        self.bound = bound
        self.owner = owner   # ClsV of the receiver, for `-> Self`

    def describe(self):
        return "function '%s'" % self.qual


class UnknownSimV(V):
    """A simulator value whose type the checker cannot tell: `.attr` on it is an error."""

    def __init__(self, origin):
        self.origin = origin   # text for the message: "the result of Scene.add_entity(...)"


class OpaqueV(V):
    """Exists in the simulator but cannot be checked (unindexed, unresolved, unchecked,
    dynamic): every use is accepted and gives another opaque value."""


OPAQUE = OpaqueV()


class Missing:
    def __init__(self, where):
        self.where = where   # "module 'genesis'" / "class 'Scene' (...)"


# Bases outside the index whose attributes we know. A class with any other base outside
# the index (or unresolved in a partial tree) accepts every attribute: not checkable.
PYDANTIC_BASES = {"pydantic.BaseModel", "pydantic.main.BaseModel"}
PYDANTIC_ATTRS = {
    "model_config", "model_fields", "model_computed_fields", "model_extra", "model_fields_set",
    "model_construct", "model_copy", "model_dump", "model_dump_json", "model_json_schema",
    "model_parametrized_name", "model_post_init", "model_rebuild", "model_validate",
    "model_validate_json", "model_validate_strings", "dict", "json", "parse_obj", "parse_raw",
    "parse_file", "from_orm", "construct", "copy", "schema", "schema_json", "validate",
    "update_forward_refs"}
CLOSED_EXTERNAL = {"builtins.object": set(), "object": set(), "abc.ABC": set(),
                   "typing.Generic": set(), "typing_extensions.Generic": set(),
                   "typing.Protocol": set(), "typing_extensions.Protocol": set(),
                   "enum.Enum": {"name", "value"}}
for _b in PYDANTIC_BASES:
    CLOSED_EXTERNAL[_b] = PYDANTIC_ATTRS
# metaclasses that do not change what calling the class or reading its attributes does
PLAIN_METACLASSES = {"abc.ABCMeta", "type", "builtins.type", "enum.EnumMeta", "enum.EnumType"}


class Index:
    """Name resolution over the JSON index (lazy: star imports are followed on demand)."""

    def __init__(self, data):
        if isinstance(data, Index):
            data = data.data
        if data.get("format") != "efc-sim-api":
            raise ValueError("not an efc-sim-api index")
        self.data = data
        self.modules = data["modules"]
        self.unchecked = data.get("unchecked_modules") or {}
        self.roots = {m.split(".")[0] for m in self.modules}
        prov = data.get("provenance") or {}
        self.label = "%s %s" % (prov.get("simulator", "?"), prov.get("version", "?"))
        self._mro_cache = {}

    # ------------------------------------------------------------------ modules
    def is_unchecked(self, dotted):
        for m in self.unchecked:
            if dotted == m or dotted.startswith(m + "."):
                return True
        return False

    def is_indexed(self, dotted):
        return dotted.split(".")[0] in self.roots

    def resolve(self, dotted, depth=0):
        """A dotted name (module, module.attr.attr, module.Class.Nested) to a value.

        Returns a V, or Missing when an indexed module lacks the name."""
        if depth > 40:
            return OPAQUE
        if self.is_unchecked(dotted) or not self.is_indexed(dotted):
            return OPAQUE
        parts = dotted.split(".")
        for i in range(len(parts), 0, -1):
            mod = ".".join(parts[:i])
            if mod in self.modules:
                val = ModV(mod)
                for p in parts[i:]:
                    val = self.getattr(val, p, depth + 1)
                    if isinstance(val, Missing) or val is None:
                        return val
                return val
        return Missing("package '%s'" % parts[0])

    def getattr(self, val, name, depth=0):
        """One step of a dotted name inside the index (module attribute, nested class,
        class member). Missing when the step does not exist."""
        if isinstance(val, ModV):
            return self.module_attr(val.name, name, depth)
        if isinstance(val, ClsV):
            r = self.class_attr(val, name, via_instance=False)
            if isinstance(r, Missing):
                return r
            v, kind = r
            if kind == "n":
                return v
            if kind in ("m", "s", "c"):
                return FnV(val.qual + "." + name, v[1], bound=(kind == "c"), owner=val)
            return OPAQUE
        if isinstance(val, InstV):
            return OPAQUE
        return OPAQUE

    def module_attr(self, mod, name, depth=0, seen=None):
        if self.is_unchecked(mod + "." + name) or self.is_unchecked(mod):
            return OPAQUE
        rec = self.modules.get(mod)
        if rec is None:
            return OPAQUE
        seen = seen or set()
        if (mod, name) in seen or depth > 40:
            return OPAQUE
        seen.add((mod, name))
        if name in rec.get("fn", {}):
            return FnV(mod + "." + name, rec["fn"][name])
        if name in rec.get("cls", {}):
            return ClsV(mod + "." + name, rec["cls"][name])
        n = rec.get("n", {}).get(name)
        if n is not None:
            if "a" in n:
                target = self.resolve(n["a"], depth + 1)
                # the import exists in the real source, so the name exists even when the
                # tree we indexed lacks what it points to
                return OPAQUE if isinstance(target, Missing) else target
            return self.var_value(n, "%s.%s" % (mod, name), depth)
        if mod + "." + name in self.modules:
            # a submodule: an attribute of its package once anything imported it
            return ModV(mod + "." + name)
        opaque = False
        for star in rec.get("star", []):
            srec = self.modules.get(star)
            if srec is None or self.is_unchecked(star):
                opaque = True   # `from <unindexed or missing module> import *`
                continue
            if "all" in srec:
                if name in srec["all"]:
                    r = self.module_attr(star, name, depth + 1, seen)
                    return OPAQUE if isinstance(r, Missing) else r
                continue
            if name.startswith("_"):
                continue
            r = self.module_attr(star, name, depth + 1, seen)
            if not isinstance(r, Missing):
                return r
        if opaque or "open" in rec or name in rec.get("xn", []):
            return OPAQUE
        if name.startswith("_"):
            return OPAQUE   # private names are not indexed: never reported
        if "all" in rec and name in rec["all"]:
            return OPAQUE   # listed in __all__ but defined in a way we did not see
        return Missing("module '%s'" % mod)

    def var_value(self, n, qual, depth=0):
        """A module variable: typed by its annotation or by the class it is made from."""
        if n.get("multi"):
            return UnknownSimV("variable %s" % qual)
        if "t" in n:
            if not self.is_indexed(n["t"]):
                return None   # annotated with a type outside the simulator: not checked
            t = self.resolve(n["t"], depth + 1)
            if isinstance(t, ClsV):
                return InstV(t, declared=qual)
        if "c" in n:
            t = self.resolve(n["c"], depth + 1)
            if isinstance(t, ClsV):
                return InstV(t, declared=qual)
        return UnknownSimV("variable %s" % qual)

    # ------------------------------------------------------------------ types of values
    def returned(self, sig, owner, what, depth=0, call=None):
        """The value a call (or a property read) gives, from the return annotation; for a
        property without one, from the attribute path it returns ("via")."""
        if sig.get("ov") is not None:
            variant = pick_overload(sig["ov"], call)
            if variant is None or variant["rt"] == "?":
                return UnknownSimV("the result of %s (overloaded)" % what)
            sig = {"rt": variant["rt"], "r": variant["rt"]}
        if "rt" in sig:
            rt = sig["rt"]
            if rt == "Self":
                return InstV(owner, declared=what) if isinstance(owner, ClsV) else OPAQUE
            if not self.is_indexed(rt):
                return None   # builtins, torch, numpy: known, not the simulator's
            v = self.resolve(rt)
            if isinstance(v, ClsV):
                return InstV(v, declared=what)
            return UnknownSimV("the result of %s (returns %s)" % (what, sig.get("r", rt)))
        if "r" in sig:
            return None   # annotated with a type outside the index (list[...], Tensor, None)
        if "via" in sig and isinstance(owner, ClsV) and depth < 8:
            cur = InstV(owner)
            for step in sig["via"].split("."):
                if not isinstance(cur, InstV):
                    break
                cur = self.member_value(cur.cls, step, depth + 1)
            else:
                if cur is None or isinstance(cur, InstV):
                    return cur
        return UnknownSimV("the result of %s" % what)

    def member_value(self, cls, name, depth=0):
        """The value of instance attribute `name` (private too) of an instance of cls."""
        for c in self.mro(cls):
            if not isinstance(c, ClsV):
                continue
            r = c.rec
            m = r.get("m", {}).get(name)
            if m is not None:
                if m.get("k") == "p":
                    return self.returned(m, cls, "property %s.%s" % (c.short, name), depth)
                return OPAQUE
            if name in r.get("it", {}):
                return self.attr_type_value(r["it"][name], "attribute %s.%s" % (c.short, name))
            t = r.get("at", {}).get(name)
            if t:
                return self.attr_type_value(t, "attribute %s.%s" % (c.short, name))
            if any(a[0] == name for a in r.get("ann", [])):
                return None   # annotated with something that is not one class
        return UnknownSimV("attribute %s.%s" % (cls.short, name))

    def attr_type_value(self, t, what):
        """An "it"/"at" entry: "dotted" (annotation) or "dotted()" (made by that call)."""
        if t.endswith("()"):
            v = self.resolve(t[:-2]) if self.is_indexed(t[:-2]) else None
            return InstV(v, declared=what) if isinstance(v, ClsV) else UnknownSimV(what)
        if not self.is_indexed(t):
            return None
        v = self.resolve(t)
        return InstV(v, declared=what) if isinstance(v, ClsV) else UnknownSimV(what)

    # ------------------------------------------------------------------ classes
    def class_at(self, qual):
        v = self.resolve(qual)
        return v if isinstance(v, ClsV) else None

    def mro(self, cls):
        """C3 linearisation of indexed classes; external bases appear as strings.

        Returns (list of ClsV or str), where a str is a base outside the index (dotted
        name) or "?" for one that cannot be resolved."""
        key = cls.qual
        if key in self._mro_cache:
            return self._mro_cache[key]
        self._mro_cache[key] = [cls, "?"]   # cycle guard
        seqs = []
        direct = []
        for b in cls.rec.get("b", []):
            v = self.resolve(b)
            if isinstance(v, ClsV):
                seqs.append(list(self.mro(v)))
                direct.append(v)
            else:
                name = b if b in CLOSED_EXTERNAL or b.startswith("builtins.") else (
                    b if not self.is_indexed(b) else "?")
                seqs.append([name])
                direct.append(name)
        for _ in cls.rec.get("ub", []):
            seqs.append(["?"])
            direct.append("?")
        seqs.append(direct)
        out = [cls]
        seqs = [[x for x in s] for s in seqs if s]

        def ident(x):
            return x.qual if isinstance(x, ClsV) else x

        while True:
            seqs = [s for s in seqs if s]
            if not seqs:
                break
            for s in seqs:
                head = s[0]
                if not any(ident(head) in [ident(y) for y in t[1:]] for t in seqs):
                    break
            else:
                # inconsistent hierarchy: fall back to depth-first order
                for s in seqs:
                    for x in s:
                        if ident(x) not in [ident(y) for y in out]:
                            out.append(x)
                break
            out.append(head)
            seqs = [t[1:] if ident(t[0]) == ident(head) else t for t in seqs]
        self._mro_cache[key] = out
        return out

    def class_open(self, cls):
        """Why attributes of this class cannot be listed (None: they can)."""
        for c in self.mro(cls):
            if isinstance(c, ClsV):
                if "open" in c.rec:
                    return "%s defines %s" % (c.short, c.rec["open"])
            elif c == "?":
                return "a base class is not in the index"
            elif c not in CLOSED_EXTERNAL:
                return "base %s is outside the index" % c
        return None

    def class_attr(self, cls, name, via_instance):
        """Look an attribute up on a class (and its bases). Returns (value, kind) or Missing.
        Instance attributes are found through the class too (`via_instance` is informative:
        reading `Class.x` for an `x` set in __init__ is not worth an error).

        kind: "m" method, "s"/"c" static/class method, "p" property, "f" field or
        attribute, "n" nested class."""
        for c in self.mro(cls):
            if not isinstance(c, ClsV):
                if c in CLOSED_EXTERNAL and name in CLOSED_EXTERNAL[c]:
                    return OPAQUE, "f"
                continue
            r = c.rec
            m = r.get("m", {}).get(name)
            if m is not None:
                return (c, m), m.get("k", "m")
            if name in r.get("cls", {}):
                return ClsV(c.qual + "." + name, r["cls"][name]), "n"
            for a in r.get("ann", []):
                if a[0] == name:
                    return (c, a), "a"
            if name in r.get("ca", []) or name in r.get("ia", []) or name in r.get("xa", []):
                return (c, name), "f"
        if name.startswith("_") or self.class_open(cls):
            return OPAQUE, "f"
        return Missing("'%s' (%s)" % (cls.short, cls.qual))

    def model_kind(self, cls):
        """'pydantic', 'dataclass', 'configclass' or None (an ordinary class)."""
        kind = None
        for c in self.mro(cls):
            if isinstance(c, ClsV):
                if c.rec.get("dc") and kind is None:
                    kind = c.rec["dc"]
            elif c in PYDANTIC_BASES:
                kind = "pydantic"
        return kind


# --------------------------------------------------------------------------- the checker


class ScriptClass:
    """A class defined by the script: its `self.x` types, and its bases if simulator."""

    def __init__(self, name):
        self.name = name
        self.attrs = {}         # name -> value (V or None)
        self.annotated = set()  # names whose type comes from an annotation (wins)
        self.sim_bases = []     # ClsV bases from the simulator


class ScriptInstV(V):
    def __init__(self, sc):
        self.sc = sc


class Checker:
    def __init__(self, index, filename):
        self.ix = index if isinstance(index, Index) else Index(index)
        self.filename = filename
        self.problems = []
        self._seen = set()
        self.imports = {}       # file-wide alias -> dotted target (None: ambiguous)
        self.scopes = []        # list of dicts name -> value
        self.in_fallback = 0
        self.attr_guarded = 0   # inside `try:` whose handler catches AttributeError
        self.guards = set()     # (ast.dump(obj), "name") from enclosing `if hasattr(obj, "name"):`

    # ------------------------------------------------------------------ reporting
    def err(self, node, msg):
        key = (getattr(node, "lineno", 0), getattr(node, "col_offset", 0), msg)
        if key in self._seen:
            return
        self._seen.add(key)
        self.problems.append(Problem(self.filename, key[0], key[1] + 1, msg))

    # ------------------------------------------------------------------ imports
    def collect_imports(self, tree):
        """Every import in the file, at any depth: alias -> dotted target.

        Scripts import the simulator inside functions and use the alias in other
        functions (or in string annotations); an alias bound to two different targets
        is ambiguous and not used."""
        for node in ast.walk(tree):
            pairs = []
            if isinstance(node, ast.Import):
                for a in node.names:
                    if a.asname:
                        pairs.append((a.asname, a.name))
                    else:
                        pairs.append((a.name.split(".")[0], a.name.split(".")[0]))
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                for a in node.names:
                    if a.name != "*":
                        pairs.append((a.asname or a.name, node.module + "." + a.name))
            for alias, target in pairs:
                if alias in self.imports and self.imports[alias] != target:
                    self.imports[alias] = None
                else:
                    self.imports[alias] = target

    def check_import(self, node):
        if self.in_fallback:
            return   # `except ImportError:` fallbacks target other versions
        ix = self.ix
        if isinstance(node, ast.Import):
            for a in node.names:
                if not ix.is_indexed(a.name) or ix.is_unchecked(a.name):
                    continue
                v = ix.resolve(a.name)
                if isinstance(v, Missing):
                    self.err(node, "no module '%s' in %s (%s has no attribute '%s')" % (
                        a.name, ix.label, v.where, a.name.rsplit(".", 1)[-1]))
                elif not isinstance(v, (ModV, OpaqueV)):
                    self.err(node, "'%s' is not a module in %s (use from ... import)" % (a.name, ix.label))
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            mod = node.module
            if not ix.is_indexed(mod) or ix.is_unchecked(mod):
                return
            mv = ix.resolve(mod)
            if isinstance(mv, Missing):
                self.err(node, "no module '%s' in %s" % (mod, ix.label))
                return
            if not isinstance(mv, ModV):
                if not isinstance(mv, OpaqueV):
                    self.err(node, "'%s' is not a module in %s" % (mod, ix.label))
                return
            for a in node.names:
                if a.name == "*":
                    continue
                v = ix.module_attr(mv.name, a.name)
                if isinstance(v, Missing):
                    self.err(node, "cannot import name '%s' from '%s' (%s)" % (a.name, mod, ix.label))

    def import_value(self, target):
        if target is None or not self.ix.is_indexed(target):
            return None
        v = self.ix.resolve(target)
        return None if isinstance(v, Missing) else v

    # ------------------------------------------------------------------ scopes
    def lookup(self, name):
        for scope in reversed(self.scopes):
            if name in scope:
                return scope[name]
        if name in self.imports:
            return self.import_value(self.imports[name])
        return None

    def bind(self, name, value):
        self.scopes[-1][name] = value

    def bind_target(self, target, value):
        if isinstance(target, ast.Name):
            self.bind(target.id, value)
        elif isinstance(target, (ast.Tuple, ast.List)):
            for e in target.elts:
                self.bind_target(e.value if isinstance(e, ast.Starred) else e, None)
        elif isinstance(target, ast.Attribute):
            self.eval(target.value)
            self.self_attr_assign(target, value, annotated=False)
        elif isinstance(target, ast.Subscript):
            self.eval(target.value)
            self.eval(target.slice)
        elif isinstance(target, ast.Starred):
            self.bind_target(target.value, None)

    # ------------------------------------------------------------------ annotations
    def annotation_type(self, node):
        """A script annotation to a value type: InstV of an indexed class, OPAQUE for a
        simulator name that is not a class (unchecked module, unresolved), None for a
        type outside the simulator. Reports annotations naming what does not exist."""
        if node is None:
            return None
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            try:
                expr = ast.parse(node.value.strip(), mode="eval").body
            except SyntaxError:
                return None
            for sub in ast.walk(expr):   # report at the string's position
                sub.lineno, sub.col_offset = node.lineno, node.col_offset
            return self.annotation_type(expr)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr):
            parts = [p for p in (node.left, node.right)
                     if not (isinstance(p, ast.Constant) and p.value is None)]
            if len(parts) == 1:
                return self.annotation_type(parts[0])
            return None
        if isinstance(node, ast.Subscript):
            head = self.dotted_target(node.value)
            if head in ("typing.Optional", "Optional"):
                return self.annotation_type(node.slice)
            return None
        v = self.eval(node)   # reports missing names inside the annotation
        if isinstance(v, ClsV):
            return InstV(v)
        if isinstance(v, (OpaqueV, UnknownSimV, ModV, FnV, InstV)):
            return OPAQUE
        if isinstance(v, ScriptClassV):
            return ScriptInstV(v.sc)
        return None

    def dotted_target(self, node):
        parts = []
        while isinstance(node, ast.Attribute):
            parts.append(node.attr)
            node = node.value
        if not isinstance(node, ast.Name):
            return None
        head = self.imports.get(node.id) or node.id
        return ".".join([head] + list(reversed(parts)))

    # ------------------------------------------------------------------ attributes
    def guarded(self, node, attr):
        return bool(self.attr_guarded) or (ast.dump(node.value), attr) in self.guards

    def getattr_value(self, base, attr, node):
        """Value of base.attr; reports a missing attribute or an untyped receiver."""
        if attr.startswith("__") and attr.endswith("__"):
            return OPAQUE if isinstance(base, V) and not isinstance(base, ScriptInstV) else None
        ix = self.ix
        if isinstance(base, UnknownSimV):
            holder = ("'%s' (%s)" % (node.value.id, base.origin)) if isinstance(node.value, ast.Name) \
                else base.origin
            self.err(node, "'.%s' used on %s, whose type %s does not tell: annotate it "
                           "(name: \"module.Class\" = ...)" % (attr, holder, ix.label))
            return OPAQUE
        if isinstance(base, ModV):
            v = ix.module_attr(base.name, attr)
            if isinstance(v, Missing) and self.guarded(node, attr):
                return OPAQUE
            if isinstance(v, Missing):
                self.err(node, "module '%s' has no attribute '%s' in %s" % (base.name, attr, ix.label))
                return OPAQUE
            return v
        if isinstance(base, ClsV):
            r = ix.class_attr(base, attr, via_instance=False)
            if isinstance(r, Missing) and self.guarded(node, attr):
                return OPAQUE
            if isinstance(r, Missing):
                self.err(node, "%s has no attribute '%s' in %s" % (r.where, attr, ix.label))
                return OPAQUE
            val, kind = r
            if kind in ("m", "s", "c"):
                owner, sig = val
                return FnV(owner.qual + "." + attr, sig, bound=(kind == "c"), owner=base)
            if kind == "n":
                return val
            if kind == "a":
                return OPAQUE
            return None if val is not OPAQUE else OPAQUE  # class attributes: enum members, constants
        if isinstance(base, InstV):
            cls = base.cls
            r = ix.class_attr(cls, attr, via_instance=True)
            if isinstance(r, Missing) and self.guarded(node, attr):
                return OPAQUE
            if isinstance(r, Missing):
                subs = self.subclasses_with(cls, attr)
                if subs and base.declared:
                    # the source only promises cls; the object may well be a subclass
                    self.err(node, "'.%s' is not on '%s', the type %s is declared to give in %s; "
                                   "subclasses have it (%s): annotate the variable with the one it is"
                             % (attr, cls.short, base.declared, ix.label, ", ".join(subs)))
                else:
                    self.err(node, "%s has no attribute '%s' in %s%s" % (
                        r.where, attr, ix.label,
                        (" (subclasses have it: %s)" % ", ".join(subs)) if subs else ""))
                return OPAQUE
            val, kind = r
            if val is OPAQUE:
                return OPAQUE
            if kind in ("m", "s", "c"):
                owner, sig = val
                return FnV(owner.qual + "." + attr, sig, bound=(kind != "s"), owner=cls)
            if kind == "p":
                owner, sig = val
                return self.returned(sig, cls, "property %s.%s" % (owner.short, attr))
            if kind == "n":
                return val
            return ix.member_value(cls, attr)
        if isinstance(base, FnV):
            return OPAQUE   # function attributes (__name__, ...) are not checked
        if isinstance(base, ScriptInstV):
            sc = base.sc
            if attr in sc.attrs:
                return sc.attrs[attr]
            for sb in sc.sim_bases:
                r = ix.class_attr(sb, attr, via_instance=True)
                if not isinstance(r, Missing):
                    return self.getattr_value(InstV(sb), attr, node)
            return None
        if isinstance(base, OpaqueV):
            return OPAQUE
        return None

    def subclasses_with(self, cls, attr):
        """Indexed subclasses of cls that have attr (at most 3, for the message)."""
        found = []
        for mod, rec in self.ix.modules.items():
            for cname, crec in rec.get("cls", {}).items():
                c = ClsV(mod + "." + cname, crec)
                if any(isinstance(x, ClsV) and x.qual == cls.qual for x in self.ix.mro(c)[1:]):
                    if not isinstance(self.ix.class_attr(c, attr, True), Missing):
                        found.append(c.qual)
        return sorted(found)[:3]

    # ------------------------------------------------------------------ calls
    def returned(self, sig, owner, what, call=None):
        return self.ix.returned(sig, owner, what, call=call)

    def check_args(self, node, sig, bound, what):
        """Keywords and positional count against a signature."""
        params = list(sig.get("a", []))
        po = sig.get("po", 0)
        if bound and params:
            params = params[1:]
            po = max(0, po - 1)
        names = [p.rstrip("=") for p in params]
        ko = [p.rstrip("=") for p in sig.get("ko", [])]
        star_args = any(isinstance(a, ast.Starred) for a in node.args)
        npos = len(node.args)
        if not star_args and "va" not in sig and npos > len(names):
            self.err(node, "%s takes at most %d positional argument%s, %d given (%s)" % (
                what, len(names), "" if len(names) == 1 else "s", npos, self.ix.label))
        if "kw" in sig:
            return
        for kw in node.keywords:
            if kw.arg is None or kw.arg.startswith("_"):
                continue
            if kw.arg in names[po:] or kw.arg in ko:
                continue
            if kw.arg in names[:po]:
                self.err(kw, "%s: '%s' is positional-only (%s)" % (what, kw.arg, self.ix.label))
                continue
            self.err(kw, "%s got an unexpected keyword argument '%s' (%s)" % (what, kw.arg, self.ix.label))

    def check_construct(self, node, cls):
        """Calling a class: __init__ along the bases, or the fields of a model class."""
        ix = self.ix
        what = "%s()" % cls.short
        mro = ix.mro(cls)
        for c in mro:
            if isinstance(c, ClsV) and c.rec.get("meta") and c.rec["meta"] not in PLAIN_METACLASSES:
                return   # a metaclass may change what calling the class does
            if isinstance(c, ClsV) and "__new__" in c.rec.get("m", {}):
                return
        kind = ix.model_kind(cls)
        inits = []     # (ClsV, sig) of explicit __init__ along the MRO, nearest first
        unknown = False
        for c in mro:
            if isinstance(c, ClsV):
                if "__init__" in c.rec.get("m", {}):
                    inits.append((c, c.rec["m"]["__init__"]))
            elif c == "?" or c not in CLOSED_EXTERNAL:
                unknown = True
        if kind is None:
            # an ordinary class: the nearest __init__ decides
            for c in mro:
                if isinstance(c, ClsV):
                    if "__init__" in c.rec.get("m", {}):
                        self.check_args(node, c.rec["m"]["__init__"], True, what)
                        return
                elif c in ("builtins.object", "object", "abc.ABC", "typing.Generic",
                           "typing.Protocol", "typing_extensions.Generic"):
                    continue
                else:
                    return   # __init__ may come from a base we do not have
            # object.__init__: no arguments at all
            self.check_args(node, {"a": ["self"]}, True, what)
            return
        if unknown and kind != "pydantic":
            return
        if any(isinstance(c, str) and (c == "?" or (c not in CLOSED_EXTERNAL))
               for c in mro):
            return   # fields may come from a base we do not have
        fields, npos_fields = [], 0
        for c in mro:
            if not isinstance(c, ClsV):
                continue
            if kind == "pydantic" and c.rec.get("extra") == "allow":
                return   # extra="allow": any keyword is kept as an extra attribute
            for a in c.rec.get("ann", []):
                name, flags = a[0], a[1:]
                if "cv" in flags:
                    continue
                if kind == "dataclass" and "ni" in flags:
                    continue
                fields.append(name)
                # pydantic accepts the alias (and, with populate_by_name, the name: both kept)
                fields += [f[len("alias="):] for f in flags if f.startswith("alias=")]
            if kind == "configclass":
                fields.extend(c.rec.get("ca", []))
        fields = list(dict.fromkeys(fields))
        if kind != "pydantic":
            npos_fields = len(fields)
            if any(x.rec.get("kwo") for x in mro if isinstance(x, ClsV)):
                npos_fields = 0
        # explicit __init__s: their named parameters are accepted too (pydantic models that
        # take deprecated keywords and forward **data to BaseModel); a dataclass whose own
        # __init__ takes **kwargs accepts anything
        extra_kw, max_pos, va = [], npos_fields, False
        for i, (c, sig) in enumerate(inits):
            params = sig.get("a", [])[1:]
            extra_kw += [p.rstrip("=") for p in params] + [p.rstrip("=") for p in sig.get("ko", [])]
            if i == 0:
                max_pos = max(max_pos, len(params))
            if "va" in sig and i == 0:
                va = True
            if "kw" in sig and kind != "pydantic":
                return
        star_args = any(isinstance(a, ast.Starred) for a in node.args)
        if not star_args and not va and len(node.args) > max_pos:
            self.err(node, "%s takes at most %d positional argument%s, %d given (%s)" % (
                what, max_pos, "" if max_pos == 1 else "s", len(node.args), ix.label))
        accepted = set(fields) | set(extra_kw)
        for kw in node.keywords:
            if kw.arg is None or kw.arg.startswith("_") or kw.arg in accepted:
                continue
            self.err(kw, "%s has no field or keyword '%s' (%s fields, %s)" % (what, kw.arg, kind, ix.label))

    def eval_call(self, node):
        f = self.eval(node.func)
        for a in node.args:
            self.eval(a.value if isinstance(a, ast.Starred) else a)
        for kw in node.keywords:
            self.eval(kw.value)
        name = ast.unparse(node.func)
        if isinstance(f, ClsV):
            self.check_construct(node, f)
            return InstV(f)
        if isinstance(f, FnV):
            self.check_args(node, f.sig, f.bound, "%s()" % self.short_qual(f.qual))
            return self.returned(f.sig, f.owner, "%s()" % name, call=(node, f.bound))
        if isinstance(f, InstV):
            r = self.ix.class_attr(f.cls, "__call__", True)
            if not isinstance(r, Missing) and r[0] is not OPAQUE and r[1] == "m":
                _owner, sig = r[0]
                self.check_args(node, sig, True, "%s.__call__()" % f.cls.short)
                return self.returned(sig, f.cls, "%s()" % name)
            return OPAQUE
        if isinstance(f, ScriptClassV):
            return ScriptInstV(f.sc)
        if isinstance(f, (OpaqueV, ModV, UnknownSimV)):
            return OPAQUE
        return None

    @staticmethod
    def short_qual(qual):
        parts = qual.split(".")
        # module.Class.method -> Class.method; module.func -> func
        for i, p in enumerate(parts):
            if p[:1].isupper():
                return ".".join(parts[i:])
        return parts[-1]

    # ------------------------------------------------------------------ expressions
    def eval(self, node):
        if node is None:
            return None
        if isinstance(node, ast.Name):
            return self.lookup(node.id)
        if isinstance(node, ast.Attribute):
            base = self.eval(node.value)
            if base is None:
                return None
            return self.getattr_value(base, node.attr, node)
        if isinstance(node, ast.Call):
            return self.eval_call(node)
        if isinstance(node, ast.Lambda):
            self.eval_defaults(node.args)
            self.scopes.append({a.arg: None for a in all_params(node.args)})
            self.eval(node.body)
            self.scopes.pop()
            return None
        if isinstance(node, (ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp)):
            self.scopes.append({})
            for g in node.generators:
                self.eval(g.iter)
                self.bind_target(g.target, None)
                for c in g.ifs:
                    self.eval(c)
            if isinstance(node, ast.DictComp):
                self.eval(node.key)
                self.eval(node.value)
            else:
                self.eval(node.elt)
            self.scopes.pop()
            return None
        if isinstance(node, ast.NamedExpr):
            v = self.eval(node.value)
            self.bind_target(node.target, v)
            return v
        if isinstance(node, ast.IfExp):
            self.eval(node.test)
            a, b = self.eval(node.body), self.eval(node.orelse)
            return a if a is b else None
        if isinstance(node, ast.BoolOp):
            vals = [self.eval(v) for v in node.values]
            return None if len({id(v) for v in vals}) > 1 else vals[0]
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.expr):
                self.eval(child)
            elif isinstance(child, (ast.comprehension, ast.keyword)):
                self.eval(child.value if isinstance(child, ast.keyword) else child.iter)
        return None

    def eval_defaults(self, args):
        for d in args.defaults + [d for d in args.kw_defaults if d is not None]:
            self.eval(d)

    # ------------------------------------------------------------------ statements
    def run(self, tree):
        self.collect_imports(tree)
        self.scopes = [{}]
        self.class_stack = []
        self.func_stack = []
        self.body(tree.body)
        return self.problems

    def body(self, stmts):
        for st in stmts:
            self.stmt(st)

    def stmt(self, st):
        if isinstance(st, (ast.Import, ast.ImportFrom)):
            self.check_import(st)
            if isinstance(st, ast.Import):
                for a in st.names:
                    if a.asname:
                        self.bind(a.asname, self.import_value(a.name))
                    else:
                        head = a.name.split(".")[0]
                        self.bind(head, self.import_value(head))
            elif st.level == 0 and st.module:
                for a in st.names:
                    if a.name != "*":
                        self.bind(a.asname or a.name, self.import_value(st.module + "." + a.name))
            return
        if isinstance(st, ast.Assign):
            v = self.eval(st.value)
            if isinstance(st.value, (ast.Tuple, ast.List)) and len(st.targets) == 1 \
                    and isinstance(st.targets[0], (ast.Tuple, ast.List)) \
                    and len(st.targets[0].elts) == len(st.value.elts):
                for t, e in zip(st.targets[0].elts, st.value.elts):
                    self.bind_target(t, self.eval(e) if not isinstance(e, ast.Starred) else None)
                return
            for t in st.targets:
                self.bind_target(t, v)
            return
        if isinstance(st, ast.AnnAssign):
            t = self.annotation_type(st.annotation)
            if st.value is not None:
                self.eval(st.value)
            if isinstance(st.target, ast.Name):
                if self.in_class_body():
                    sc = self.class_stack[-1]
                    sc.attrs[st.target.id] = t
                    sc.annotated.add(st.target.id)
                self.bind(st.target.id, t)
            elif isinstance(st.target, ast.Attribute):
                self.eval(st.target.value)
                self.self_attr_assign(st.target, t, annotated=True)
            else:
                self.bind_target(st.target, None)
            return
        if isinstance(st, ast.AugAssign):
            self.eval(st.value)
            if isinstance(st.target, ast.Name):
                self.eval(st.target)
                self.bind(st.target.id, None)
            else:
                self.bind_target(st.target, None)
            return
        if isinstance(st, (ast.FunctionDef, ast.AsyncFunctionDef)):
            self.function(st)
            return
        if isinstance(st, ast.ClassDef):
            self.classdef(st)
            return
        if isinstance(st, (ast.For, ast.AsyncFor)):
            self.eval(st.iter)
            self.bind_target(st.target, None)
            self.body(st.body)
            self.body(st.orelse)
            return
        if isinstance(st, (ast.With, ast.AsyncWith)):
            for item in st.items:
                self.eval(item.context_expr)
                if item.optional_vars is not None:
                    self.bind_target(item.optional_vars, None)
            self.body(st.body)
            return
        if isinstance(st, ast.Try) or (hasattr(ast, "TryStar") and isinstance(st, ast.TryStar)):
            # code that expects an attribute may be missing (version compatibility) is not
            # a misuse: `try: ... except AttributeError:` bodies are not held to the index
            catches_attr = any(h.type is not None and "AttributeError" in ast.unparse(h.type)
                               for h in st.handlers)
            self.attr_guarded += catches_attr
            self.body(st.body)
            self.attr_guarded -= catches_attr
            for h in st.handlers:
                self.eval(h.type)
                fallback = h.type is None or any(
                    (ast.unparse(t) if t is not None else "") in
                    ("ImportError", "ModuleNotFoundError", "Exception", "BaseException")
                    for t in (h.type.elts if isinstance(h.type, ast.Tuple) else [h.type]))
                if h.name:
                    self.bind(h.name, None)
                self.in_fallback += fallback
                self.body(h.body)
                self.in_fallback -= fallback
            self.body(st.orelse)
            self.body(st.finalbody)
            return
        if isinstance(st, (ast.If, ast.While)):
            self.eval(st.test)
            added = hasattr_guards(st.test) - self.guards
            self.guards |= added     # `if hasattr(obj, "name"):` -- obj.name is guarded
            self.body(st.body)
            self.guards -= added
            self.body(st.orelse)
            return
        if hasattr(ast, "Match") and isinstance(st, ast.Match):
            self.eval(st.subject)
            for case in st.cases:
                self.eval(case.guard)
                self.body(case.body)
            return
        for child in ast.iter_child_nodes(st):
            if isinstance(child, ast.expr):
                self.eval(child)

    def in_class_body(self):
        # classdef() empties func_stack while it visits a class body, so a class body is
        # "a class on the stack and no function inside it yet"
        return bool(self.class_stack) and not self.func_stack

    def function(self, fn):
        for d in fn.decorator_list:
            self.eval(d)
        self.eval_defaults(fn.args)
        scope = {}
        params = all_params(fn.args)
        in_class = self.in_class_body()
        sc = self.class_stack[-1] if in_class else None
        decos = {ast.unparse(d) for d in fn.decorator_list}
        for i, p in enumerate(params):
            t = None
            if p.annotation is not None:
                t = self.annotation_type(p.annotation)
            elif i == 0 and sc is not None and "staticmethod" not in decos and p in fn.args.posonlyargs + fn.args.args:
                t = ScriptInstV(sc) if "classmethod" not in decos else None
            elif p.arg in self.imports and isinstance(self.import_value(self.imports[p.arg]), ModV):
                # `def build(gs, ...)`: the module passed as a parameter under its alias
                t = self.import_value(self.imports[p.arg])
            scope[p.arg] = t
        if fn.returns is not None:
            self.annotation_type(fn.returns)
        self.bind(fn.name, None)
        self.scopes.append(scope)
        self.func_stack.append((fn, sc, len(self.class_stack)))
        self.body(fn.body)
        self.func_stack.pop()
        self.scopes.pop()

    def classdef(self, cd):
        for d in cd.decorator_list:
            self.eval(d)
        sc = ScriptClass(cd.name)
        for b in cd.bases:
            v = self.eval(b)
            if isinstance(v, ClsV):
                sc.sim_bases.append(v)
        for kw in cd.keywords:
            self.eval(kw.value)
        # annotations of self.x anywhere in the class: known before the methods run
        for sub in ast.walk(cd):
            if isinstance(sub, ast.AnnAssign) and isinstance(sub.target, ast.Attribute) \
                    and isinstance(sub.target.value, ast.Name) and sub.target.value.id == "self":
                sc.attrs[sub.target.attr] = self.annotation_type(sub.annotation)
                sc.annotated.add(sub.target.attr)
        self.scopes.append({})
        self.class_stack.append(sc)
        # the class body runs in its own scope; methods do not see it (Python rules)
        saved = self.func_stack
        self.func_stack = []
        self.body(cd.body)
        self.func_stack = saved
        self.class_stack.pop()
        self.scopes.pop()
        self.bind(cd.name, ScriptClassV(sc))

    def self_attr_assign(self, target, value, annotated):
        """`self.x = value` in a method of a script class: remember the type of x."""
        if not (isinstance(target.value, ast.Name) and self.func_stack):
            return
        fn, sc, _ = self.func_stack[-1]
        if sc is None:
            return
        params = fn.args.posonlyargs + fn.args.args
        if not params or params[0].arg != target.value.id:
            return
        name = target.attr
        if annotated:
            sc.attrs[name] = value
            sc.annotated.add(name)
            return
        if name in sc.annotated:
            return
        if name not in sc.attrs:
            sc.attrs[name] = value
        elif not same_type(sc.attrs[name], value):
            sc.attrs[name] = None   # assigned different things: not tracked


class ScriptClassV(V):
    def __init__(self, sc):
        self.sc = sc


def same_type(a, b):
    if a is None or b is None:
        return a is b
    if isinstance(a, InstV) and isinstance(b, InstV):
        return a.cls.qual == b.cls.qual
    return type(a) is type(b) and isinstance(a, UnknownSimV)


def hasattr_guards(test):
    """(ast.dump(obj), name) for every `hasattr(obj, "name")` that must hold for the test
    to be true (alone or in an `and`)."""
    out = set()
    tests = test.values if isinstance(test, ast.BoolOp) and isinstance(test.op, ast.And) else [test]
    for t in tests:
        if isinstance(t, ast.Call) and isinstance(t.func, ast.Name) and t.func.id == "hasattr" \
                and len(t.args) == 2 and isinstance(t.args[1], ast.Constant) and isinstance(t.args[1].value, str):
            out.add((ast.dump(t.args[0]), t.args[1].value))
    return out


def pick_overload(variants, call):
    """The first @overload variant a call matches, as a type checker picks it, judging only
    what can be told without types: a parameter annotated `None` in the variant must be
    omitted or passed the literal None. None when no call is known or nothing matches."""
    if call is None:
        return None
    node, bound = call
    for v in variants:
        if isinstance(v, str):
            return None   # an index from an early extract_api.py: return types only
        params = v.get("a", [])[1:] if bound else v.get("a", [])
        given = {}
        for p, a in zip(params, node.args):
            given[p] = a
        if any(isinstance(a, ast.Starred) for a in node.args) or any(k.arg is None for k in node.keywords):
            return None
        for k in node.keywords:
            given[k.arg] = k.value
        if all(n not in given or (isinstance(given[n], ast.Constant) and given[n].value is None)
               for n in v.get("none", [])):
            return v
    return None


def all_params(args):
    out = list(args.posonlyargs) + list(args.args)
    if args.vararg:
        out.append(args.vararg)
    out += list(args.kwonlyargs)
    if args.kwarg:
        out.append(args.kwarg)
    return out


# --------------------------------------------------------------------------- API


def load_index(path):
    with open(path, encoding="utf-8") as f:
        return Index(json.load(f))


def check_source(text, filename, index):
    """Problems in one script's source text (raises SyntaxError if it does not parse)."""
    tree = ast.parse(text, filename=filename)
    return Checker(index, filename).run(tree)


def format_sig(name, sig):
    """A signature record as Python-like text: name(a, b=..., *, c) -> R."""
    if sig.get("k") == "p":
        return "%s (property%s)%s" % (name, ", settable" if sig.get("set") else "",
                                      " -> " + sig["r"] if "r" in sig else "")
    parts = []
    for i, p in enumerate(sig.get("a", [])):
        parts.append(p.rstrip("=") + ("=..." if p.endswith("=") else ""))
        if sig.get("po") and i == sig["po"] - 1:
            parts.append("/")
    if "va" in sig:
        parts.append("*" + sig["va"])
    elif sig.get("ko"):
        parts.append("*")
    parts += [p.rstrip("=") + ("=..." if p.endswith("=") else "") for p in sig.get("ko", [])]
    if "kw" in sig:
        parts.append("**" + sig["kw"])
    text = "%s(%s)" % (name, ", ".join(parts))
    if "r" in sig:
        text += " -> " + sig["r"]
    if sig.get("k") in ("s", "c"):
        text = ("@staticmethod " if sig["k"] == "s" else "@classmethod ") + text
    return text


def describe(index, dotted):
    """What the index knows about a dotted name (for people writing scripts)."""
    ix = index if isinstance(index, Index) else Index(index)
    v = ix.resolve(dotted)
    if isinstance(v, Missing):
        return "%s: not in %s (%s has no such attribute)" % (dotted, ix.label, v.where)
    if isinstance(v, ModV):
        rec = ix.modules[v.name]
        names = sorted(set(rec.get("fn", {})) | set(rec.get("cls", {})) | set(rec.get("n", {})))
        subs = sorted(m[len(v.name) + 1:] for m in ix.modules
                      if m.startswith(v.name + ".") and "." not in m[len(v.name) + 1:])
        return "module %s (%s)\n  names: %s\n  submodules: %s%s" % (
            v.name, rec.get("f", "no file"), ", ".join(names), ", ".join(subs),
            ("\n  star imports: " + ", ".join(rec["star"])) if rec.get("star") else "")
    if isinstance(v, FnV):
        return "%s: %s" % (v.qual, format_sig(v.qual.rsplit(".", 1)[-1], v.sig))
    if isinstance(v, ClsV):
        lines = ["class %s(%s)" % (v.qual, ", ".join(v.rec.get("b", []) + v.rec.get("ub", [])))]
        mro = ix.mro(v)
        lines.append("  mro: " + " > ".join(c.short if isinstance(c, ClsV) else c for c in mro))
        kind = ix.model_kind(v)
        if kind:
            fields = []
            for c in mro:
                if isinstance(c, ClsV):
                    fields += [a[0] for a in c.rec.get("ann", []) if "cv" not in a[1:]
                               and not (kind == "dataclass" and "ni" in a[1:])]
                    if kind == "configclass":
                        fields += c.rec.get("ca", [])
            lines.append("  %s fields (init keywords): %s" % (kind, ", ".join(dict.fromkeys(fields))))
        seen = set()
        for c in mro:
            if not isinstance(c, ClsV):
                continue
            for name, sig in c.rec.get("m", {}).items():
                if name not in seen:
                    seen.add(name)
                    lines.append("  %s%s" % (format_sig(name, sig),
                                             "" if c is v else "   [from %s]" % c.short))
            for name in c.rec.get("ca", []) + c.rec.get("ia", []):
                if name not in seen:
                    seen.add(name)
                    lines.append("  %s (attribute)%s" % (name, "" if c is v else "   [from %s]" % c.short))
        why = ix.class_open(v)
        if why:
            lines.append("  (attributes not checked: %s)" % why)
        return "\n".join(lines)
    return "%s: exists, not checkable (%s)" % (dotted, type(v).__name__)


def main(argv=None):
    ap = argparse.ArgumentParser(description="Check scripts against a simulator API index.")
    ap.add_argument("--index", required=True, help="index JSON made by extract_api.py")
    ap.add_argument("--show", action="append", default=[], metavar="DOTTED.NAME",
                    help="print what the index knows about a name (module, class, function)")
    ap.add_argument("scripts", nargs="*")
    try:
        args = ap.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    if not args.scripts and not args.show:
        print("check_api: no script to check (or --show NAME)", file=sys.stderr)
        return 2
    try:
        index = load_index(args.index)
    except (OSError, ValueError, KeyError) as e:
        print("check_api: cannot read index %s: %s" % (args.index, e), file=sys.stderr)
        return 2
    for name in args.show:
        print(describe(index, name))
    problems, usage = [], False
    for path in args.scripts:
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
            problems += check_source(text, path, index)
        except OSError as e:
            print("check_api: cannot read %s: %s" % (path, e), file=sys.stderr)
            usage = True
        except SyntaxError as e:
            # a script that does not parse is a problem of the script, not of the usage
            problems.append(Problem(path, e.lineno or 0, e.offset or 0, "syntax error: %s" % e.msg))
    for p in problems:
        print(p)
    if usage:
        return 2
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
