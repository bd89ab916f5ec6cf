#!/usr/bin/python3
"""Work-precision of adaptive against fixed steps (issue 17), one scene, in one run.

For each tolerance (solver.tolerance.rtol = atol = tol) and each fixed h, runs `alphaflex run`
and reads: the relative error of one sensor at t_end against a reference CSV (its last row),
accepted and rejected steps, Newton iterations, and the run's own wall time from its summary
(setup, integration and output; process start not counted). Prints a table, the least-squares
slope of log error against log tol (tolerance proportionality: 1) and, for a target error, the
steps and time of each policy interpolated in log-log.

Example (Andrews, 1e-4 in beta):
  /usr/bin/python3 scripts/adaptive_work_precision.py --exe build/alphaflex --scene inputs/andrews.yaml \
      --reference tests/reference/andrews.csv --sensor beta --target 1e-4 \
      --tol 1e-3 3e-4 1e-4 3e-5 1e-5 1e-6 --h 1.2e-4 8e-5 5.6e-5 4e-5 2.8e-5 2e-5
"""
import argparse, csv, math, os, re, subprocess, sys, tempfile

def run(exe, scene, sets, outdir, repeat):
    best = None
    for _ in range(repeat):
        cmd = [exe, "run", scene, "-o", outdir, "--set", "output.hdf5=off"]
        for s in sets: cmd += ["--set", s]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            sys.exit("failed: " + " ".join(cmd) + "\n" + p.stdout + p.stderr)
        wall = float(re.search(r"wall time\s+([0-9.]+) s", p.stdout).group(1))
        best = wall if best is None else min(best, wall)
    m = re.search(r"steps\s+(\d+)( accepted, (\d+) rejected, (\d+) Newton failures)?", p.stdout)
    newton = int(re.search(r"Newton iterations\s+total (\d+)", p.stdout).group(1))
    name = re.search(r"sensors\s+(\S+\.csv)", p.stdout).group(1)
    with open(name) as f:
        rows = list(csv.reader(f))
    return dict(steps=int(m.group(1)), rejected=int(m.group(3) or 0), newton=newton, wall=best,
                header=rows[0], last=[float(x) for x in rows[-1]])

def interp(xs, ys, target):
    """log-log interpolation of y at x = target over the points (x decreasing in y)."""
    pts = sorted(zip(xs, ys))
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= target <= x1:
            w = (math.log(target) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + w * (math.log(y1) - math.log(y0)))
    return float("nan")

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True); ap.add_argument("--scene", required=True)
    ap.add_argument("--reference", required=True); ap.add_argument("--sensor", required=True)
    ap.add_argument("--target", type=float, default=1e-4)
    ap.add_argument("--tol", type=float, nargs="+", default=[]); ap.add_argument("--h", type=float, nargs="+", default=[])
    ap.add_argument("--set", action="append", default=[]); ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--absolute", action="store_true", help="absolute instead of relative errors")
    a = ap.parse_args()
    with open(a.reference) as f:
        rows = list(csv.reader(f))
    ref = float(rows[-1][rows[0].index(a.sensor)])
    out = tempfile.mkdtemp(prefix="awp_")
    res = []
    for kind, values in (("tol", a.tol), ("h", a.h)):
        for v in values:
            tol_sets = [f"solver.tolerance.rtol={v}", f"solver.tolerance.atol={v}"]
            sets = list(a.set) + (tol_sets if kind == "tol" else [f"solver.h={v}"])
            r = run(a.exe, a.scene, sets, os.path.join(out, f"{kind}_{v}"), a.repeat)
            x = r["last"][r["header"].index(a.sensor)]
            r["error"] = abs(x - ref) / (1.0 if a.absolute else abs(ref))
            r["kind"], r["value"] = kind, v
            res.append(r)
    print(f"| policy | tol or h | steps | rejected | Newton/step | wall (ms) | error in {a.sensor} |")
    print("|---|---|---|---|---|---|---|")
    for r in res:
        print(f"| {'adaptive' if r['kind'] == 'tol' else 'fixed'} | {r['value']:g} | {r['steps']} | {r['rejected']} | "
              f"{r['newton'] / max(1, r['steps'] + r['rejected']):.2f} | {1e3 * r['wall']:.1f} | {r['error']:.3e} |")
    ad = [r for r in res if r["kind"] == "tol"]
    fx = [r for r in res if r["kind"] == "h"]
    if len(ad) >= 2:
        lx = [math.log(r["value"]) for r in ad]; ly = [math.log(r["error"]) for r in ad]
        mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
        slope = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sum((x - mx) ** 2 for x in lx)
        ratios = [r["error"] / r["value"] for r in ad]
        print(f"\nslope of log error vs log tol: {slope:.3f}; error/tol from {min(ratios):.3g} to {max(ratios):.3g}")
    at = {}
    for name, rs in (("adaptive", ad), ("fixed", fx)):
        if len(rs) >= 2:
            e = [r["error"] for r in rs]
            at[name] = (interp(e, [r['steps'] for r in rs], a.target), interp(e, [r['wall'] for r in rs], a.target))
            print(f"{name}: at {a.sensor} error {a.target:g}: steps {at[name][0]:.0f}, wall {1e3 * at[name][1]:.1f} ms")
    if len(at) == 2:
        print(f"fixed / adaptive at error {a.target:g}: steps {at['fixed'][0] / at['adaptive'][0]:.2f}, "
              f"wall {at['fixed'][1] / at['adaptive'][1]:.2f}")

if __name__ == "__main__":
    main()
