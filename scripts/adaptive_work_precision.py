#!/usr/bin/python3
"""Work-precision of adaptive against fixed steps (issue 17), one scene, in one run.

For each tolerance (solver.tolerance.rtol = atol = tol) and each fixed h, alternating the two
(tol 1, h 1, tol 2, h 2, ...: a change of the machine's load falls on both alike), runs `alphaflex run`
and reads: the relative error of one sensor at t_end against a reference CSV (its last row),
accepted and rejected steps, Newton iterations, and the run's own wall time from its summary
(setup, integration and output; process start not counted). Prints a table, the least-squares
slope of log error against log tol (tolerance proportionality: 1) and, for a target error, the
steps and time of each policy interpolated in log-log.

CPU is the process CPU time of each run (user + system, from the operating system's accounting of
the child process: it includes start-up, and is what a loaded machine does not inflate, unlike the
wall time). `--reference-h H` computes the reference in the same run: the scene with fixed steps of
H (a much finer step than any measured). `--doc NAME` writes the table and the figures at the target
error between the markers `<!-- NAME: begin -->` and `<!-- NAME: end -->` of docs/performance_notes.md
and of docs/performance.md (scripts/benchmark.py copies the notes under its tables).

Factorizations per accepted step come from the summary's count of numeric factorizations (the
consistent start's included). `--startup` also measures the process start-up, interleaved: the scene
run for two steps of 1e-7 s before each pair (tol i, h i); the median of its CPU is subtracted from
each run's CPU for the integration-only figures, and both ratios are printed.

Example (the damped struck beam, issue 17's third target; ~3 min of CPU):
  /usr/bin/python3 scripts/adaptive_work_precision.py --exe build/alphaflex --scene inputs/beam_impulse_damped.yaml \
      --reference-h 6.25e-5 --sensor tip_y --absolute --target 1e-5 --repeat 1 --doc adaptive_struck_beam \
      --tol 1e-4 1e-5 1e-6 --h 2e-3 1e-3 5e-4 2.5e-4 1.25e-4

Example (the hammer-struck damped beam, issue 17's fourth round; the reference h = 1e-5 s lands on
the blow's three breakpoints, none of the measured fixed h does):
  /usr/bin/python3 scripts/adaptive_work_precision.py --exe build/alphaflex --scene inputs/beam_hammer_damped.yaml \
      --reference-h 5e-6 --sensor tip_y --absolute --target 1e-4 --repeat 1 --doc adaptive_hammer \
      --startup --tol 1e-3 1e-4 1e-5 1e-6 --h 4e-4 2e-4 1e-4 5e-5 2.5e-5 1.25e-5

Example (Andrews, 1e-4 in beta):
  /usr/bin/python3 scripts/adaptive_work_precision.py --exe build/alphaflex --scene inputs/andrews.yaml \
      --reference tests/reference/andrews.csv --sensor beta --target 1e-4 \
      --tol 1e-3 3e-4 1e-4 3e-5 1e-5 1e-6 --h 1.2e-4 8e-5 5.6e-5 4e-5 2.8e-5 2e-5
"""
import argparse, csv, math, os, re, resource, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchmark as bm  # noqa: E402

