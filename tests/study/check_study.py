#!/usr/bin/python3
"""Runs `alphaflex study` and checks what it wrote (tests/study/CMakeLists.txt).

    check_study.py --csv OUT/NAME_study.csv [--columns a,b,...] [--png NAME_x.png ...]
                   [--slope LABEL:ERROR:LO:HI ...] [--rows N] -- COMMAND...

COMMAND must exit 0 within --timeout seconds; then the CSV must have the columns, the rows, every
alphaflex row status ok, the least-squares slopes of log(err_ERROR) vs log(h) over the rows of
LABEL within [LO, HI], and each PNG must exist and start with the PNG signature.
"""
import argparse
import csv
import math
import os
import subprocess
import sys


def fail(msg):
    print("check_study.py: FAIL:", msg)
    sys.exit(1)


def slope(h, e):
    pts = [(math.log(a), math.log(b)) for a, b in zip(h, e) if b > 0 and math.isfinite(b)]
    n = len(pts)
    if n < 2:
        return float("nan")
    sx = sum(p[0] for p in pts)
    sy = sum(p[1] for p in pts)
    sxx = sum(p[0] ** 2 for p in pts)
    sxy = sum(p[0] * p[1] for p in pts)
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)


def main():
    argv = sys.argv[1:]
    if "--" not in argv:
        fail("no command after --")
    i = argv.index("--")
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", required=True)
    ap.add_argument("--columns", default="")
    ap.add_argument("--png", action="append", default=[])
    ap.add_argument("--slope", action="append", default=[])
    ap.add_argument("--rows", type=int, default=0)
    ap.add_argument("--timeout", type=float, default=120)
    a = ap.parse_args(argv[:i])
    cmd = argv[i + 1:]
    for p in [a.csv] + a.png:
        if os.path.exists(p):
            os.remove(p)
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=a.timeout)
    except subprocess.TimeoutExpired:
        fail("timed out after %g s: %s" % (a.timeout, " ".join(cmd)))
    sys.stdout.write(r.stdout)
    sys.stderr.write(r.stderr)
    if r.returncode != 0:
        fail("exit code %d" % r.returncode)
    with open(a.csv) as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    rows = list(csv.DictReader(lines))
    if a.rows and len(rows) != a.rows:
        fail("%d rows, expected %d" % (len(rows), a.rows))
    for c in [c for c in a.columns.split(",") if c]:
        if c not in rows[0]:
            fail("no column %s (columns: %s)" % (c, ",".join(rows[0].keys())))
    for row in rows:
        if row["method"] == "alphaflex" and row["status"] != "ok":
            fail("run %s h=%s failed: %s" % (row["label"], row["h"], row["failure"]))
    for s in a.slope:
        label, err, lo, hi = s.rsplit(":", 3)
        rs = [row for row in rows if row["label"] == label]
        if not rs:
            fail("no rows labelled %s" % label)
        k = slope([float(row["h"]) for row in rs], [float(row["err_" + err]) for row in rs])
        print("slope %s %s = %.3f (bounds [%s, %s])" % (label, err, k, lo, hi))
        if not (float(lo) <= k <= float(hi)):
            fail("slope of %s for %s is %.3f, outside [%s, %s]" % (err, label, k, lo, hi))
    for p in a.png:
        if not os.path.exists(p) or os.path.getsize(p) < 1000:
            fail("no chart %s" % p)
        with open(p, "rb") as fh:
            if fh.read(8) != b"\x89PNG\r\n\x1a\n":
                fail("%s is not a PNG" % p)
    print("check_study.py: ok")


if __name__ == "__main__":
    main()
