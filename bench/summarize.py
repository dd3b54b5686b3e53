#!/usr/bin/env python3
"""Summary table of bench/run: reads the JSON (--benchmark_format=json) of
compile_bench and play_bench and prints, per spec, the median check, compile
and MuJoCo load times with the compile/load ratio, and the steps per second
raw vs with templates with the template overhead. Standard library only.

usage: summarize.py [--wall] COMPILE_JSON PLAY_JSON [FIRST_CALL_JSON]

Compile times are CPU time (user + system) of the benchmark process, which
other processes on the machine disturb less than wall time; --wall uses wall
time instead. "(in memory)" is generate_mujoco: the same compile with its
files made in memory and not written (efc's own work); "(writing files)" is
write_files: writing those files into an empty folder. FIRST_CALL_JSON (first_call_bench --json) adds
the first call in a fresh process: one compile against one MuJoCo load, each
the first of its process.
"""
import json
import re
import sys

TEMPLATE_TARGET_PCT = 3.0  # template evaluation, objects without particles
WELL_UNDER = 0.5           # compile "well under" MuJoCo's own load: at most half of it


def read(path):
    """{(kind, spec): {'median': entry, ...} or {'error': message}}"""
    with open(path) as f:
        data = json.load(f)
    out = {}
    for b in data.get("benchmarks", []):
        run = re.sub(r"/(min_time|repeats|iterations):[^/]*", "", b.get("run_name", b["name"]))
        kind, _, spec = run.partition("/")
        slot = out.setdefault((kind, spec), {})
        if b.get("error_occurred"):
            slot.setdefault("error", b.get("error_message", "error").strip().splitlines()[0])
        elif b.get("run_type") == "aggregate":
            slot[b["aggregate_name"]] = b
        else:  # a single run (e.g. --benchmark_repetitions=1)
            slot.setdefault("median", b)
    return data.get("context", {}), out


TIME_FIELD = "cpu_time"


def ms(entry):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[entry.get("time_unit", "ns")]
    return entry[TIME_FIELD] * scale


def cell(slot, fmt):
    if slot is None:
        return "-"
    if "error" in slot:
        return "ERROR"
    return fmt(slot["median"])


def specs_in(results, kinds):
    seen = []
    for kind, spec in results:
        if kind in kinds and spec not in seen:
            seen.append(spec)
    # examples alphabetically, generated specs (large_*) last
    return sorted(seen, key=lambda s: (s.startswith("large_"), s))


def table(header, rows):
    widths = [max(len(str(r[i])) for r in [header] + rows) for i in range(len(header))]
    line = lambda r: "  ".join(str(c).ljust(w) if i == 0 else str(c).rjust(w)
                               for i, (c, w) in enumerate(zip(r, widths)))
    print(line(header))
    print("  ".join("-" * w for w in widths))
    for r in rows:
        print(line(r))


def repetitions(results):
    """'median of N repetitions' as the JSON says (1 for a single run)."""
    for slot in results.values():
        entry = slot.get("median")
        if entry:
            n = int(entry.get("repetitions", 1) or 1)
            return "median of %d repetitions" % n if n > 1 else "a single run"
    return "no runs"


