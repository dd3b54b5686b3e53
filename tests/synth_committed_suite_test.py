#!/usr/bin/env python3
"""The committed synthetic suite (tests/data/synth-suite) is usable: every
sequence passes `efc check-sequence`, its spec passes `efc check`, and its
truth (joints.csv, effects.csv) is what `efc play` logs when it follows the
sequence's receptor schedule (truth/profile.csv), number for number.

Usage: synth_committed_suite_test.py EFC SOURCE_DIR
"""
import csv
import json
import pathlib
import subprocess
import sys
import tempfile


def run(efc, *args):
    return subprocess.run([efc, *args], capture_output=True, text=True)


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    efc, root = sys.argv[1], pathlib.Path(sys.argv[2])
    suite = root / "tests" / "data" / "synth-suite"
    index = json.loads((suite / "index.json").read_text())
    problems, compared = [], 0
    for entry in index["sequences"]:
        seq = suite / entry["sequence"]
        spec = suite / entry["spec"]
        for args in (["check-sequence", str(seq)], ["check", str(spec)]):
            r = run(efc, *args)
            if r.returncode != 0:
                problems.append(f"{' '.join(args)}: exit {r.returncode}: {r.stderr}")
        timeline = json.loads((seq / "truth" / "timeline.json").read_text())
        with tempfile.TemporaryDirectory() as tmp:
            log = pathlib.Path(tmp) / "play.csv"
            r = run(efc, "play", str(spec), "--profile", f"csv:{seq / 'truth' / 'profile.csv'}",
                    "--duration", repr(timeline["duration"]), "--dt", repr(timeline["dt"]), "--csv", str(log))
            if r.returncode != 0:
                problems.append(f"play {spec}: exit {r.returncode}: {r.stderr}")
                continue
            play = rows(log)
        effects = rows(seq / "truth" / "effects.csv")
        fps = json.loads((seq / "meta.json").read_text())["fps"]
        for frame, truth in enumerate(effects):
            row = play[round(frame / fps / timeline["dt"])]
            for column, value in truth.items():
                if column == "t":
                    continue
                compared += 1
                if row[column] != value:
                    problems.append(f"{entry['name']} frame {frame} {column}: play {row[column]}, truth {value}")
    for p in problems[:20]:
        print(p)
    print(f"synth_committed_suite: {len(index['sequences'])} sequences, {compared} values compared, "
          f"{len(problems)} problems")
    return 1 if problems or compared == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
