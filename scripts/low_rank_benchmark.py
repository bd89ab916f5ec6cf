#!/usr/bin/python3
"""Block low-rank factorization (solver.linear.low_rank, MUMPS' BLR) against the exact one, for
docs/performance.md (issue 22): the same scene run with low_rank off and at each tolerance, one run
at a time, on one rank; a markdown table of CPU time, peak memory, MUMPS' factor entries (full rank,
INFOG(29), and compressed, INFOG(35)), Newton iterations, and the largest relative difference of
the final sensor values from the exact run's.

    scripts/low_rank_benchmark.py [--exe build/alphaflex] --scene inputs/plate_pressure.yaml
        [--set key=value ...] [--tolerances 1e-8,1e-6,1e-4] [--label TEXT]

CPU time is the run's process CPU (resource.getrusage of the child: the machine is shared, wall
time would charge the run for the other jobs); memory is the summary's peak resident set.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(exe, scene, sets, outdir):
    cmd = [exe, "run", scene, "-o", outdir]
    for s in sets:
        cmd += ["--set", s]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:  # a Newton failure (exit 3) is a result: too loose a tolerance
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        return {"failed": f"exit {r.returncode}: {lines[-1] if lines else ''}",
                "cpu": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)}
    name = os.path.splitext(os.path.basename(scene))[0]
    with open(os.path.join(outdir, f"{name}.summary.json")) as f:
        s = json.load(f)
    s["cpu"] = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return s


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    p.add_argument("--scene", required=True)
    p.add_argument("--set", action="append", default=[])
    p.add_argument("--tolerances", default="1e-8,1e-6,1e-4")
    p.add_argument("--label", default="")
    a = p.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        exact = run(a.exe, a.scene, a.set, tmp)
        rows.append(("off (exact)", exact))
        for t in a.tolerances.split(","):
            rows.append((t, run(a.exe, a.scene, a.set + [f"solver.linear.low_rank={t}"], tmp)))
    ref = exact["final_sensors"]
    label = a.label or os.path.basename(a.scene) + " " + " ".join(a.set)
    print(f"{label}: {exact['unknowns']} unknowns, {exact['steps']} step(s)\n")
    print("| low_rank | CPU (s) | peak memory (MB) | MUMPS memory (MB) | factor entries | compressed entries (INFOG(35)) | Newton iterations | largest relative sensor difference |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for tol, s in rows:
        if "failed" in s:
            print(f"| {tol} | {s['cpu']:.2f} | | | | | | failed ({s['failed'][:120]}) |")
            continue
        m = s["mumps"]
        lr = m.get("low_rank", {}).get("factor_entries")
        diff = 0.0
        for k, v in s["final_sensors"].items() if isinstance(s["final_sensors"], dict) else []:
            r0 = ref[k]
            diff = max(diff, abs(v - r0) / abs(r0) if r0 else abs(v))
        comp = f"{lr:.4g} ({100 * lr / m['factor_entries']:.1f} %)" if lr else "–"
        print(f"| {tol} | {s['cpu']:.2f} | {s['memory_mb']['peak_all_ranks']:.0f} | {m['memory_mb_all_ranks']:.0f} | "
              f"{m['factor_entries']:.4g} | {comp} | {s['newton']['total']} | {diff:.1e} |")


if __name__ == "__main__":
    main()
