#!/usr/bin/env python3
"""Summary table of bench/run: reads the JSON (--benchmark_format=json) of
compile_bench and play_bench and prints, per spec, the median check, compile
and MuJoCo load times with the compile/load ratio, and the steps per second
raw vs with templates with the template overhead. Standard library only.

usage: summarize.py [--wall] COMPILE_JSON PLAY_JSON

Compile times are CPU time (user + system) of the benchmark process, which
other processes on the machine disturb less than wall time; --wall uses wall
time instead. "(writing files)" is write_files: writing the same output files
from memory into an empty folder; "ratio w/o writing" is (compile - that) /
MuJoCo load, efc's own work.
"""
import json
import re
import sys

TEMPLATE_TARGET_PCT = 3.0  # template evaluation, objects without particles
RATIO_TARGET = 1.0         # compile must be (well) under MuJoCo's own load


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


def main(argv):
    global TIME_FIELD
    if "--wall" in argv:
        argv = [a for a in argv if a != "--wall"]
        TIME_FIELD = "real_time"
    if len(argv) != 3:
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
    print("Compile (%s time, median of 5 repetitions, ms; ratio = compile / MuJoCo load)" % (
        "wall" if TIME_FIELD == "real_time" else "CPU"))
    rows, ratios, own_ratios = [], [], []
    for spec in specs_in(comp, {"check", "compile_mujoco", "compile_mjcf", "mujoco_load"}):
        g = {k: comp.get((k, spec))
             for k in ("check", "compile_mujoco", "compile_mjcf", "write_files", "mujoco_load")}
        for k, slot in g.items():
            if slot and "error" in slot:
                errors.append("%s/%s: %s" % (k, spec, slot["error"]))
        ratio = own_ratio = writing = "-"
        c, l = g["compile_mujoco"], g["mujoco_load"]
        if c and l and "median" in c and "median" in l:
            r = ms(c["median"]) / ms(l["median"])
            ratios.append((r, spec))
            ratio = "%.2f" % r
            w = g["write_files"]
            if w and "median" in w:
                writing = "%.3f" % ms(w["median"])
                own = max(0.0, ms(c["median"]) - ms(w["median"])) / ms(l["median"])
                own_ratios.append((own, spec))
                own_ratio = "%.2f" % own
        parts = "-"
        for slot in g.values():
            if slot and "median" in slot and "parts" in slot["median"]:
                parts = "%d" % slot["median"]["parts"]
                break
        f = lambda e: "%.3f" % ms(e)
        rows.append([spec, parts, cell(g["check"], f), cell(g["compile_mujoco"], f), writing,
                     cell(g["compile_mjcf"], f), cell(g["mujoco_load"], f), ratio, own_ratio])
    table(["spec", "parts", "check", "compile", "(writing files)", "(mjcf only)", "mujoco load",
           "ratio", "ratio w/o writing"], rows)
    if ratios:
        worst = max(ratios)
        large = [r for r, s in ratios if s.startswith("large_")]
        print("compile/load ratio: worst %.2f (%s), median %.2f%s; target < %.1f: %s" % (
            worst[0], worst[1], sorted(r for r, _ in ratios)[len(ratios) // 2],
            ", 200-part spec %.3f" % large[0] if large else "", RATIO_TARGET,
            "met" if worst[0] < RATIO_TARGET else "NOT met"))
    if own_ratios:
        worst = max(own_ratios)
        print("without writing the files (compile - writing the same files from memory, over"
              " MuJoCo load): worst %.2f (%s), median %.2f" % (
                  worst[0], worst[1], sorted(r for r, _ in own_ratios)[len(own_ratios) // 2]))
    print()
    print("Other targets: load_spec + emit (ms, median)")
    other = []
    for spec in specs_in(comp, {"compile_urdf", "compile_bullet"}):
        u, b = comp.get(("compile_urdf", spec)), comp.get(("compile_bullet", spec))
        f = lambda e: "%.3f" % ms(e)
        other.append([spec, cell(u, f), cell(b, f)])
    table(["spec", "urdf", "bullet"], other)

    for group, title, target in (
            ("play", "Playback without particles", True),
            ("play_fluid", "Playback with particles (fluid effects; informational)", False)):
        specs = specs_in(play, {group})
        if not specs:
            continue
        print()
        print(title + " (median of 5; steps/s of mj_step alone vs the harness step:")
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
