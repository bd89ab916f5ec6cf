#!/usr/bin/python3
"""SciPy's Radau IIA (order 5, Hairer & Wanner) on Andrews' squeezing mechanism: a peer on the
work-precision chart of `alphaflex study` (docs/study.md).

    /usr/bin/python3 scripts/study_radau_andrews.py --tolerances 1e-4,1e-6,1e-8 [--t-end 0.03] --out radau.csv

The formulation is the one of scripts/reference/andrews_reference.py, imported from it (the test
set's 7 relative coordinates, reduced to index 1: every right-hand side solves
[[M, G^T], [G, 0]] [q''; lambda] = [f; gamma]); the first-order system in (q, q') goes to
scipy.integrate.solve_ivp(method='Radau', rtol=tol, atol=tol) in one call, with its
finite-difference Jacobian and dense LU, as the solver is used out of the box. lambda at t_end is
the index-1 multiplier of the final state.

CPU time is time.process_time() around solve_ivp (the interpreter start and the imports are not
counted), like the process CPU time alphaflex measures around its own runs.
Writes one CSV row per tolerance: method,rtol,atol,ok,cpu,steps,nfev,njev,nlu,message and the
values at t_end named like the sensors of inputs/andrews.yaml (beta..epsilon in rad, lambda1..6 in N).
"""
import argparse
import os
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference"))
import andrews_reference as ar  # noqa: E402  (the formulation, not duplicated here)

NAMES = ar.NAMES + ["lambda%d" % i for i in range(1, 7)]


def solve(tol, t_end):
    y0 = np.concatenate([ar.Q0, np.zeros(7)])
    c0 = time.process_time()
    r = solve_ivp(ar.rhs, (0.0, t_end), y0, method="Radau", rtol=tol, atol=tol)
    cpu = time.process_time() - c0
    y = r.y[:, -1]
    values = np.concatenate([y[:7], ar.accel(y)[1]])
    return r, cpu, values


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tolerances", required=True, help="comma-separated rtol = atol values")
    ap.add_argument("--t-end", type=float, default=0.03)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    try:
        tols = [float(t) for t in a.tolerances.split(",") if t.strip()]
    except ValueError:
        sys.exit("study_radau_andrews.py: --tolerances: expected numbers, got '%s'" % a.tolerances)
    if not tols or any(not (t > 0) for t in tols):
        sys.exit("study_radau_andrews.py: --tolerances: expected positive numbers")
    rows = []
    for tol in tols:
        r, cpu, values = solve(tol, a.t_end)
        ok = bool(r.success) and abs(r.t[-1] - a.t_end) <= 1e-12 * max(1.0, a.t_end)
        msg = str(r.message).replace(",", ";").replace("\n", " ")
        rows.append(["SciPy Radau (index 1)", repr(tol), repr(tol), "1" if ok else "0", "%.6g" % cpu,
                     str(len(r.t) - 1), str(r.nfev), str(r.njev), str(r.nlu), msg]
                    + ["%.17g" % v for v in values])
        print("Radau tol %.0e: %s, CPU %.3f s, %d steps, %d f-evaluations" % (tol, "ok" if ok else "FAILED",
                                                                           cpu, len(r.t) - 1, r.nfev))
    with open(a.out, "w") as fh:
        fh.write(",".join(["method", "rtol", "atol", "ok", "cpu", "steps", "nfev", "njev", "nlu", "message"]
                          + NAMES) + "\n")
        for row in rows:
            fh.write(",".join(row) + "\n")


if __name__ == "__main__":
    main()
