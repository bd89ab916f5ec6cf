#!/usr/bin/python3
"""CPU of a reduced link against its full nonlinear mesh, and the reduced link's error, in one run
of this script (issue 19: "at >= 20x less CPU for a link of >= 10^3 unknowns, ratio measured in one
run"; docs/benchmarks/reduced.md).

The scene is the flexible pendulum of tests/cli/reduced_pendulum.yaml (a steel strip hinged at its
root and released horizontal under gravity, tip sag 2.6 % of L: the small-deformation regime),
refined to --elements beam elements (170: 1026 coordinates), run over --t-end with the full
geometrically nonlinear mesh and with the same block reduced by Craig-Bampton on its root
(`reduction: {method: craig_bampton, modes: K, interface: [root]}`, K = --modes).

The variants alternate (full, reduced, full, reduced, ...) for --rounds rounds, so that the load of
a shared machine falls on both alike; each figure is the least over the rounds. CPU is the process
CPU time of each run (user + system, the operating system's accounting of the child process; the
wall time of a loaded machine is not a measure). Each variant is also run for a single step: that
run's CPU is the fixed cost (process start, mesh, the reduction, set-up), and the difference is the
CPU of the steps. The reduction's own cost is the fixed cost of the reduced variant less that of
the block reduced rigidly (`method: rigid`: the same small model, no modes). Fields and the final checkpoint are off in both (output.hdf5 off, checkpoint_at_end off): the
comparison is of the dynamics; the sensors are written every step.

Error: for each sensor, max |reduced - full| over the run divided by the full run's range of that
sensor (the issue's measure).

Example (~1 min of CPU):
  /usr/bin/python3 scripts/reduced_cost.py --exe build/alphaflex --doc reduced_cost

With --study, the ladder of a fidelity study instead (`alphaflex study SCENE --study FILE`, e.g.
the slider-crank's rod or the four-bar's links refined with --set mesh.elements=N): the study is
run for each variant of the reduced rungs — `linear` (geometric_stiffness off, static_modes none)
and `geometric` (geometric_stiffness on, static_modes inertia) — alternating, --rounds times; the
CPU of each rung is the run's own (the study's `cpu` column: run_simulation only, without the scene
build and the one-off reduction), the least over the rounds, and the ratio is the full rung's CPU
(same study run set) over the rung's. Errors are the study's (max over the sensors of
max |rung - full| / the full run's range), identical in every round.
  /usr/bin/python3 scripts/reduced_cost.py --exe build/alphaflex --study inputs/studies/slider_crank_reduction.yaml \
      --scene inputs/slider_crank_flexible_3d.yaml --set mesh.elements=85 --ladder 2,4,8
"""
import argparse, csv, os, re, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(a, out, extra):
    cmd = [a.exe, "run", a.scene, "-o", out, "--set", f"mesh.elements={a.elements}",
           "--set", "output.hdf5=off", "--set", "output.checkpoint_at_end=off", "--set", "output.progress=0"] + extra
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        child = subprocess.Popen(cmd, stdout=out, stderr=err, text=True)
        _, status, usage = os.wait4(child.pid, 0)  # this child's own accounting
        child.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout = out.read()
        if child.returncode != 0:
            sys.exit("failed: " + " ".join(cmd) + "\n" + stdout + err.read())
    cpu = usage.ru_utime + usage.ru_stime
    unknowns = int(re.search(r"unknowns\s+(\d+)", stdout).group(1))
    steps = int(re.search(r"steps\s+(\d+)", stdout).group(1))
    newton = int(re.search(r"Newton iterations\s+total (\d+)", stdout).group(1))
    name = re.search(r"sensors\s+(\S+\.csv)", stdout).group(1)
    with open(name) as f:
        rows = list(csv.DictReader(f))
    series = {k: [float(r[k]) for r in rows] for k in rows[0]}
    return dict(cpu=cpu, unknowns=unknowns, steps=steps, newton=newton, series=series)


