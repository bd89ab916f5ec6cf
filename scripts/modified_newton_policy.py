#!/usr/bin/python3
"""Modified against full Newton on every scene of inputs/ (issue 22: "modified Newton by default
where it pays"): time and accuracy of the sensors, written as a table into docs/performance.md
(between the markers of the section "Modified Newton by default").

    /usr/bin/python3 scripts/modified_newton_policy.py [--exe build/alphaflex] [--repeat 3]
                                                       [--scenes andrews,beam_spinup,...] [--no-doc]

Every dynamic scene runs as given (its own h and t_end; the few long ones shortened, see SHORTER)
with `solver.newton.modified=off` and `=on`, alternated `--repeat` times, HDF5 off, and once with
the default (whose summary names the method it took: `newton.method`); the time is
the shortest of the run's step loop (the summary's wall time less its setup, so reading, meshing
and start-up are not in it) and the process CPU. Accuracy: for every sensor, the largest difference
between the two runs' CSV rows over the whole run, relative to the largest |value| of that sensor
in the full-Newton run (the scale of a sensor that passes through zero); the table gives the
worst sensor. The last column is the method the default (`solver.newton.modified: auto`, modified
Newton from MODIFIED_FROM unknowns or for a model with an element that favours it) takes on the
scene, as a third run's summary states it. Static scenes (solver.analysis: static) are listed: their load steps use full Newton
whatever the key says (integrators/quasi_static.cpp), so there is nothing to measure.
"""
import argparse
import os
import resource
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import alphaflex_results as ar  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchmark as bm  # noqa: E402

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
# Scenes whose full run takes more than ~20 s on this machine: shortened (the policy is about the
# steps, not the length of the run).
SHORTER = {"fourbar_flexible": ["solver.t_end=3"], "beam_spinup": ["solver.t_end=5"],
           "beam_impulse": ["solver.t_end=0.3"]}
# The default (solver.newton.modified: auto): modified Newton from this many unknowns, all ranks
# together (NewtonOptions::modified_from, the key solver.newton.modified_from).
MODIFIED_FROM = 30
BEGIN = "<!-- modified_newton_policy: begin -->"
END = "<!-- modified_newton_policy: end -->"


def is_static(path):
    import yaml
    with open(path) as fh:
        y = yaml.safe_load(fh)
    return str((y.get("solver") or {}).get("analysis", "dynamic")) == "static"


