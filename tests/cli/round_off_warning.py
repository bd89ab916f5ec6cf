#!/usr/bin/python3
"""The round-off warning per reaction (issue 22; integrators/round_off_floor.hpp, docs/performance.md
"The round-off warning per reaction"), through the real executable on --np ranks, on the beam spin-up:

  1. t_end = 0.1 s, h = 1e-4 s: the hub's estimate is 1.1e-4 of its own torque (measured noise
     9e-6): no warning about reactions; the accelerations' warning (0.237 % of |q̈|) stays;
  2. t_end = 0.1 s, h = 2e-5 s: the hub's estimate is 0.23 % of its torque (Λ = 3.65e-3 N·m,
     m = 0.4, b = 2.8e7, ‖q‖ = 10 m): a warning naming joint 'hub' and h >= 3.04e-05 s, where
     ε‖q‖(β'm + b) = 1e-3 Λ (round_off_floor.hpp; within 1 %: m, b and Λ are rounded here);
  3. t_end = 0.01 s, h = 5e-6 s: the torque is still small (1.5e-6 N·m) and ε‖q‖b = 6.2e-8 alone
     exceeds 0.1 % of it: the warning says that no step size helps;
  4. on 2 ranks, the warnings are those of 1 rank, word for word.
"""
import json
import os
import re
import subprocess
import sys

from run_options import parser, prepare


def main():
    ap = parser(__doc__)
    a = ap.parse_args()
    name = prepare(a)

    def warnings(tag, np, *sets):
        out = os.path.join(a.out, tag)
        launcher = [a.mpirun, "--oversubscribe", "-np", str(np)] if np > 1 else []
        cmd = launcher + [a.exe, "run", a.scene, "-o", out, "--set", "output.hdf5=off",
                          "--set", "output.checkpoint_at_end=off"]
        for s in sets:
            cmd += ["--set", s]
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        if p.returncode != 0:
            sys.exit(f"{tag}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
        with open(os.path.join(out, name + ".summary.json")) as fh:
            return [w for w in json.load(fh)["warnings"] if "round-off" in w]

    slow = ("solver.t_end=0.1", "solver.h=1e-4")
    fine = ("solver.t_end=0.1", "solver.h=2e-5")
    early = ("solver.t_end=0.01", "solver.h=5e-6")
    w1 = warnings("slow", a.np, *slow)
    if any("reactions of joint" in w for w in w1):
        sys.exit(f"1: a reaction warning at h = 1e-4 (estimate 1.1e-4 of the hub torque): {w1}")
    if not any("the accelerations may carry" in w for w in w1):
        sys.exit(f"1: the accelerations' warning is missing: {w1}")
    w2 = warnings("fine", a.np, *fine)
    hub = [w for w in w2 if "reactions of joint 'hub'" in w]
    h_ok = [float(x) for x in re.findall(r"use h >= (\S+) s", hub[0])] if len(hub) == 1 else []
    if len(h_ok) != 1 or abs(h_ok[0] - 3.04e-5) > 0.01 * 3.04e-5:
        sys.exit(f"2: expected one warning naming joint 'hub' with h >= 3.04e-05 s: {w2}")
    w3 = warnings("early", a.np, *early)
    if not any("reactions of joint 'hub'" in w and "No step size" in w for w in w3):
        sys.exit(f"3: expected the hub's warning saying no step size helps: {w3}")
    if a.np > 1:
        for tag, sets, got in (("slow1", slow, w1), ("fine1", fine, w2), ("early1", early, w3)):
            one = warnings(tag, 1, *sets)
            if one != got:
                sys.exit(f"4: {a.np} ranks warn {got}, 1 rank {one}")
    print("round-off warnings as expected:", w1 + w2 + w3)


if __name__ == "__main__":
    main()
