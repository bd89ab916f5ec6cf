#!/usr/bin/python3
"""Runs per second of `alphaflex study` on 1 rank and on N ranks in concurrent groups
(mpirun -np N ... --ranks-per-run K), for the table in docs/performance.md (issue 22).

    scripts/study_throughput.py [--exe build/alphaflex] [--ranks 2] [--ranks-per-run 1]
                                [--repeats 3] [--study SCENE:STUDY ...] [--without-peers]
                                [--study-set key=value ...]

For each study it runs the one-rank and the N-rank command alternately (--repeats times each, the
order of the two swapped at every repetition, so that the load of a shared machine falls on both
alike) and measures each command as a user sees it: the wall time of the process from exec to
exit (start-up, MPI_Init, the runs, gathering, file writing and, with --plots, the charts), and the
CPU time (user + system) of the process and everything it started (ranks, peers, chart script).
It counts the runs: the alphaflex rows of the CSV, the reference run, and the peers' rows (IDA,
Radau) unless --without-peers (then the study is run from a copy without its `peers:` block). It
prints a markdown table: runs, the median (and the shortest) wall time of each command, runs per
second and their ratio from the medians and from the shortest, the CPU times, and the load
average of the machine (1-minute, at the start and end of the study's measurements); and checks
that both CSVs have the same rows (scripts/../tests/study/compare_study_csv.py, time columns
excepted). --plots draws the charts as `alphaflex study` does by default (both commands alike).

Every process runs in a session of its own (setsid -w, also each rank under mpirun): Linux's
autogroup scheduling (kernel.sched_autogroup_enabled = 1, Debian's default) shares the CPU among
sessions, not processes, so on a machine busy with other sessions the two ranks of one session
would share one session's CPU and show no gain whatever the code does. --same-session turns this
off (the numbers then say what a user of a busy desktop sees). --study-set is given to both commands
(e.g. more step sizes, so that the runs and not the start-up are measured).
"""
import argparse
import csv
import os
import resource
import statistics
import shlex
import subprocess
import sys
import tempfile
import time

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT = ["inputs/slider_crank.yaml:inputs/studies/slider_crank_convergence.yaml",
           "inputs/andrews.yaml:inputs/studies/andrews_work_precision.yaml"]


def study_copy(study, tmp, without_peers):
    """The study file with its relative reference path made absolute (and no peers if asked)."""
    with open(study) as f:
        doc = yaml.safe_load(f)
    s = doc["study"]
    ref = s.get("reference", {})
    if "file" in ref and not os.path.isabs(ref["file"]):
        ref["file"] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(study)), ref["file"]))
    if without_peers:
        s.pop("peers", None)
    path = os.path.join(tmp, os.path.basename(study))
    with open(path, "w") as f:
        yaml.safe_dump(doc, f, sort_keys=False)
    return path, s.get("name"), bool(s.get("reference", {}).get("h"))


def count_runs(csv_path, reference_run):
    with open(csv_path) as f:
        rows = list(csv.DictReader(l for l in f if not l.startswith("#")))
    return len(rows) + (1 if reference_run else 0), sum(float(r["cpu"]) for r in rows)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    p.add_argument("--mpirun", default="mpirun")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--ranks-per-run", type=int, default=1)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--study", action="append", help="SCENE:STUDY (default: the slider-crank and Andrews convergence studies)")
    p.add_argument("--without-peers", action="store_true")
    p.add_argument("--same-session", action="store_true")
    p.add_argument("--study-set", action="append", default=[], help="key=value for both commands' --study-set")
    p.add_argument("--plots", action="store_true", help="draw the charts (the command's default) in both commands")
    a = p.parse_args()
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    lines = [f"| study | runs | 1 rank: wall (s), median (min) | CPU (s) | {a.ranks} ranks, {a.ranks_per_run} per run: "
             "wall (s), median (min) | CPU (s) | runs/s 1 rank | runs/s N ranks | ratio of medians (of minima) | load |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    with tempfile.TemporaryDirectory() as tmp:
        for item in a.study or DEFAULT:
            scene, study = (os.path.join(ROOT, x) if not os.path.isabs(x) else x for x in item.split(":"))
            copy, name, reference_run = study_copy(study, tmp, a.without_peers)
            own = [] if a.same_session else ["setsid", "-w"]
            base = own + [a.exe, "study", scene, "--study", copy] + ([] if a.plots else ["--no-plots"])
            for kv in a.study_set:
                base += ["--study-set", kv]
            cmds = {"1": base + ["-o", os.path.join(tmp, "one")],
                    "N": [a.mpirun, "--oversubscribe", "-np", str(a.ranks)] + base +
                         ["-o", os.path.join(tmp, "many"), "--ranks-per-run", str(a.ranks_per_run)]}
            walls = {"1": [], "N": []}
            cpus = {"1": [], "N": []}
            load0 = os.getloadavg()[0]
            for rep in range(a.repeats):
                for key in (("1", "N") if rep % 2 == 0 else ("N", "1")):
                    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
                    t0 = time.perf_counter()
                    r = subprocess.run(cmds[key], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                    wall = time.perf_counter() - t0
                    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
                    if r.returncode != 0:
                        sys.exit(f"{shlex.join(cmds[key])} exited {r.returncode}:\n{r.stderr}")
                    walls[key].append(wall)
                    cpus[key].append(c1.ru_utime - c0.ru_utime + c1.ru_stime - c0.ru_stime)
                    print(f"  {os.path.basename(study)} {key}: {wall:.2f} s wall, {cpus[key][-1]:.2f} s CPU", file=sys.stderr, flush=True)
            load1 = os.getloadavg()[0]
            one, many = (os.path.join(tmp, d, f"{name}_study.csv") for d in ("one", "many"))
            cmp = subprocess.run([sys.executable, os.path.join(ROOT, "tests", "study", "compare_study_csv.py"), one, many],
                                 capture_output=True, text=True)
            if cmp.returncode != 0:
                sys.exit(cmp.stdout + cmp.stderr)
            runs, _ = count_runs(one, reference_run)
            med = {k: statistics.median(v) for k, v in walls.items()}
            low = {k: min(v) for k, v in walls.items()}
            cpu = {k: statistics.median(v) for k, v in cpus.items()}
            label = os.path.basename(study) + (" (without peers)" if a.without_peers else "") + (" (charts)" if a.plots else "")
            lines.append(f"| {label} | {runs} | {med['1']:.2f} ({low['1']:.2f}) | {cpu['1']:.2f} | {med['N']:.2f} ({low['N']:.2f}) | "
                         f"{cpu['N']:.2f} | {runs / med['1']:.2f} | {runs / med['N']:.2f} | "
                         f"**{med['1'] / med['N']:.2f}** ({low['1'] / low['N']:.2f}) | {load0:.0f}–{load1:.0f} |")
            print(lines[-1], file=sys.stderr, flush=True)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