def run(exe, scene, sets, outdir, repeat):
    best = best_cpu = None
    for _ in range(repeat):
        # What is measured is the sensors' CSV: no field output, no checkpoint at the end (docs/input.md:
        # `checkpoint_at_end: off` for benchmarks and sweeps), for adaptive and fixed runs alike.
        cmd = [exe, "run", scene, "-o", outdir, "--set", "output.hdf5=off", "--set", "output.checkpoint_at_end=off"]
        for s in sets: cmd += ["--set", s]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, capture_output=True, text=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode != 0:
            sys.exit("failed: " + " ".join(cmd) + "\n" + p.stdout + p.stderr)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        wall = float(re.search(r"wall time\s+([0-9.]+) s", p.stdout).group(1))
        best = wall if best is None else min(best, wall)
        best_cpu = cpu if best_cpu is None else min(best_cpu, cpu)
    m = re.search(r"steps\s+(\d+)( accepted, (\d+) rejected, (\d+) Newton failures)?", p.stdout)
    newton = int(re.search(r"Newton iterations\s+total (\d+)", p.stdout).group(1))
    factorizations = int(re.search(r"factorizations\s+(\d+) numeric", p.stdout).group(1))
    name = re.search(r"sensors\s+(\S+\.csv)", p.stdout).group(1)
    with open(name) as f:
        rows = list(csv.reader(f))
    return dict(steps=int(m.group(1)), rejected=int(m.group(3) or 0), newton=newton, factorizations=factorizations,
                wall=best, cpu=best_cpu,
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
    ap.add_argument("--reference", help="reference CSV (its last row)"); ap.add_argument("--sensor", required=True)
    ap.add_argument("--reference-h", type=float, help="instead of --reference: a fixed-step run of this h, in the same run")
    ap.add_argument("--doc", help="write the results between the markers <!-- DOC: begin/end --> of docs/performance*.md")
    ap.add_argument("--target", type=float, default=1e-4)
    ap.add_argument("--tol", type=float, nargs="+", default=[]); ap.add_argument("--h", type=float, nargs="+", default=[])
    ap.add_argument("--set", action="append", default=[]); ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--adaptive-set", action="append", default=[], help="a --set for the adaptive runs only (e.g. solver.tolerance.hold=1.2)")
    ap.add_argument("--absolute", action="store_true", help="absolute instead of relative errors")
    ap.add_argument("--startup", action="store_true",
                    help="also run the scene for 2 steps of 1e-7 s before each pair (tol i, h i): the process start-up's CPU, "
                         "whose median is subtracted for the integration-only CPU")
    a = ap.parse_args()
    out = tempfile.mkdtemp(prefix="awp_")
    if a.reference_h:
        r = run(a.exe, a.scene, list(a.set) + [f"solver.h={a.reference_h}"], os.path.join(out, "reference"), 1)
        ref = r["last"][r["header"].index(a.sensor)]
        ref_text = f"fixed h = {a.reference_h:g} s ({r['steps']} steps, this run): {a.sensor} = {ref:.10g}"
    elif a.reference:
        with open(a.reference) as f:
            rows = list(csv.reader(f))
        ref = float(rows[-1][rows[0].index(a.sensor)])
        ref_text = a.reference
    else:
        sys.exit("--reference or --reference-h is needed")
    res = []
    # Adaptive and fixed runs alternate (tol 1, h 1, tol 2, h 2, ...), so that a change of the
    # machine's load during the sweep falls on both policies alike; the table lists them by policy.
    order = []
    for i in range(max(len(a.tol), len(a.h))):
        order += [("tol", a.tol[i])] if i < len(a.tol) else []
        order += [("h", a.h[i])] if i < len(a.h) else []
    startup = []
    for i, (kind, v) in enumerate(order):
        if a.startup and (i == 0 or order[i - 1][0] == "h" or kind == "tol"):
            st = run(a.exe, a.scene, list(a.set) + ["solver.h=1e-7", "solver.t_end=2e-7"], os.path.join(out, f"startup_{i}"), 1)
            startup.append(st["cpu"])
        tol_sets = [f"solver.tolerance.rtol={v}", f"solver.tolerance.atol={v}"]
        sets = list(a.set) + (tol_sets + list(a.adaptive_set) if kind == "tol" else [f"solver.h={v}"])
        r = run(a.exe, a.scene, sets, os.path.join(out, f"{kind}_{v}"), a.repeat)
        x = r["last"][r["header"].index(a.sensor)]
        r["error"] = abs(x - ref) / (1.0 if a.absolute else abs(ref))
        r["kind"], r["value"] = kind, v
        res.append(r)
    res.sort(key=lambda r: (r["kind"] != "tol", -r["value"]))  # adaptive first, each from the largest value
    st_cpu = sorted(startup)[len(startup) // 2] if startup else 0.0
    for r in res:
        r["cpu_int"] = max(r["cpu"] - st_cpu, 1e-4)
    lines = [f"| policy | tol or h | steps | rejected | Newton/step | factorizations/step | wall (ms) | CPU (ms) |"
             + (" CPU − start-up (ms) |" if startup else "") + f" error in {a.sensor} |",
             "|---|---|---|---|---|---|---|---|" + ("---|" if startup else "") + "---|"]
    for r in res:
        lines.append(f"| {'adaptive' if r['kind'] == 'tol' else 'fixed'} | {r['value']:g} | {r['steps']} | {r['rejected']} | "
                     f"{r['newton'] / max(1, r['steps'] + r['rejected']):.2f} | {r['factorizations'] / max(1, r['steps']):.3f} | "
                     f"{1e3 * r['wall']:.1f} | {1e3 * r['cpu']:.1f} | " + (f"{1e3 * r['cpu_int']:.1f} | " if startup else "")
                     + f"{r['error']:.3e} |")
    lines += ["", f"Reference: {ref_text}; errors {'absolute' if a.absolute else 'relative'}, at t_end."
              + (f" Adaptive runs with {', '.join(a.adaptive_set)}." if a.adaptive_set else "")]
    if startup:
        lines.append(f"Start-up (2 steps of 1e-7 s, {len(startup)} runs interleaved with the sweep): CPU median "
                     f"{1e3 * st_cpu:.0f} ms, from {1e3 * min(startup):.0f} to {1e3 * max(startup):.0f} ms; subtracted for "
                     f"the integration-only CPU.")
    ad = [r for r in res if r["kind"] == "tol"]
    fx = [r for r in res if r["kind"] == "h"]
    def slope(xs, ys):
        lx = [math.log(x) for x in xs]; ly = [math.log(y) for y in ys]
        mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
        return sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sum((x - mx) ** 2 for x in lx)
    if len(ad) >= 2:
        ratios = [r["error"] / r["value"] for r in ad]
        lines.append(f"Slope of log error against log tol: {slope([r['value'] for r in ad], [r['error'] for r in ad]):.2f}; "
                     f"error/tol from {min(ratios):.3g} to {max(ratios):.3g}.")
    if len(fx) >= 2:
        lines.append(f"Slope of log error against log h (fixed): {slope([r['value'] for r in fx], [r['error'] for r in fx]):.2f}.")
    at = {}
    for name, rs in (("adaptive", ad), ("fixed", fx)):
        if len(rs) >= 2:
            e = [r["error"] for r in rs]
            at[name] = (interp(e, [r['steps'] for r in rs], a.target), interp(e, [r['cpu'] for r in rs], a.target),
                        interp(e, [r['cpu_int'] for r in rs], a.target))
            lines.append(f"At error {a.target:g} ({name}, interpolated in log-log): {at[name][0]:.0f} steps, "
                         f"{1e3 * at[name][1]:.0f} ms CPU" + (f", {1e3 * at[name][2]:.0f} ms without start-up" if startup else "") + ".")
    if len(at) == 2:
        lines.append(f"Fixed / adaptive at error {a.target:g}: steps {at['fixed'][0] / at['adaptive'][0]:.2f}, "
                     f"CPU {at['fixed'][1] / at['adaptive'][1]:.2f}"
                     + (f", CPU without start-up {at['fixed'][2] / at['adaptive'][2]:.2f}" if startup else "") + ".")
    lines.append(f"Load average at the end: {os.getloadavg()[0]:.1f}.")
    print("\n".join(lines))
    if a.doc:
        bm.replace_between_markers(f"<!-- {a.doc}: begin -->", f"<!-- {a.doc}: end -->", "\n".join(lines))

if __name__ == "__main__":
    main()