def error(ref, x, key):
    rng = max(ref[key]) - min(ref[key])
    return max(abs(p - q) for p, q in zip(ref[key], x[key])) / rng


VARIANTS = {
    "linear": ["--study-set", "reduce.geometric_stiffness=off", "--study-set", "reduce.static_modes=none",
               "--study-set", "reduce.derivatives=0"],
    "geometric": ["--study-set", "reduce.geometric_stiffness=on", "--study-set", "reduce.static_modes=inertia",
                  "--study-set", "reduce.derivatives=0"],
    # Geometric stiffness with the modal derivatives of the first N basis vectors (--derivatives).
    "derivatives": ["--study-set", "reduce.geometric_stiffness=on", "--study-set", "reduce.static_modes=none"],
}


def run_study(a, out, variant):
    ladder = "[" + ", ".join(a.ladder.split(",") + ["full"]) + "]"
    cmd = [a.exe, "study", a.scene, "--study", a.study, "-o", out, "--study-set", f"reduce.ladder={ladder}"]
    for s in a.set or []:
        cmd += ["--set", s]
    cmd += VARIANTS[variant]
    if variant == "derivatives":
        cmd += ["--study-set", f"reduce.derivatives={a.derivatives}"]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("failed: " + " ".join(cmd) + "\n" + done.stdout + done.stderr)
    name = [f for f in os.listdir(out) if f.endswith("_study.csv")][0]
    with open(os.path.join(out, name)) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return {r["label"]: dict(cpu=float(r["cpu"]), err=float(r["err_max"]), newton=float(r["newton_mean"]),
                             unknowns=int(r["unknowns"])) for r in rows}


def study_main(a):
    variants = a.variants.split(",")
    res = {v: [] for v in variants}
    loads = []
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for v in variants:
                loads.append(os.getloadavg()[0])
                res[v].append(run_study(a, f"{tmp}/{v}{r}", v))
    labels = list(res[variants[0]][0])
    best = {v: {l: min(x[l]["cpu"] for x in res[v]) for l in labels} for v in variants}
    head = "| rung |" + "".join(f" {v}: unknowns | Newton/step | max error | CPU (s) | full ÷ rung |" for v in variants)
    lines = [f"{os.path.relpath(os.path.abspath(a.scene), ROOT)} {' '.join(a.set or [])}, study {os.path.relpath(os.path.abspath(a.study), ROOT)}; "
             f"least CPU of {a.rounds} alternating rounds (the study's run CPU); load average "
             f"{min(loads):.1f}-{max(loads):.1f} on {os.cpu_count()} cores, {time.strftime('%Y-%m-%d')}.", "", head,
             "|---|" + "---|---|---|---|---|" * len(variants)]
    for l in labels:
        row = f"| {l} |"
        for v in variants:
            x = res[v][0][l]
            row += f" {x['unknowns']} | {x['newton']:.2f} | {x['err']:.2e} | {best[v][l]:.3f} | {best[v]['full'] / best[v][l]:.1f} |"
        lines.append(row)
    text = "\n".join(lines)
    print(text)
    return text


