#!/usr/bin/python3
"""Checks the load axis of a `fidelity` study (study.load, docs/study.md "Over a load axis") from
its CSV: the printed change point of the lightest acceptable rung, the slope of log(error) against
log(load scale) of one rung over the small loads, and optionally its error per unit scale at the
smallest scale, and that another run of the same study (e.g. under mpirun -np 2) has the same rows
and the same change points.

    check_load_ladder.py CSV [--change 'FROM:TO:S1:S2'] [--rung LABEL] [--below S] [--slope LO:HI]
                         [--coefficient C:LO:HI] [--same-as OTHER.csv] [--png FILE ...] [-- COMMAND ...]

COMMAND (if given) runs first and must exit 0 (it writes CSV). --change: the only change point is
from rung FROM to rung TO between load scales S1 and S2. --slope: the least-squares slope of
log(err_max) vs log(load_scale) of rung --rung over the scales <= --below lies in [LO, HI].
--coefficient: err_max / (C * load_scale) of that rung at the smallest scale lies in [LO, HI].
--same-as: the rows equal OTHER's (all columns but the CPU-time ones and `recommended`, which
follows the CPU times) and so do the `# load axis:` lines.
"""
import argparse
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import alphaflex_results as ar  # noqa: E402

TIME_COLUMNS = {"cpu", "cpu_per_step", "wall", "cpu_ratio", "recommended"}


def fail(msg):
    print("check_load_ladder.py: FAIL:", msg)
    sys.exit(1)


argv = sys.argv[1:]
command = []
if "--" in argv:
    command = argv[argv.index("--") + 1:]
    argv = argv[:argv.index("--")]
p = argparse.ArgumentParser()
p.add_argument("csv")
p.add_argument("--change")
p.add_argument("--rung", default="2 modes")
p.add_argument("--below", type=float, default=math.inf)
p.add_argument("--slope")
p.add_argument("--coefficient")
p.add_argument("--same-as")
p.add_argument("--png", action="append", default=[], help="a chart that must exist and be non-empty")
a = p.parse_args(argv)

if command:
    r = subprocess.run(command)
    if r.returncode != 0:
        fail(f"{' '.join(command)} exited with {r.returncode}")
study = ar.load_study(a.csv)
rows, changes = study.rows, [c[len("load axis: "):] for c in study.comments if c.startswith("load axis: lightest")]
if not rows or "load_scale" not in rows[0]:
    fail(f"{a.csv}: no rows with a load_scale column")
print("check_load_ladder.py:", "; ".join(changes))

if a.change:
    frm, to, s1, s2 = a.change.split(":")
    want = f"lightest acceptable variant changes from `{frm}` to `{to}` between load scale {s1} and {s2}"
    if changes != [want]:
        fail(f"expected the one change point '{want}', the CSV says {changes}")

pts = sorted((float(r["load_scale"]), float(r["err_max"])) for r in rows
             if r["label"] == a.rung and r["status"] == "ok" and r["err_max"])
if a.slope or a.coefficient:
    if not pts:
        fail(f"no measured rows of rung '{a.rung}'")
    for s, e in pts:
        print(f"  {a.rung}: load scale {s:g}: err_max {e:.4g}")
if a.slope:
    lo, hi = (float(x) for x in a.slope.split(":"))
    small = [(math.log(s), math.log(e)) for s, e in pts if s <= a.below and e > 0]
    if len(small) < 2:
        fail(f"fewer than 2 points of rung '{a.rung}' at load scales <= {a.below:g}")
    mx = sum(x for x, _ in small) / len(small)
    my = sum(y for _, y in small) / len(small)
    k = sum((x - mx) * (y - my) for x, y in small) / sum((x - mx) ** 2 for x, _ in small)
    print(f"  slope of log err_max vs log load_scale ({len(small)} scales <= {a.below:g}): {k:.4f}")
    if not lo <= k <= hi:
        fail(f"slope {k:.4f} outside [{lo}, {hi}]")
if a.coefficient:
    c, lo, hi = (float(x) for x in a.coefficient.split(":"))
    s, e = pts[0]
    ratio = e / (c * s)
    print(f"  err_max / ({c:g} * scale) at scale {s:g}: {ratio:.4f}")
    if not lo <= ratio <= hi:
        fail(f"err_max / ({c:g} * scale) = {ratio:.4f} at scale {s:g}, outside [{lo}, {hi}]")
if a.same_as:
    other = ar.load_study(a.same_as)
    if len(other.rows) != len(rows):
        fail(f"{a.same_as} has {len(other.rows)} rows, {a.csv} {len(rows)}")
    for i, (x, y) in enumerate(zip(rows, other.rows)):
        if list(x) != list(y):
            fail(f"columns differ: {list(x)} vs {list(y)}")
        for c in x:
            if c not in TIME_COLUMNS and x[c] != y[c]:
                fail(f"row {i + 1} ({x['label']}, load scale {x['load_scale']}), column {c}: '{x[c]}' vs '{y[c]}'")
    theirs = [c[len("load axis: "):] for c in other.comments if c.startswith("load axis: lightest")]
    if theirs != changes:
        fail(f"change points differ: {changes} vs {theirs} in {a.same_as}")
    print(f"  {len(rows)} rows and the change points agree with {a.same_as}")
for png in a.png:
    if not os.path.isfile(png) or os.path.getsize(png) == 0:
        fail(f"no chart {png}")
print("check_load_ladder.py: ok")
