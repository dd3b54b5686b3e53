#!/usr/bin/env python3
"""Extract the public API of a Python package from its source, without importing it.

    python3 extract_api.py --root SRC_DIR --package genesis [--package ...] \
        --name Genesis --version 0.4.5 --source-url URL --commit SHA --out genesis-0.4.5.json \
        [--include-subpackage genesis.engine ...] [--exclude-subpackage genesis.ext ...] \
        [--unchecked MODULE=REASON ...]

The simulators cannot be installed here, so `check_api.py` checks scripts against this
index instead. Only the standard library is used and no file of the package is imported
(importing would need the simulator's compiled dependencies and a GPU).

The tree may be partial (files fetched one by one): a module that is referenced but not
present is simply absent from the index; the checker treats whatever leads to it
(a base class, a re-export, `from .x import *`) as unresolved, i.e. not checkable, never
as an error.

Index format (format "efc-sim-api", version 1), one JSON object, minified:

  {"format": "efc-sim-api", "version": 1,
   "provenance": {simulator, version, source_url, commit, extracted, command, root_packages,
                  include_subpackages, exclude_subpackages},
   "unchecked_modules": {module: reason},
   "modules": {dotted module name: MODULE}}

  MODULE = {"f": file relative to --root, "pkg": 1 if a package,
            "fn": {name: SIG}, "cls": {name: CLASS},
            "n": {name: NAME},           # every other module-level binding
            "star": [dotted module],     # `from M import *` (resolved lazily by the checker)
            "all": [names],              # static __all__, when present
            "open": reason,              # names can appear dynamically: missing names are
                                         # not errors (module __getattr__, globals()[x] = ...,
                                         # syntax error in the file)
            "xn": [names]}               # extra names a closed module __getattr__ answers

  NAME = {"a": dotted}                   # an import / alias of another object
       | {"v": 1, "t": dotted?, "c": dotted?}
                                         # a variable; "t" its annotated type, "c" the callee
                                         # when the value is a call (the checker uses it
                                         # only when it resolves to an indexed class)
       | {"v": 1, "multi": 1}            # bound several ways (try/except, redefinition): unknown

  SIG = {"a": ["self", "x", "y="],       # positional-or-keyword params; "=" suffix: has a default
         "po": 1,                        # how many of "a" are positional-only (absent: 0)
         "ko": ["z", "w="],              # keyword-only params
         "va": "args", "kw": "kwargs",   # present when the function has *args / **kwargs
         "r": "return annotation source", "rt": "resolved dotted return type",
         "k": "s"|"c"|"p",               # methods only: staticmethod, classmethod, property
         "set": 1,                       # property with a setter
         "ov": [{"rt": "resolved return" or "?", "a": [params], "none": [params annotated None]}],
                                         # the @overload variants, in order
         "via": "_sim.rigid_solver"}     # property without annotation whose body is
                                         # `return self._sim.rigid_solver`

  CLASS = {"b": [dotted bases], "ub": [unresolvable base expressions],
           "m": {name: SIG}, "ca": [class attributes], "ann": [[name, flags]],
           "ia": [instance attributes (self.x = ...)], "cls": {nested classes},
           "dc": "dataclass"|"configclass", "kwo": 1 (dataclass(kw_only=True)),
           "open": reason, "xa": [extra names a closed __getattr__ answers],
           "meta": dotted metaclass, "priv": 1 (private, kept because it is a base),
           "extra": pydantic model_config extra ("forbid", "allow", "ignore")}
  ann flags: "=" has a default, "cv" ClassVar, "ni" field(init=False), "kw" keyword-only
  (after a KW_ONLY marker), "alias=NAME" pydantic Field(alias=NAME). Types of annotated attributes are in "at": {name: dotted}.
  "it": {attribute: dotted} types of instance attributes (private ones too, for "via"):
  from `self.x: T = ...` or a parameter annotated T ("dotted"), or from
  `self.x = Callee(...)` ("dotted()": every non-None assignment calls the same callee;
  the checker uses it only when the callee is an indexed class).

Private names (leading "_", except dunders such as __init__ / __call__) are dropped, but
private classes that are bases of other classes are kept (their public methods are
inherited), and private modules are kept (re-exports point into them).
"""

import argparse
import ast
import datetime
import json
import os
import shlex
import sys

FORMAT = "efc-sim-api"
FORMAT_VERSION = 1


