#!/usr/bin/python3
"""Checks that two `alphaflex study` CSVs hold the same rows in the same order, column by column,
except the time columns (cpu, cpu_per_step, wall by default), which measure the machine: a study
run with concurrent groups (mpirun -np N --ranks-per-run k) against the same study on one rank
(tests/study/CMakeLists.txt).

    compare_study_csv.py A.csv B.csv [--ignore cpu,cpu_per_step,wall] [--rtol 0]
                         [--run-a 'COMMAND'] [--run-b 'COMMAND'] [--also NAME_history.csv ...]

--run-a/--run-b: commands (shell words) that write A and B first; each must exit 0. --rtol 0
(default) asks for identical text: a one-rank group does the arithmetic of a one-rank job. With
k > 1 the factorization is distributed and results differ by round-off: give a relative tolerance.
--also: further files of the two studies, next to A and B (e.g. the time histories the charts are
drawn from, NAME_history.csv), compared the same way.
"""
import argparse
import csv
import math
import os
import shlex
import subprocess
import sys


def fail(msg):
    print("compare_study_csv.py: FAIL:", msg)
    sys.exit(1)


def rows(path):
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    return list(csv.DictReader(lines))


def compare(a, b, ignore, rtol):
    ra, rb = rows(a), rows(b)
    if not ra:
        fail(f"{a}: no rows")
    if len(ra) != len(rb):
        fail(f"{a} has {len(ra)} rows, {b} {len(rb)}")
    if list(ra[0].keys()) != list(rb[0].keys()):
        fail(f"columns differ: {list(ra[0].keys())} vs {list(rb[0].keys())}")
    compared = 0
    for i, (x, y) in enumerate(zip(ra, rb)):
        for c in x:
            if c in ignore or x[c] == y[c]:
                compared += 1
                continue
            try:
                u, v = float(x[c]), float(y[c])
            except ValueError:
                fail(f"row {i + 1} ({x['label']}, h {x['h']}), column {c}: '{x[c]}' vs '{y[c]}'")
            if not (math.isfinite(u) and math.isfinite(v)) or abs(u - v) > rtol * max(abs(u), abs(v)):
                fail(f"row {i + 1} ({x['label']}, h {x['h']}), column {c}: {x[c]} vs {y[c]} (rtol {rtol})")
            compared += 1
    print(f"compare_study_csv.py: {a} and {b}: {len(ra)} rows, {compared} fields agree (ignored: {', '.join(sorted(ignore))})")


p = argparse.ArgumentParser()
p.add_argument("a")
p.add_argument("b")
p.add_argument("--ignore", default="cpu,cpu_per_step,wall")
p.add_argument("--rtol", type=float, default=0.0)
p.add_argument("--run-a")
p.add_argument("--run-b")
p.add_argument("--timeout", type=float, default=600)
p.add_argument("--also", action="append", default=[])
args = p.parse_args()
for cmd in (args.run_a, args.run_b):
    if cmd:
        r = subprocess.run(shlex.split(cmd), timeout=args.timeout)
        if r.returncode != 0:
            fail(f"{cmd} exited {r.returncode}")
ignore = set(args.ignore.split(","))
compare(args.a, args.b, ignore, args.rtol)
for name in args.also:
    compare(os.path.join(os.path.dirname(args.a), name), os.path.join(os.path.dirname(args.b), name), ignore, args.rtol)
