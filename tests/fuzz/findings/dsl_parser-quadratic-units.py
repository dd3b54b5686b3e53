#!/usr/bin/env python3
# Reproducer for dsl_parser-quadratic-units.md: a .efc file with N parts,
# each with a revolute joint whose range carries a unit (or none).
#   python3 tests/fuzz/findings/dsl_parser-quadratic-units.py 8000 > /tmp/u.efc
#   python3 tests/fuzz/findings/dsl_parser-quadratic-units.py 8000 "" > /tmp/n.efc
#   time build/efc check /tmp/u.efc; time build/efc check /tmp/n.efc
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 8000
unit = sys.argv[2] if len(sys.argv) > 2 else " deg"
print("efc 1\nobject many {\n  part base: base { box { size (1, 1, 1) } }")
for i in range(n):
    print(f"  part p{i}: other {{ sphere {{ radius 0.01 }}; "
          f"joint revolute on base {{ range 0 .. 90{unit} }} }}")
print("}")