def write_doc(name, text):
    path = os.path.join(ROOT, "docs/benchmarks/reduced.md")
    doc = open(path).read()
    begin, end = f"<!-- {name}: begin -->", f"<!-- {name}: end -->"
    if begin not in doc or end not in doc:
        sys.exit(f"{path}: no markers {begin} ... {end}")
    head, rest = doc.split(begin, 1)
    doc = head + begin + "\n" + text + "\n" + end + rest.split(end, 1)[1]
    open(path, "w").write(doc)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--study", help="a fidelity study file: run its ladder instead (see above)")
    p.add_argument("--set", action="append", help="with --study: a scene --set (repeatable), e.g. mesh.elements=85")
    p.add_argument("--ladder", default="2,4,8", help="with --study: the reduced rungs (the full rung is added)")
    p.add_argument("--variants", default="linear,geometric", help="with --study: linear, geometric, derivatives (comma-separated)")
    p.add_argument("--derivatives", type=int, default=6, help="the variant `derivatives`: reduce.derivatives (default 6)")
    p.add_argument("--exe", required=True)
    p.add_argument("--scene", default=os.path.join(ROOT, "tests/cli/reduced_pendulum.yaml"))
    p.add_argument("--elements", type=int, default=170)
    p.add_argument("--modes", type=int, default=8)
    p.add_argument("--t-end", type=float, default=1.0)
    p.add_argument("--h", type=float, default=1e-3)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--sensors", nargs="+", default=["angle", "fx"])
    p.add_argument("--doc", help="write the table between <!-- NAME: begin --> and <!-- NAME: end --> of docs/benchmarks/reduced.md")
    a = p.parse_args()
    if a.study:
        text = study_main(a)
        if a.doc:
            write_doc(a.doc, text)
        return
    reduction = ["--set", f"beams.0.reduction={{method: craig_bampton, modes: {a.modes}, interface: [root]}}"]
    variants = {"full": [], "reduced": reduction}
    timing = ["--set", f"solver.h={a.h}"]
    res = {v: dict(long=[], short=[]) for v in variants}
    rigid = []  # one-step runs of the block reduced rigidly: the same model size without the modes
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for v, extra in variants.items():
                res[v]["long"].append(run(a, f"{tmp}/{v}{r}", extra + timing + ["--set", f"solver.t_end={a.t_end}"]))
                res[v]["short"].append(run(a, f"{tmp}/{v}{r}s", extra + timing + ["--set", f"solver.t_end={a.h}"]))
            rigid.append(run(a, f"{tmp}/rigid{r}s", ["--set", "beams.0.reduction={method: rigid, interface: [root]}"] + timing
                             + ["--set", f"solver.t_end={a.h}"])["cpu"])
    best = {v: dict(total=min(x["cpu"] for x in res[v]["long"]), fixed=min(x["cpu"] for x in res[v]["short"])) for v in variants}
    for v in variants:
        best[v]["steps"] = best[v]["total"] - best[v]["fixed"]
    full, red = res["full"]["long"][0], res["reduced"]["long"][0]
    if len(full["series"]["t"]) != len(red["series"]["t"]):
        sys.exit("the runs' output times differ")
    errors = {k: error(full["series"], red["series"], k) for k in a.sensors}
    reduction_cpu = best["reduced"]["fixed"] - min(rigid)
    ratio = best["full"]["total"] / best["reduced"]["total"]
    step_ratio = best["full"]["steps"] / best["reduced"]["steps"]
    lines = [
        f"Flexible pendulum ({a.elements} elements), t_end = {a.t_end} s, h = {a.h} s ({full['steps']} steps), "
        f"{a.modes} modes; least of {a.rounds} alternating rounds; process CPU (user + system) in s.",
        "",
        "| variant | unknowns | Newton iterations | CPU, whole run | fixed (one-step run) | steps (difference) |",
        "|---|---|---|---|---|---|",
    ]
    for v in variants:
        x = res[v]["long"][0]
        lines.append(f"| {v} | {x['unknowns']} | {x['newton']} | {best[v]['total']:.3f} | {best[v]['fixed']:.3f} | {best[v]['steps']:.3f} |")
    lines += [
        "",
        f"- CPU ratio full / reduced, whole run: **{ratio:.1f}x**; of the steps alone: {step_ratio:.1f}x",
        f"- Craig-Bampton reduction (fixed cost of the reduced run less a rigidly reduced one's): {reduction_cpu:.3f} s",
        "- error, max |reduced - full| / range of the full run: "
        + ", ".join(f"{k} {e:.2e}" for k, e in errors.items()),
        f"- >= 20x less CPU: {'met' if ratio >= 20 else 'not met'} (whole run); "
        f"within 1 %: {'yes' if max(errors.values()) < 0.01 else 'no'}",
    ]
    text = "\n".join(lines)
    print(text)
    if a.doc:
        write_doc(a.doc, text)


if __name__ == "__main__":
    main()