def verdict(what, ratios, target):
    """One line: worst and median of (ratio, spec) pairs against the target."""
    worst = max(ratios)
    large = [r for r, s in ratios if s.startswith("large_")]
    print("%s: worst %.2f (%s), median %.2f%s; target < %.1f: %s" % (
        what, worst[0], worst[1], sorted(r for r, _ in ratios)[len(ratios) // 2],
        ", 200-part spec %.3f" % large[0] if large else "", target,
        "met" if worst[0] < target else "NOT met"))


def first_call(path):
    """The first_call_bench table: each figure the first call of a new process."""
    with open(path) as f:
        data = json.load(f)
    key = "wall_ms" if TIME_FIELD == "real_time" else "cpu_ms"
    print()
    print("First call in a fresh process (%s time, median of %d processes, ms): what one `efc"
          " compile` and one program loading the result each pay" % (
              "wall" if key == "wall_ms" else "CPU", data.get("runs", 0)))
    rows, ratios = [], []
    for e in sorted(data.get("specs", []), key=lambda e: (e["spec"].startswith("large_"), e["spec"])):
        c, l = e["compile_" + key], e["load_" + key]
        ratios.append((c / l, e["spec"]))
        rows.append([e["spec"], "%d" % e["parts"], "%.3f" % c, "%.3f" % l, "%.2f" % (c / l)])
    table(["spec", "parts", "compile", "mujoco load", "ratio"], rows)
    if ratios:
        verdict("first call: compile / MuJoCo load", ratios, WELL_UNDER)


def main(argv):
    global TIME_FIELD
    if "--wall" in argv:
        argv = [a for a in argv if a != "--wall"]
        TIME_FIELD = "real_time"
    if len(argv) not in (3, 4):
        print(__doc__, file=sys.stderr)
        return 2
    ctx, comp = read(argv[1])
    _, play = read(argv[2])
    errors = []
    unstable = []  # MuJoCo warned (an unstable simulation is reset): figures not meaningful

    print("efc benchmarks: %s, %s CPUs, load average %s" % (
        ctx.get("host_name", "?"), ctx.get("num_cpus", "?"),
        " ".join("%.1f" % x for x in ctx.get("load_avg", [])) or "?"))
    print()
    print("Compile (%s time, %s, ms; ratio = compile / MuJoCo load)" % (
        "wall" if TIME_FIELD == "real_time" else "CPU", repetitions(comp)))
    rows, ratios, mem_ratios = [], [], []
    for spec in specs_in(comp, {"check", "compile_mujoco", "generate_mujoco", "mujoco_load"}):
        g = {k: comp.get((k, spec))
             for k in ("check", "compile_mujoco", "generate_mujoco", "write_files", "mujoco_load")}
        for k, slot in g.items():
            if slot and "error" in slot:
                errors.append("%s/%s: %s" % (k, spec, slot["error"]))
        ratio = mem_ratio = "-"
        c, m, l = g["compile_mujoco"], g["generate_mujoco"], g["mujoco_load"]
        if l and "median" in l:
            if c and "median" in c:
                r = ms(c["median"]) / ms(l["median"])
                ratios.append((r, spec))
                ratio = "%.2f" % r
            if m and "median" in m:
                r = ms(m["median"]) / ms(l["median"])
                mem_ratios.append((r, spec))
                mem_ratio = "%.2f" % r
        parts = "-"
        for slot in g.values():
            if slot and "median" in slot and "parts" in slot["median"]:
                parts = "%d" % slot["median"]["parts"]
                break
        f = lambda e: "%.3f" % ms(e)
        rows.append([spec, parts, cell(g["check"], f), cell(g["compile_mujoco"], f),
                     cell(g["generate_mujoco"], f), cell(g["write_files"], f),
                     cell(g["mujoco_load"], f), ratio, mem_ratio])
    table(["spec", "parts", "check", "compile", "(in memory)", "(writing files)", "mujoco load",
           "ratio", "ratio in memory"], rows)
    if mem_ratios:
        verdict("efc's own work (in memory) / MuJoCo load", mem_ratios, WELL_UNDER)
    if ratios:
        verdict("compile with its files written / MuJoCo load", ratios, WELL_UNDER)
    if len(argv) == 4:
        first_call(argv[3])
    print()
    print("Other targets: load_spec + emit (ms, median)")
    other = []
    for spec in specs_in(comp, {"compile_urdf", "compile_bullet"}):
        u, b = comp.get(("compile_urdf", spec)), comp.get(("compile_bullet", spec))
        f = lambda e: "%.3f" % ms(e)
        other.append([spec, cell(u, f), cell(b, f)])
    table(["spec", "urdf", "bullet"], other)

    targets = sorted({k[len("emit_"):] for k, _ in comp if k.startswith("emit_")},
                     key=lambda t: (["mujoco", "urdf", "bullet"].index(t) if t in ("mujoco", "urdf", "bullet") else 9, t))
    if targets:
        print()
        print("Emission per target: Backend::generate of the loaded object, in memory (ms, median)")
        rows = []
        kinds = {"emit_" + t for t in targets}
        for spec in specs_in(comp, kinds):
            f = lambda e: "%.3f" % ms(e)
            rows.append([spec] + [cell(comp.get(("emit_" + t, spec)), f) for t in targets])
        table(["spec"] + targets, rows)

    for group, title, target in (
            ("play", "Playback without particles", True),
            ("play_fluid", "Playback with particles (fluid effects; informational)", False)):
        specs = specs_in(play, {group})
        if not specs:
            continue
        print()
        print(title + " (%s; steps/s of mj_step alone vs the harness step:" % repetitions(play))
        print("  recorded inputs + Controller::step + mj_step; overhead = end to end; template % ="
              " templates timed in the loop / raw)")
        rows, worst, worst_e2e = [], None, None
        for spec in specs:
            slot = play[(group, spec)]
            if "error" in slot:
                errors.append("%s/%s: %s" % (group, spec, slot["error"]))
                rows.append([spec, "-", "ERROR", "ERROR", "-", "-", "-", "-"])
                continue
            e = slot["median"]
            pct = e["template_pct"]
            if worst is None or pct > worst[0]:
                worst = (pct, spec)
            if worst_e2e is None or e["overhead_pct"] > worst_e2e[0]:
                worst_e2e = (e["overhead_pct"], spec)
            warn = int(e.get("warnings", 0))
            if warn:
                unstable.append("%s/%s" % (group, spec))
            rows.append([spec, "%d" % e.get("functions", 0), "%.0f" % e["raw_steps_per_s"],
                         "%.0f" % e["tmpl_steps_per_s"], "%+.2f" % e["overhead_pct"],
                         "%.2f" % pct, "%.0f" % e["template_ns"], "%d" % warn if warn else ""])
        table(["spec", "functions", "raw steps/s", "templ steps/s", "overhead %", "template %",
               "template ns", "mj warnings"], rows)
        if worst and target:
            print("template cost per step: worst %.2f%% end to end (%s), worst %.2f%% timed in the"
                  " loop (%s); target < %.0f%% (end to end): %s" % (
                      worst_e2e[0], worst_e2e[1], worst[0], worst[1], TEMPLATE_TARGET_PCT,
                      "met" if worst_e2e[0] < TEMPLATE_TARGET_PCT else "NOT met"))

    if unstable:
        print()
        print("MuJoCo warned during playback (e.g. an unstable simulation was reset; see play.log): " +
              ", ".join(unstable) + "; their steps/s are not meaningful")
    if errors:
        print()
        print("Errors (%d):" % len(errors))
        for e in errors:
            print("  " + e)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