def is_private(name):
    """Leading underscore, but dunders (__init__, __call__, __getattr__ ...) are public."""
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def dotted(node):
    """a.b.c for a Name/Attribute chain, else None."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
        return ".".join(reversed(parts))
    return None


def is_type_checking_test(test):
    name = dotted(test)
    return name in ("TYPE_CHECKING", "typing.TYPE_CHECKING")


def is_main_test(test):
    # `if __name__ == "__main__":` blocks define nothing importable.
    return (isinstance(test, ast.Compare) and isinstance(test.left, ast.Name)
            and test.left.id == "__name__")


class ModuleInfo:
    def __init__(self, name, relfile, is_pkg):
        self.name = name
        self.relfile = relfile
        self.is_pkg = is_pkg
        self.trees = []          # (ast.Module) from .py and/or .pyi
        self.kinds = []          # ".py" / ".pyi", one per tree
        self.scope = {}          # name -> dotted (imports, defs) for resolution
        self.tc_scope = {}       # TYPE_CHECKING-only imports: for annotations only
        self.out = None


class Extractor:
    def __init__(self, root, packages, include, exclude):
        self.root = os.path.abspath(root)
        self.packages = packages
        self.include = include
        self.exclude = exclude
        self.modules = {}
        self.base_names = set()   # last components of every base expression (keep private bases)
        self.errors = []

    # ---------------------------------------------------------------- discovery
    def wanted(self, modname):
        for ex in self.exclude:
            if modname == ex or modname.startswith(ex + "."):
                return False
        if not self.include:
            return True
        for inc in self.include:
            # a module inside an included subpackage, or a package on the way to one
            # (its __init__ defines the re-exports that lead there)
            if modname == inc or modname.startswith(inc + ".") or inc.startswith(modname + "."):
                return True
        return modname in self.packages

    def discover(self):
        for pkg in self.packages:
            top = os.path.join(self.root, *pkg.split("."))
            if os.path.isfile(top + ".py") or os.path.isfile(top + ".pyi"):
                self.add_file(pkg, top + (".py" if os.path.isfile(top + ".py") else ".pyi"), False)
                continue
            if not os.path.isdir(top):
                sys.exit("extract_api: package %s not found under %s" % (pkg, self.root))
            for dirpath, dirnames, filenames in os.walk(top):
                dirnames[:] = sorted(d for d in dirnames if d.isidentifier())
                rel = os.path.relpath(dirpath, self.root)
                pkgname = ".".join(rel.split(os.sep))
                # A directory is a package whether or not __init__.py was fetched
                # (namespace packages, partial trees), but only if it holds Python files:
                # folders of assets (fonts, shaders) are not packages.
                if self.wanted(pkgname) and pkgname not in self.modules and has_python(dirpath):
                    self.modules[pkgname] = ModuleInfo(pkgname, None, True)
                for fn in sorted(filenames):
                    stem, ext = os.path.splitext(fn)
                    if ext not in (".py", ".pyi") or not stem.isidentifier():
                        continue
                    path = os.path.join(dirpath, fn)
                    if stem == "__init__":
                        self.add_file(pkgname, path, True)
                    else:
                        self.add_file(pkgname + "." + stem, path, False)

    def add_file(self, modname, path, is_pkg):
        if not self.wanted(modname):
            return
        info = self.modules.get(modname)
        rel = os.path.relpath(path, self.root).replace(os.sep, "/")
        if info is None:
            info = self.modules[modname] = ModuleInfo(modname, rel, is_pkg)
        elif info.relfile is None or rel.endswith(".py"):
            info.relfile = rel
        try:
            with open(path, "rb") as f:
                src = f.read()
            tree = ast.parse(src, filename=path)
        except (SyntaxError, ValueError, UnicodeDecodeError) as e:
            # Vendored Python-2 files and the like: the module exists but we do not know
            # what it defines, so the checker must not report its names as missing.
            info.parse_error = "not parsable by Python 3.11: %s" % (e.__class__.__name__,)
            self.errors.append("%s: %s" % (rel, e))
            return
        info.trees.append(tree)
        info.kinds.append(os.path.splitext(path)[1])

    # ---------------------------------------------------------------- resolution
    def resolve_relative(self, info, level, module):
        if level == 0:
            return module
        base = info.name.split(".")
        if not info.is_pkg:
            base = base[:-1]
        if level > 1:
            base = base[: len(base) - (level - 1)]
        if module:
            base = base + module.split(".")
        return ".".join(base)

    def resolve_name(self, info, name, local=None):
        """Dotted target of a (dotted) name as seen from module `info`."""
        head, _, rest = name.partition(".")
        target = None
        if local and head in local:
            target = local[head]
        elif head in info.scope:
            target = info.scope[head]
        elif head in info.tc_scope:
            target = info.tc_scope[head]
        elif head in BUILTIN_TYPES:
            target = "builtins." + head
        if target is None:
            return None
        return target + ("." + rest if rest else "")

    def resolve_annotation(self, info, node, local=None, depth=0):
        """A type annotation to one dotted class name, when it names one class.

        `X | None`, `Optional[X]`, `Union[X, None]` and string annotations give X; `Self`
        gives "Self"; anything else (containers, TypeVars resolve later, unions of several
        classes) gives None."""
        if node is None or depth > 5:
            return None
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            try:
                expr = ast.parse(node.value.strip(), mode="eval").body
            except SyntaxError:
                return None
            return self.resolve_annotation(info, expr, local, depth + 1)
        if isinstance(node, ast.Constant) and node.value is None:
            return None
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr):
            parts = [p for p in (node.left, node.right)
                     if not (isinstance(p, ast.Constant) and p.value is None)]
            if len(parts) == 1:
                return self.resolve_annotation(info, parts[0], local, depth + 1)
            return None
        if isinstance(node, ast.Subscript):
            outer = dotted(node.value)
            outer_t = self.resolve_name(info, outer, local) if outer else None
            if outer_t in ("typing.Optional", "typing_extensions.Optional"):
                return self.resolve_annotation(info, node.slice, local, depth + 1)
            if outer_t in ("typing.Union", "typing_extensions.Union") and isinstance(node.slice, ast.Tuple):
                parts = [p for p in node.slice.elts
                         if not (isinstance(p, ast.Constant) and p.value is None)
                         and dotted(p) not in ("None", "type(None)")]
                if len(parts) == 1:
                    return self.resolve_annotation(info, parts[0], local, depth + 1)
            if outer_t in ("typing.Annotated", "typing_extensions.Annotated") and isinstance(node.slice, ast.Tuple):
                return self.resolve_annotation(info, node.slice.elts[0], local, depth + 1)
            return None
        name = dotted(node)
        if name is None:
            return None
        if name in ("Self", "typing.Self", "typing_extensions.Self"):
            return "Self"
        target = self.resolve_name(info, name, local)
        if target in ("typing.Self", "typing_extensions.Self"):
            return "Self"
        return target

    # ---------------------------------------------------------------- pass 1: bindings
    def collect_scope(self, info):
        """Module-level name -> dotted target, for resolving bases and annotations."""
        for tree in info.trees:
            self._scope_body(info, tree.body, tc=False)

    def _scope_body(self, info, body, tc):
        scope = info.tc_scope if tc else info.scope
        for st in body:
            if isinstance(st, ast.Import):
                for a in st.names:
                    if a.asname:
                        scope[a.asname] = a.name
                    else:
                        head = a.name.split(".")[0]
                        scope[head] = head
            elif isinstance(st, ast.ImportFrom):
                mod = self.resolve_relative(info, st.level, st.module)
                for a in st.names:
                    if a.name == "*":
                        continue
                    scope[a.asname or a.name] = mod + "." + a.name
            elif isinstance(st, (ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
                if not tc:
                    scope[st.name] = info.name + "." + st.name
            elif isinstance(st, ast.If):
                if is_main_test(st.test):
                    continue
                self._scope_body(info, st.body, tc or is_type_checking_test(st.test))
                self._scope_body(info, st.orelse, tc)
            elif isinstance(st, ast.Try):
                for b in [st.body, st.orelse, st.finalbody] + [h.body for h in st.handlers]:
                    self._scope_body(info, b, tc)
            elif isinstance(st, (ast.With, ast.AsyncWith)):
                self._scope_body(info, st.body, tc)
            elif isinstance(st, ast.Assign) and not tc:
                src = dotted(st.value)
                for t in st.targets:
                    if isinstance(t, ast.Name) and t.id not in scope:
                        # `Alias = other.Name`: resolvable alias; else a local variable
                        scope[t.id] = (self.resolve_name(info, src) if src else None) or (info.name + "." + t.id)

    # ---------------------------------------------------------------- pass 2: records
    def extract_module(self, info):
        out = {}
        if info.relfile:
            out["f"] = info.relfile
        if info.is_pkg:
            out["pkg"] = 1
        fns, classes, names, star = {}, {}, {}, []
        state = {"all": None, "all_dynamic": False, "open": None, "xn": None}
        for tree in info.trees:
            self._module_body(info, tree.body, fns, classes, names, star, state)
        self._function_globals(info, names, state)
        for name in list(names):
            if name in fns or name in classes:
                names.pop(name)   # `global f` in a function that rebinds a def: keep the def
        if getattr(info, "parse_error", None):
            state["open"] = info.parse_error
        if info.relfile is None and not info.is_pkg:
            state["open"] = "no source file"
        if fns:
            out["fn"] = fns
        if classes:
            out["cls"] = classes
        if names:
            out["n"] = names
        if star:
            out["star"] = star
        if state["all"] is not None and not state["all_dynamic"]:
            out["all"] = state["all"]
        if state["open"]:
            out["open"] = state["open"]
        if state["xn"]:
            out["xn"] = state["xn"]
        info.out = out

    def _bind(self, tables, which, name, value):
        """Record a module-level binding in tables[which] (tables = fns, classes, names).

        A name bound twice in different ways (try/except fallbacks, if/else branches,
        `f = wrap(f)`) becomes an unknown variable: it exists, nothing more is known."""
        if is_private(name):
            return
        fns, classes, names = tables
        table = tables[which]
        elsewhere = any(name in t for i, t in enumerate(tables) if i != which)
        if elsewhere or (name in table and table[name] != value):
            fns.pop(name, None)
            classes.pop(name, None)
            names[name] = {"v": 1, "multi": 1}
            return
        table[name] = value

    def _module_body(self, info, body, fns, classes, names, star, state, in_try=False):
        tables = (fns, classes, names)
        for st in body:
            if isinstance(st, ast.Import):
                for a in st.names:
                    if a.asname:
                        self._bind(tables, 2, a.asname, {"a": a.name})
                    else:
                        head = a.name.split(".")[0]
                        self._bind(tables, 2, head, {"a": head})
            elif isinstance(st, ast.ImportFrom):
                mod = self.resolve_relative(info, st.level, st.module)
                for a in st.names:
                    if a.name == "*":
                        if mod not in star:
                            star.append(mod)
                        continue
                    self._bind(tables, 2, a.asname or a.name, {"a": mod + "." + a.name})
            elif isinstance(st, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if st.name == "__getattr__":
                    closed, extra = analyse_getattr(st)
                    if closed:
                        state["xn"] = sorted(set(state["xn"] or []) | extra)
                    else:
                        state["open"] = "module __getattr__"
                    continue
                if is_private(st.name):
                    continue
                if any(dotted(d) in ("overload", "typing.overload", "typing_extensions.overload")
                       for d in st.decorator_list):
                    continue  # the implementation follows; overloads of functions: rare
                self._bind(tables, 0, st.name, self.signature(info, st, method=False))
            elif isinstance(st, ast.ClassDef):
                if is_private(st.name) and st.name not in self.base_names:
                    continue
                rec = self.class_record(info, st, info.name + "." + st.name)
                if is_private(st.name):
                    # kept only because a class derives from it
                    rec["priv"] = 1
                    classes[st.name] = rec
                else:
                    self._bind(tables, 1, st.name, rec)
            elif isinstance(st, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                self._module_assign(info, st, fns, classes, names, state)
            elif isinstance(st, ast.Expr) and isinstance(st.value, ast.Call):
                self._module_call(info, st.value, state)
            elif isinstance(st, ast.If):
                if is_main_test(st.test):
                    continue
                if is_type_checking_test(st.test):
                    # names imported for type checking only do not exist at run time
                    self._module_body(info, st.orelse, fns, classes, names, star, state)
                    continue
                self._module_body(info, st.body, fns, classes, names, star, state)
                self._module_body(info, st.orelse, fns, classes, names, star, state)
            elif isinstance(st, ast.Try):
                for b in [st.body, st.orelse, st.finalbody] + [h.body for h in st.handlers]:
                    self._module_body(info, b, fns, classes, names, star, state, in_try=True)
            elif isinstance(st, (ast.With, ast.AsyncWith)):
                self._module_body(info, st.body, fns, classes, names, star, state)
            elif isinstance(st, (ast.For, ast.AsyncFor, ast.While)):
                self._module_loop(info, st, names, state)

    def _module_call(self, info, call, state):
        fname = dotted(call.func)
        # __all__.extend([...]) / __all__.append("x")
        if fname in ("__all__.extend", "__all__.append", "__all__.__iadd__"):
            if state["all"] is None:
                state["all"] = []
            vals = strings_of(call.args[0]) if call.args else None
            if fname == "__all__.append" and call.args and isinstance(call.args[0], ast.Constant):
                vals = [call.args[0].value] if isinstance(call.args[0].value, str) else None
            if vals is None:
                state["all_dynamic"] = True
            else:
                state["all"] += vals
        elif fname in ("globals().update", "setattr", "vars().update") or (
                isinstance(call.func, ast.Attribute) and call.func.attr == "update"
                and isinstance(call.func.value, ast.Call) and dotted(call.func.value.func) in ("globals", "vars")):
            if fname == "setattr" and not (call.args and is_this_module(call.args[0])):
                return  # setattr(some_object, ...) does not touch this module
            state["open"] = "names set dynamically (%s)" % (fname or "globals().update")
        elif fname and fname.endswith("lazy_loader.attach_stub") or fname == "lazy.attach_stub":
            state["open"] = "lazy_loader stub"

    def _module_assign(self, info, st, fns, classes, names, state):
        targets = st.targets if isinstance(st, ast.Assign) else [st.target]
        value = st.value
        for t in targets:
            if isinstance(t, ast.Name):
                if t.id == "__all__":
                    if isinstance(st, ast.AugAssign):
                        vals = strings_of(value)
                        if vals is None:
                            state["all_dynamic"] = True
                        else:
                            state["all"] = (state["all"] or []) + vals
                    else:
                        vals = strings_of(value) if value is not None else []
                        if vals is None:
                            state["all_dynamic"] = True
                        else:
                            state["all"] = vals
                    continue
                if t.id == "__getattr__":
                    state["open"] = "module __getattr__"
                    continue
                if isinstance(st, ast.AugAssign):
                    continue
                rec = {"v": 1}
                src = dotted(value) if value is not None else None
                if src and not isinstance(st, ast.AnnAssign):
                    target = self.resolve_name(info, src)
                    if target:
                        rec = {"a": target}
                if "a" not in rec:
                    if isinstance(st, ast.AnnAssign):
                        ty = self.resolve_annotation(info, st.annotation)
                        if ty:
                            rec["t"] = ty
                    if isinstance(value, ast.Call):
                        callee = dotted(value.func)
                        callee = self.resolve_name(info, callee) if callee else None
                        if callee:
                            rec["c"] = callee
                if is_private(t.id):
                    continue
                if t.id in names and names[t.id] != rec:
                    # `logger: Logger | None = None` then reassigned: keep the annotation
                    old = names[t.id]
                    if "t" in old and "a" not in rec:
                        continue
                    names[t.id] = {"v": 1, "multi": 1}
                    continue
                if t.id in fns or t.id in classes:
                    # `f = decorate(f)`: no longer the def we recorded
                    fns.pop(t.id, None)
                    classes.pop(t.id, None)
                    names[t.id] = {"v": 1, "multi": 1}
                    continue
                names[t.id] = rec
            elif isinstance(t, (ast.Tuple, ast.List)):
                for e in ast.walk(t):
                    if isinstance(e, ast.Name) and e.id == "__getattr__":
                        # `__getattr__, __dir__, __all__ = lazy.attach_stub(...)` without its
                        # .pyi (partial tree): any name may exist
                        state["open"] = "module __getattr__ (lazy loading)"
                        continue
                    if isinstance(e, ast.Name) and e.id == "__all__":
                        state["all_dynamic"] = True
                        continue
                    if isinstance(e, ast.Name) and not is_private(e.id):
                        if e.id in fns or e.id in classes:
                            fns.pop(e.id, None)
                            classes.pop(e.id, None)
                        names[e.id] = {"v": 1} if e.id not in names else {"v": 1, "multi": 1}
            elif isinstance(t, ast.Subscript):
                base = t.value
                if isinstance(base, ast.Call) and dotted(base.func) in ("globals", "vars", "locals"):
                    if not self._known_globals_loop(info, st, names):
                        state["open"] = "names set dynamically (globals()[...] = ...)"

    def _module_loop(self, info, st, names, state):
        # The only loop that defines module names we recognise is Genesis's
        #   for name, member in SomeEnum.__members__.items(): globals()[name] = member
        # which binds every member of an enum class at module level. Any other loop writing
        # globals() makes the module open.
        self._loop_stack = getattr(self, "_loop_stack", [])
        self._loop_stack.append(st)
        try:
            for sub in ast.walk(st):
                if isinstance(sub, ast.Assign):
                    for t in sub.targets:
                        if isinstance(t, ast.Subscript) and isinstance(t.value, ast.Call) \
                                and dotted(t.value.func) in ("globals", "vars", "locals"):
                            if not self._known_globals_loop(info, sub, names):
                                state["open"] = "names set dynamically (globals()[...] = ...)"
                        elif isinstance(t, ast.Name) and not is_private(t.id):
                            # a name assigned in a module-level loop exists afterwards
                            # (when the loop runs at least once): unknown value
                            names.setdefault(t.id, {"v": 1, "multi": 1})
                elif isinstance(sub, ast.Call) and (dotted(sub.func) in ("setattr",) or (
                        isinstance(sub.func, ast.Attribute) and sub.func.attr == "update"
                        and isinstance(sub.func.value, ast.Call)
                        and dotted(sub.func.value.func) in ("globals", "vars"))):
                    if dotted(sub.func) == "setattr" and not (sub.args and is_this_module(sub.args[0])):
                        continue   # setattr(other_object, ...)
                    if dotted(sub.func) == "setattr" and self._known_setattr_loop(info, st, sub, names):
                        continue
                    state["open"] = "names set dynamically"
        finally:
            self._loop_stack.pop()

    def _known_setattr_loop(self, info, loop, call, names):
        """Genesis's grad/creation_ops.py:
            for _op in _ops:          # _ops = (torch.tensor, torch.zeros, ...)
                setattr(sys.modules[__name__], _op.__name__, wrap(_op))
        binds the last component of every element of the literal tuple."""
        if not isinstance(loop, ast.For) or not isinstance(loop.target, ast.Name) or len(call.args) < 2:
            return False
        key = call.args[1]
        if not (isinstance(key, ast.Attribute) and key.attr == "__name__"
                and isinstance(key.value, ast.Name) and key.value.id == loop.target.id):
            return False
        seq = loop.iter
        if isinstance(seq, ast.Name):
            seq = self._module_literal(info, seq.id)
        if not isinstance(seq, (ast.Tuple, ast.List)):
            return False
        got = [dotted(e) for e in seq.elts]
        if not all(got):
            return False
        for g in got:
            last = g.rsplit(".", 1)[-1]
            if not is_private(last):
                names.setdefault(last, {"v": 1, "multi": 1})
        return True

    def _module_literal(self, info, name):
        for tree in info.trees:
            for st in tree.body:
                if isinstance(st, ast.Assign) and len(st.targets) == 1 \
                        and isinstance(st.targets[0], ast.Name) and st.targets[0].id == name:
                    return st.value
        return None

    def _function_globals(self, info, names, state):
        """`global x` in a function, then x = ...: x becomes a module name (Genesis sets
        gs.tc_float and friends in gs.init()). `globals()["x"] = ...` in a function binds
        x; with a computed key the module is open."""
        for tree in info.trees:
            for fn in ast.walk(tree):
                if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    continue
                declared = set()
                for sub in ast.walk(fn):
                    if isinstance(sub, ast.Global):
                        declared.update(sub.names)
                    elif isinstance(sub, ast.Assign):
                        for t in sub.targets:
                            if isinstance(t, ast.Subscript) and isinstance(t.value, ast.Call) \
                                    and dotted(t.value.func) == "globals":
                                if isinstance(t.slice, ast.Constant) and isinstance(t.slice.value, str):
                                    declared.add(t.slice.value)
                                else:
                                    state["open"] = "names set dynamically (globals()[...] = ...)"
                for name in declared:
                    if not is_private(name):
                        names.setdefault(name, {"v": 1, "multi": 1})

    def _known_globals_loop(self, info, assign, names):
        loops = getattr(self, "_loop_stack", [])
        if not loops:
            return False
        loop = loops[-1]
        it = loop.iter if isinstance(loop, (ast.For, ast.AsyncFor)) else None
        # SomeEnum.__members__.items()
        if not (isinstance(it, ast.Call) and isinstance(it.func, ast.Attribute) and it.func.attr == "items"):
            return False
        members = it.func.value
        if not (isinstance(members, ast.Attribute) and members.attr == "__members__"):
            return False
        enum_name = dotted(members.value)
        target = self.resolve_name(info, enum_name) if enum_name else None
        if not target:
            return False
        mod, _, cname = target.rpartition(".")
        cinfo = self.modules.get(mod)
        if cinfo is None:
            return False
        for tree in cinfo.trees:
            for st in tree.body:
                if isinstance(st, ast.ClassDef) and st.name == cname:
                    for cst in st.body:
                        if isinstance(cst, ast.Assign):
                            for t in cst.targets:
                                if isinstance(t, ast.Name) and not is_private(t.id):
                                    names.setdefault(t.id, {"v": 1, "t": target})
                    return True
        return False

    # ---------------------------------------------------------------- functions
    def signature(self, info, fn, method, local=None):
        a = fn.args
        sig = {}
        pos = list(a.posonlyargs) + list(a.args)
        ndef = len(a.defaults)
        first_def = len(pos) - ndef
        sig["a"] = [p.arg + ("=" if i >= first_def else "") for i, p in enumerate(pos)]
        if a.posonlyargs:
            sig["po"] = len(a.posonlyargs)
        if a.kwonlyargs:
            sig["ko"] = [p.arg + ("=" if d is not None else "") for p, d in zip(a.kwonlyargs, a.kw_defaults)]
        if a.vararg:
            sig["va"] = a.vararg.arg
        if a.kwarg:
            sig["kw"] = a.kwarg.arg
        if fn.returns is not None:
            sig["r"] = ast.unparse(fn.returns)
            fn_local = dict(local or {})
            fn_local.update(local_imports(self, info, fn))
            rt = self.resolve_annotation(info, fn.returns, fn_local)
            if rt:
                sig["rt"] = rt
        return sig

    # ---------------------------------------------------------------- classes
    def class_record(self, info, node, qualname, outer_local=None):
        rec = {}
        local = dict(outer_local or {})
        bases, unres = [], []
        for b in node.bases:
            expr = b.value if isinstance(b, ast.Subscript) else b  # Generic[T], BaseModel[...]
            name = dotted(expr)
            target = self.resolve_name(info, name, local) if name else None
            if target:
                bases.append(target)
            else:
                unres.append(ast.unparse(b))
        if bases:
            rec["b"] = bases
        if unres:
            rec["ub"] = unres
        for kw in node.keywords:
            if kw.arg == "metaclass":
                m = dotted(kw.value)
                rec["meta"] = (self.resolve_name(info, m, local) if m else None) or ast.unparse(kw.value)
        for d in node.decorator_list:
            call = d.func if isinstance(d, ast.Call) else d
            dn = dotted(call)
            target = (self.resolve_name(info, dn, local) if dn else None) or dn or ""
            last = target.rsplit(".", 1)[-1]
            if last == "dataclass" or target in ("dataclasses.dataclass", "pydantic.dataclasses.dataclass"):
                rec["dc"] = "dataclass"
                if isinstance(d, ast.Call):
                    for kw in d.keywords:
                        if kw.arg == "kw_only" and isinstance(kw.value, ast.Constant) and kw.value.value:
                            rec["kwo"] = 1
            elif last == "configclass":
                rec["dc"] = "configclass"
        methods, cattrs, ann, atypes, iattrs, nested = {}, [], [], {}, set(), {}
        xa = set()
        evidence = {}   # attribute (private too) -> list of type evidence, see _attr_evidence
        overloads = {}
        kw_only = False
        body_local = dict(local)
        for st in node.body:
            if isinstance(st, ast.ClassDef):
                body_local[st.name] = qualname + "." + st.name
        for st in iter_class_body(node.body):
            if isinstance(st, (ast.FunctionDef, ast.AsyncFunctionDef)):
                decos = [dotted(d.func if isinstance(d, ast.Call) else d) or "" for d in st.decorator_list]
                if any(d.rsplit(".", 1)[-1] == "overload" for d in decos):
                    rt = self.resolve_annotation(info, st.returns, body_local) if st.returns is not None else None
                    overloads.setdefault(st.name, []).append(overload_record(st, rt))
                    continue
                if st.name in ("__getattr__", "__getattribute__"):
                    closed, extra = analyse_getattr(st) if st.name == "__getattr__" else (False, set())
                    if closed:
                        xa |= extra
                    else:
                        rec["open"] = st.name
                self._instance_attrs(st, iattrs, rec)
                self._attr_evidence(info, st, body_local, evidence)
                setter = [d for d in decos if d.endswith((".setter", ".deleter"))]
                if setter:
                    pname = setter[0].rsplit(".", 1)[0]
                    if pname in methods and methods[pname].get("k") == "p":
                        methods[pname]["set"] = 1
                    continue
                if is_private(st.name):
                    continue
                sig = self.signature(info, st, method=True, local=body_local)
                lasts = [d.rsplit(".", 1)[-1] for d in decos]
                if "staticmethod" in lasts:
                    sig["k"] = "s"
                elif "classmethod" in lasts:
                    sig["k"] = "c"
                elif any(x in ("property", "cached_property", "classproperty", "lazy_property",
                               "abstractproperty") for x in lasts):
                    sig["k"] = "p"
                    sig.pop("a", None)  # a property is read, not called
                    if "r" not in sig:
                        via = property_path(st)
                        if via:
                            sig["via"] = via
                methods[st.name] = sig
            elif isinstance(st, ast.ClassDef):
                if is_private(st.name) and st.name not in self.base_names:
                    continue
                nested[st.name] = self.class_record(info, st, qualname + "." + st.name, body_local)
            elif isinstance(st, ast.AnnAssign) and isinstance(st.target, ast.Name):
                name = st.target.id
                ann_txt = ast.unparse(st.annotation)
                if ann_txt in ("KW_ONLY", "dataclasses.KW_ONLY"):
                    kw_only = True
                    continue
                if is_private(name):
                    continue
                flags = []
                if st.value is not None:
                    flags.append("=")
                if ann_txt.startswith(("ClassVar", "typing.ClassVar")):
                    flags.append("cv")
                if isinstance(st.value, ast.Call) and (dotted(st.value.func) or "").rsplit(".", 1)[-1] in ("field", "Field"):
                    for kw in st.value.keywords:
                        if kw.arg == "init" and isinstance(kw.value, ast.Constant) and kw.value.value is False:
                            flags.append("ni")
                        if kw.arg == "kw_only" and isinstance(kw.value, ast.Constant) and kw.value.value is True:
                            flags.append("kw")
                        if kw.arg in ("alias", "validation_alias") and isinstance(kw.value, ast.Constant) \
                                and isinstance(kw.value.value, str):
                            flags.append("alias=" + kw.value.value)   # pydantic: the init keyword
                    if not any(kw.arg in ("default", "default_factory") for kw in st.value.keywords) \
                            and not st.value.args:
                        flags.remove("=")  # Field(ge=1): required
                if kw_only and "kw" not in flags:
                    flags.append("kw")
                ann.append([name] + flags)
                t = self.resolve_annotation(info, st.annotation, body_local)
                if t:
                    atypes[name] = t
            elif isinstance(st, ast.Assign):
                if any(isinstance(t, ast.Name) and t.id == "model_config" for t in st.targets) \
                        and isinstance(st.value, ast.Call):
                    for kw in st.value.keywords:
                        if kw.arg == "extra":
                            v = kw.value.value if isinstance(kw.value, ast.Constant) else dotted(kw.value)
                            rec["extra"] = str(v).rsplit(".", 1)[-1]
                for t in st.targets:
                    for e in ([t] if isinstance(t, ast.Name) else
                              [x for x in ast.walk(t) if isinstance(x, ast.Name)] if isinstance(t, (ast.Tuple, ast.List)) else []):
                        if e.id == "__slots__":
                            iattrs.update(x for x in (strings_of(st.value) or []) if not is_private(x))
                        elif not is_private(e.id) and e.id not in cattrs:
                            cattrs.append(e.id)
        for name, rts in overloads.items():
            if name in methods:
                methods[name]["ov"] = rts
        if methods:
            rec["m"] = methods
        if cattrs:
            rec["ca"] = cattrs
        if ann:
            rec["ann"] = ann
        if atypes:
            rec["at"] = atypes
        itypes = {}
        for name, ev in evidence.items():
            strong = {v for k, v in ev if k == "t"}
            calls = {v for k, v in ev if k == "c"}
            if len(strong) == 1 and None not in strong:
                itypes[name] = strong.pop()
            elif not strong and len(calls) == 1 and None not in calls \
                    and all(k == "c" for k, _ in ev):
                itypes[name] = calls.pop() + "()"   # made by calling it: see the docstring
        if itypes:
            rec["it"] = itypes
        iattrs -= set(methods) | set(cattrs) | {a[0] for a in ann}
        if iattrs:
            rec["ia"] = sorted(iattrs)
        if nested:
            rec["cls"] = nested
        if xa:
            rec["xa"] = sorted(xa)
        return rec

    def _attr_evidence(self, info, fn, body_local, evidence):
        """What `self.x = value` says about the type of x (private x too: properties
        return them). Evidence: ("t", T) from `self.x: T = ...` or from a parameter
        annotated T; ("c", callee) from `self.x = Callee(...)` (the checker uses it when the
        callee is an indexed class); ("?", None) for anything else. `= None` says nothing
        (the attribute is reset or not yet built)."""
        params = fn.args.posonlyargs + fn.args.args
        if not params:
            return
        first = params[0].arg
        local = dict(body_local)
        local.update(local_imports(self, info, fn))
        ann_params = {p.arg: p.annotation for p in params + fn.args.kwonlyargs if p.annotation is not None}
        for sub in ast.walk(fn):
            if isinstance(sub, ast.AnnAssign):
                pairs = [(sub.target, sub.value, sub.annotation)]
            elif isinstance(sub, ast.Assign):
                pairs = [(t, sub.value, None) for t in sub.targets]
            elif isinstance(sub, ast.AugAssign):
                pairs = [(sub.target, None, None)]
            else:
                continue
            for target, value, annotation in pairs:
                if isinstance(target, (ast.Tuple, ast.List)):
                    for e in target.elts:
                        if isinstance(e, ast.Attribute) and isinstance(e.value, ast.Name) and e.value.id == first:
                            evidence.setdefault(e.attr, []).append(("?", None))
                    continue
                if not (isinstance(target, ast.Attribute) and isinstance(target.value, ast.Name)
                        and target.value.id == first):
                    continue
                ev = evidence.setdefault(target.attr, [])
                if annotation is not None:
                    ev.append(("t", self.resolve_annotation(info, annotation, local)))
                elif isinstance(value, ast.Constant) and value.value is None:
                    pass
                elif isinstance(value, ast.Call) and dotted(value.func):
                    ev.append(("c", self.resolve_name(info, dotted(value.func), local)))
                elif isinstance(value, ast.Name) and value.id in ann_params:
                    ev.append(("t", self.resolve_annotation(info, ann_params[value.id], local)))
                else:
                    ev.append(("?", None))

    def _instance_attrs(self, fn, iattrs, rec):
        """Public attributes assigned through the method's first parameter (self.x = ...).

        `setattr(self, name, ...)` with a computed name or writes to self.__dict__ make the
        class open: its instances can have attributes we cannot list."""
        if not fn.args.args and not fn.args.posonlyargs:
            return
        first = (fn.args.posonlyargs + fn.args.args)[0].arg
        for sub in ast.walk(fn):
            targets = []
            if isinstance(sub, ast.Assign):
                targets = sub.targets
            elif isinstance(sub, (ast.AnnAssign, ast.AugAssign)):
                targets = [sub.target]
            elif isinstance(sub, (ast.For, ast.AsyncFor, ast.With)):
                targets = [sub.target] if isinstance(sub, (ast.For, ast.AsyncFor)) else \
                    [i.optional_vars for i in sub.items if i.optional_vars is not None]
            elif isinstance(sub, ast.NamedExpr):
                targets = []
            elif isinstance(sub, ast.Call):
                fname = dotted(sub.func)
                if fname in ("setattr", "object.__setattr__") and sub.args and dotted(sub.args[0]) == first:
                    if len(sub.args) > 1 and isinstance(sub.args[1], ast.Constant) and isinstance(sub.args[1].value, str):
                        if not is_private(sub.args[1].value):
                            iattrs.add(sub.args[1].value)
                    else:
                        rec["open"] = "setattr(%s, <computed name>, ...)" % first
                elif fname in (first + ".__dict__.update",):
                    rec["open"] = "%s.__dict__.update" % first
            for t in targets:
                for e in ast.walk(t):
                    if isinstance(e, ast.Attribute) and isinstance(e.value, ast.Name) and e.value.id == first \
                            and isinstance(e.ctx, ast.Store) and not is_private(e.attr):
                        iattrs.add(e.attr)
                    if isinstance(e, ast.Subscript) and dotted(e.value) == first + ".__dict__":
                        rec["open"] = "%s.__dict__[...] =" % first

    # ---------------------------------------------------------------- driver
    @staticmethod
    def choose_trees(info):
        """X.py and X.pyi both present: the .py is what runs, so it wins, unless it hands
        its names over to the stub (lazy_loader.attach_stub): then the stub lists them."""
        if ".py" not in info.kinds or ".pyi" not in info.kinds:
            return
        py = info.trees[info.kinds.index(".py")]
        pyi = info.trees[info.kinds.index(".pyi")]
        lazy = any(isinstance(n, ast.Attribute) and n.attr == "attach_stub" for n in ast.walk(py))
        info.trees, info.kinds = ([pyi], [".pyi"]) if lazy else ([py], [".py"])

    def run(self):
        self.discover()
        for info in self.modules.values():
            self.choose_trees(info)
        for info in self.modules.values():
            for tree in info.trees:
                for node in ast.walk(tree):
                    if isinstance(node, ast.ClassDef):
                        for b in node.bases:
                            expr = b.value if isinstance(b, ast.Subscript) else b
                            n = dotted(expr)
                            if n:
                                self.base_names.add(n.rsplit(".", 1)[-1])
        for info in self.modules.values():
            self.collect_scope(info)
        for info in self.modules.values():
            self.extract_module(info)
        return {name: self.modules[name].out for name in sorted(self.modules)}


BUILTIN_TYPES = {"object", "int", "float", "str", "bool", "bytes", "list", "dict", "tuple", "set",
                 "frozenset", "type", "Exception", "BaseException", "ValueError", "TypeError",
                 "RuntimeError", "KeyError", "AttributeError", "NotImplementedError", "property"}


def has_python(folder):
    for _dirpath, _dirnames, filenames in os.walk(folder):
        if any(f.endswith((".py", ".pyi")) for f in filenames):
            return True
    return False


def iter_class_body(body):
    """Class-body statements, looking into if/try blocks (conditional definitions)."""
    for st in body:
        if isinstance(st, ast.If):
            yield from iter_class_body(st.body)
            yield from iter_class_body(st.orelse)
        elif isinstance(st, ast.Try):
            for b in [st.body, st.orelse, st.finalbody] + [h.body for h in st.handlers]:
                yield from iter_class_body(b)
        else:
            yield st


def local_imports(ex, info, fn):
    """Names imported inside a function body (lazy imports), for its return annotation."""
    out = {}
    for sub in ast.walk(fn):
        if isinstance(sub, ast.ImportFrom):
            mod = ex.resolve_relative(info, sub.level, sub.module)
            for a in sub.names:
                if a.name != "*":
                    out[a.asname or a.name] = mod + "." + a.name
        elif isinstance(sub, ast.Import):
            for a in sub.names:
                out[a.asname or a.name.split(".")[0]] = a.name if a.asname else a.name.split(".")[0]
    return out


def overload_record(fn, rt):
    """One @overload variant: its return type and the parameters it requires to be None
    (`material: None = ...`), so the checker can pick the variant a call matches."""
    rec = {"rt": rt or "?"}
    params = fn.args.posonlyargs + fn.args.args
    rec["a"] = [p.arg for p in params]
    nones = [p.arg for p in params + fn.args.kwonlyargs
             if isinstance(p.annotation, ast.Constant) and p.annotation.value is None]
    if nones:
        rec["none"] = nones
    return rec


def is_this_module(node):
    """sys.modules[__name__] (or sys.modules["pkg.mod"]): the module being defined."""
    return isinstance(node, ast.Subscript) and dotted(node.value) == "sys.modules"


def property_path(fn):
    """`return self.a.b` as "a.b" (the property's type is that of the attribute path),
    when the body is only that return (and a docstring)."""
    body = [st for st in fn.body if not (isinstance(st, ast.Expr) and isinstance(st.value, ast.Constant))]
    params = fn.args.posonlyargs + fn.args.args
    if len(body) != 1 or not isinstance(body[0], ast.Return) or not params:
        return None
    name = dotted(body[0].value) if body[0].value is not None else None
    first = params[0].arg
    if not name or not name.startswith(first + "."):
        return None
    return name[len(first) + 1:]


def strings_of(node):
    """A list/tuple of string constants (possibly concatenated with +), else None."""
    if isinstance(node, (ast.List, ast.Tuple)):
        out = []
        for e in node.elts:
            if isinstance(e, ast.Constant) and isinstance(e.value, str):
                out.append(e.value)
            else:
                return None
        return out
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        a, b = strings_of(node.left), strings_of(node.right)
        if a is None or b is None:
            return None
        return a + b
    return None


def analyse_getattr(fn):
    """Is this `__getattr__` closed: does it only answer a fixed set of names?

    Closed when its last statement raises AttributeError and the name parameter is only
    compared (==, in) with other values: the names it answers are then among the string
    constants of its body. Anything else (getattr(self._wrapped, name), name.startswith,
    f-strings of the name ...) answers names we cannot list: open."""
    params = fn.args.posonlyargs + fn.args.args
    if not params:
        return False, set()
    pname = params[-1].arg
    if not fn.body:
        return False, set()
    last = fn.body[-1]
    if not isinstance(last, ast.Raise) or last.exc is None:
        return False, set()
    exc = last.exc.func if isinstance(last.exc, ast.Call) else last.exc
    if (dotted(exc) or "").rsplit(".", 1)[-1] != "AttributeError":
        return False, set()
    allowed = set()
    for sub in ast.walk(fn):
        if isinstance(sub, ast.Compare):
            for operand in [sub.left] + sub.comparators:
                if isinstance(operand, ast.Name) and operand.id == pname:
                    allowed.add(id(operand))
            if not all(isinstance(op, (ast.Eq, ast.In, ast.NotEq, ast.NotIn)) for op in sub.ops):
                return False, set()
        # the exception message may mention the name
        if isinstance(sub, ast.Raise) and sub.exc is not None:
            for n in ast.walk(sub.exc):
                if isinstance(n, ast.Name) and n.id == pname:
                    allowed.add(id(n))
    for sub in ast.walk(fn):
        if isinstance(sub, ast.Name) and sub.id == pname and isinstance(sub.ctx, ast.Load) and id(sub) not in allowed:
            return False, set()
    extra = {c.value for c in ast.walk(fn) if isinstance(c, ast.Constant) and isinstance(c.value, str)
             and c.value.isidentifier()}
    return True, extra


def main(argv=None):
    ap = argparse.ArgumentParser(description="Extract a package's public API (names and signatures) with ast.")
    ap.add_argument("--root", required=True, help="folder that contains the package folder(s)")
    ap.add_argument("--package", action="append", required=True, help="top-level package (repeatable)")
    ap.add_argument("--name", required=True, help="simulator name, e.g. Genesis")
    ap.add_argument("--version", required=True)
    ap.add_argument("--source-url", required=True)
    ap.add_argument("--commit", required=True, help="tag and/or commit sha the source was taken from")
    ap.add_argument("--tag", default=None)
    ap.add_argument("--out", required=True)
    ap.add_argument("--include-subpackage", action="append", default=[],
                    help="index only these subpackages (and the packages on the way to them)")
    ap.add_argument("--exclude-subpackage", action="append", default=[])
    ap.add_argument("--unchecked", action="append", default=[], metavar="MODULE=REASON",
                    help="a module whose names the checker must not check, with the reason")
    ap.add_argument("--date", default=None, help="extraction date (default: today, UTC)")
    ap.add_argument("--partial", action="store_true",
                    help="the source tree is a partial download: say so in the provenance")
    args = ap.parse_args(argv)

    ex = Extractor(args.root, args.package, args.include_subpackage, args.exclude_subpackage)
    modules = ex.run()
    unchecked = {}
    for item in args.unchecked:
        mod, sep, reason = item.partition("=")
        if not sep or not mod:
            ap.error("--unchecked wants MODULE=REASON, got %r" % item)
        unchecked[mod.strip()] = reason.strip()
    cmd = ["python3", sys.argv[0]] + (sys.argv[1:] if argv is None else list(argv))
    prov = {
        "simulator": args.name,
        "version": args.version,
        "source_url": args.source_url,
        "commit": args.commit,
        "extracted": args.date or datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
        "command": " ".join(shlex.quote(c) for c in cmd),
        "root_packages": args.package,
        "modules": len(modules),
    }
    if args.tag:
        prov["tag"] = args.tag
    if args.include_subpackage:
        prov["include_subpackages"] = args.include_subpackage
    if args.exclude_subpackage:
        prov["exclude_subpackages"] = args.exclude_subpackage
    if args.partial:
        prov["partial"] = True
    if ex.errors:
        prov["parse_errors"] = ex.errors
    index = {"format": FORMAT, "version": FORMAT_VERSION, "provenance": prov,
             "unchecked_modules": unchecked, "modules": modules}
    text = json.dumps(index, separators=(",", ":"), sort_keys=False, ensure_ascii=True)
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(text + "\n")
    print("extract_api: %d modules, %d bytes -> %s%s" % (
        len(modules), len(text), args.out,
        (" (%d files not parsable)" % len(ex.errors)) if ex.errors else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