def run(exe, scene, modified, outdir, extra):
    """modified: True (on), False (off) or None (the default, `auto`)."""
    args = [exe, "run", scene, "-o", outdir, "--set", "output.hdf5=off"]
    if modified is not None:
        args += ["--set", "solver.newton.modified=" + ("on" if modified else "off")]
    for s in extra:
        args += ["--set", s]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(args, cwd=ROOT, env=ENV, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    name = os.path.splitext(os.path.basename(scene))[0]
    if p.returncode != 0:
        return {"failed": p.returncode, "message": (p.stderr or p.stdout).strip().splitlines()[-1:]}
    j = ar.load_summary(outdir)
    wall = j["wall_time"]
    csvs = [f for f in os.listdir(outdir) if f.endswith(".csv")]
    return {"loop": wall["s"] - wall["setup"]["s"], "cpu": cpu, "steps": j["steps"],
            "newton": j["newton"]["total"], "factorizations": j["factorizations"]["numeric"],
            "unknowns": j["unknowns"], "method": j["newton"].get("method", ""), "sensors": ar.load_sensors(os.path.join(outdir, csvs[0])) if csvs else None,
            "name": name}


def sensor_difference(full, mod):
    worst, which = 0.0, "–"
    for k, a in full.items():
        if k == "t" or k not in mod or len(mod[k]) != len(a):
            continue
        b = mod[k]
        scale = np.nanmax(np.abs(a))
        if not np.isfinite(scale) or scale == 0.0:
            continue
        d = np.nanmax(np.abs(a - b)) / scale
        if d > worst:
            worst, which = d, k
    return worst, which


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--scenes", default="")
    ap.add_argument("--no-doc", action="store_true")
    a = ap.parse_args()
    scenes = sorted(f for f in os.listdir(os.path.join(ROOT, "inputs")) if f.endswith(".yaml"))
    if a.scenes:
        want = set(a.scenes.split(","))
        scenes = [s for s in scenes if os.path.splitext(s)[0] in want]
    rows = []
    for f in scenes:
        name = os.path.splitext(f)[0]
        path = os.path.join("inputs", f)
        if is_static(os.path.join(ROOT, path)):
            rows.append((name, None))
            print(f"{name}: static", flush=True)
            continue
        runs = {False: [], True: []}
        with tempfile.TemporaryDirectory() as tmp:
            for r in range(a.repeat):
                for modified in ((False, True) if r % 2 == 0 else (True, False)):
                    out = os.path.join(tmp, f"{int(modified)}_{r}")
                    runs[modified].append(run(a.exe, path, modified, out, SHORTER.get(name, [])))
            # The default's choice, as its summary states it (solver.newton.modified: auto).
            auto = run(a.exe, path, None, os.path.join(tmp, "auto"), SHORTER.get(name, []))
        best = {}
        for modified, rs in runs.items():
            failed = [x for x in rs if "failed" in x]
            best[modified] = failed[0] if failed else dict(rs[0], loop=min(x["loop"] for x in rs),
                                                          cpu=min(x["cpu"] for x in rs))
        best[None] = auto
        rows.append((name, best))
        fu, mo = best[False], best[True]
        if "failed" in fu or "failed" in mo:
            print(f"{name}: failed full={fu.get('failed')} modified={mo.get('failed')}", flush=True)
        else:
            print(f"{name}: {fu['unknowns']} unknowns, loop {fu['loop']:.3f} / {mo['loop']:.3f} s, "
                  f"ratio {fu['loop'] / max(mo['loop'], 1e-9):.2f}", flush=True)
    table = format_table(rows, " ".join(f"{k}: {' '.join(v)}" for k, v in SHORTER.items()))
    print(table)
    if not a.no_doc:
        bm.replace_between_markers(BEGIN, END, table)


def format_table(rows, shorter):
    lines = ["| scene | unknowns | steps | Newton/step, full / modified | factorizations/step, modified "
             "| step loop, full (s) | modified (s) | full / modified | CPU, full / modified "
             "| largest sensor difference (relative) | default (`auto`) takes |",
             "|---|---:|---:|---|---:|---:|---:|---:|---:|---|---|"]
    right, dynamic, gains = 0, 0, []
    right_by_size, gains_by_size = 0, []
    for name, best in rows:
        if best is None:
            lines.append(f"| {name} | | | static analysis: full Newton in the load steps | | | | | | | full |")
            continue
        fu, mo, auto = best[False], best[True], best[None]
        if "failed" in auto or not auto.get("method"):
            # Without the default's own statement the scene cannot be counted for or against it.
            lines.append(f"| {name} | | | the default's run failed (exit {auto.get('failed', 0)}) or named no method "
                         f"| | | | | | | |")
            continue
        if "failed" in fu or "failed" in mo:
            lines.append(f"| {name} | | | failed: full exit {fu.get('failed', 0)}, modified exit {mo.get('failed', 0)} "
                         f"({' '.join(mo.get('message', fu.get('message', [])))}) | | | | | | | |")
            continue
        takes_modified = auto["method"].startswith("modified")
        by_size = fu["unknowns"] >= MODIFIED_FROM  # the size rule alone, for comparison
        ratio = fu["loop"] / max(mo["loop"], 1e-9)
        dynamic += 1
        right += (ratio > 1.0) == takes_modified
        right_by_size += (ratio > 1.0) == by_size
        gains.append(ratio if takes_modified else 1.0)
        gains_by_size.append(ratio if by_size else 1.0)
        steps = max(fu["steps"], 1)
        if fu["sensors"] is not None and mo["sensors"] is not None:
            d, which = sensor_difference(fu["sensors"], mo["sensors"])
            diff = f"{d:.1e} ({which})"
        else:
            diff = "no sensors"
        lines.append(
            f"| {name} | {fu['unknowns']} | {fu['steps']} | {fu['newton'] / steps:.2f} / {mo['newton'] / max(mo['steps'], 1):.2f} "
            f"| {mo['factorizations'] / max(mo['steps'], 1):.2f} | {fu['loop']:.3f} | {mo['loop']:.3f} "
            f"| **{ratio:.2f}** | {fu['cpu'] / max(mo['cpu'], 1e-9):.2f} | {diff} | {'modified' if takes_modified else 'full'} |")
    lines.append("")
    if dynamic:
        mean = float(np.exp(np.mean(np.log(gains))))
        lines.append(f"The default (modified Newton from {MODIFIED_FROM} unknowns, or with a reduced body or a motor "
                     f"that reads sensors) takes the faster method on {right} of "
                     f"{dynamic} dynamic scenes; its step loop is {mean:.2f}× as fast as full Newton's (geometric mean "
                     f"over the dynamic scenes; {min(gains):.2f}–{max(gains):.2f}×). The size rule alone (modified "
                     f"Newton from {MODIFIED_FROM} unknowns, whatever the elements) would take it on {right_by_size} "
                     f"and be {float(np.exp(np.mean(np.log(gains_by_size)))):.2f}× as fast.")
        lines.append("")
    lines.append(f"Shortened runs (`--set`): {shorter}.")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
