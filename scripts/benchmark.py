#!/usr/bin/python3
"""Performance benchmark of alphaflex on its large scene (inputs/gridshell.yaml), written to
docs/performance.md with charts in docs/figures/ and the measured rows in docs/benchmarks/performance.csv.

    /usr/bin/python3 scripts/benchmark.py [--exe build/alphaflex] [--sizes 8,16,32,48,64]
                                          [--ranks 1,2] [--baseline OTHER_EXE] [--quick]

For each size n (laths per direction; unknowns ~ 48 n^2) and rank count it runs the scene twice,
for 2 and for 2 + S steps (S = --steps), and takes the differences of the two runs' summaries:
time per step and its split (assembly, factorization, solve, output, other), Newton iterations
per step, without the start-up (partition, preallocation, consistent start). Memory is the peak
resident set of the ranks (getrusage) and MUMPS' own figure for its factorization. With
--baseline, the same cases also run with another executable, alternating with this one, so a
change can be compared side by side on this shared, noisy machine (ratios within one run).

Times are wall-clock on a shared 2-core machine: quote ratios, not absolute values.
"""
import argparse
import csv
import datetime
import os
import re
import subprocess
import sys
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "inputs", "gridshell.yaml")
H = 0.01  # the scene's step (s)
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def parse(text):
    """The numbers of an `alphaflex run` summary."""
    def num(pattern, cast=float, default=None):
        m = re.search(pattern, text)
        if not m:
            if default is not None:
                return default
            raise RuntimeError(f"'{pattern}' not in the summary:\n{text}")
        return cast(m.group(1))
    out = {
        "unknowns": num(r"unknowns\s+(\d+)", int),
        "multipliers": num(r"\((?:\d+) coordinates, (\d+) multipliers\)", int),
        "steps": num(r"steps\s+(\d+)", int),
        "newton": num(r"Newton iterations\s+total (\d+)", int),
        "factorizations": num(r"factorizations\s+(\d+) numeric", int),
        "wall": num(r"wall time\s+([\d.]+) s"),
        "mumps_entries": num(r"MUMPS\s+([\d.e+]+) entries", float, 0.0),
        "mumps_flops": num(r"entries in the factors, ([\d.e+]+) flop", float, 0.0),
        "mumps_mb": num(r"flop per factorization, ([\d.e+]+) MB in all", float, 0.0),
        "rss_mb": num(r"memory\s+peak ([\d.e+]+) MB resident in all ranks"),
        "rss_max_mb": num(r"MB resident in all ranks \(([\d.e+]+) MB largest rank\)"),
        "scene_mb": num(r"([\d.e+]+) MB of it per rank for the scene's whole model", float, 0.0),
    }
    for phase in ("setup", "assembly", "factorization", "solve", "output", "other"):
        out[phase] = num(rf"\n\s+{phase}\s+([\d.]+) s")
    return out


def run(exe, n, ranks, steps):
    cmd = [exe, "run", SCENE, "-o", os.path.join("/tmp", f"af_bench_{n}_{ranks}"),
           "--set", f"mesh.parameters.n={n}", "--set", f"solver.t_end={steps * H!r}", "--set", "output.every=1",
           "--set", "output.progress=0"]
    if ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)] + cmd
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV)
    total = time.time() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    r = parse(p.stdout)
    r["process"] = total  # includes reading the scene, meshing with gmsh, building the model
    return r


def measure(exe, n, ranks, steps):
    """Per-step figures from the difference of a 2-step and a (2 + steps)-step run."""
    a, b = run(exe, n, ranks, 2), run(exe, n, ranks, 2 + steps)
    d = {k: (b[k] - a[k]) for k in ("newton", "factorizations", "wall", "assembly", "factorization", "solve",
                                    "output", "other")}
    s = b["steps"] - a["steps"]
    row = {"n": n, "ranks": ranks, "unknowns": b["unknowns"], "steps": s,
           "newton_per_step": d["newton"] / s,
           "step_s": d["wall"] / s,
           "us_per_step_per_unknown": 1e6 * d["wall"] / s / b["unknowns"]}
    for phase in ("assembly", "factorization", "solve", "output", "other"):
        row[phase + "_s"] = d[phase] / s
    row["factorization_share"] = d["factorization"] / d["wall"] if d["wall"] > 0 else 0.0
    row["iteration_over_factor_solve"] = ((d["wall"] / max(d["newton"], 1)) /
                                          ((d["factorization"] + d["solve"]) / max(d["factorizations"], 1)))
    row["setup_s"] = b["setup"]
    row["start_s"] = b["process"] - b["wall"]  # scene, gmsh, model (before the run summary's clock)
    row["rss_mb"] = b["rss_mb"]
    row["rss_max_mb"] = b["rss_max_mb"]
    row["bytes_per_unknown"] = 1e6 * b["rss_mb"] / b["unknowns"]
    row["scene_mb"] = b["scene_mb"]
    row["mumps_mb"] = b["mumps_mb"]
    row["mumps_entries"] = b["mumps_entries"]
    row["mumps_gflop"] = b["mumps_flops"] / 1e9
    return row


def git_revision():
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip() or "unknown"
    except OSError:
        return "unknown"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    ap.add_argument("--baseline", help="another alphaflex executable to run side by side")
    ap.add_argument("--sizes", default="8,16,32,48,64")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--steps", type=int, default=4)
    ap.add_argument("--quick", action="store_true", help="sizes 8,16 only, 2 steps (a check of the script)")
    ap.add_argument("--outdir", default=os.path.join(ROOT, "docs"))
    a = ap.parse_args()
    sizes = [8, 16] if a.quick else [int(s) for s in a.sizes.split(",")]
    ranks = [int(r) for r in a.ranks.split(",")]
    steps = 2 if a.quick else a.steps
    exes = [("this", os.path.abspath(a.exe))] + ([("baseline", os.path.abspath(a.baseline))] if a.baseline else [])

    rows = []
    t_start = time.time()
    for n in sizes:
        for r in ranks:
            for label, exe in exes:  # alternating, so that both see the same machine load
                row = measure(exe, n, r, steps)
                row["exe"] = label
                rows.append(row)
                print(f"{label:8s} n={n:3d} ranks={r} unknowns={row['unknowns']:7d}  {row['step_s']:.3f} s/step  "
                      f"{row['us_per_step_per_unknown']:.2f} us/step/unknown  Newton {row['newton_per_step']:.2f}/step  "
                      f"factorization {100 * row['factorization_share']:.0f} %  rss {row['rss_mb']:.0f} MB", flush=True)

    rev = git_revision()
    date = datetime.date.today().isoformat()
    bench_dir = os.path.join(a.outdir, "benchmarks")
    fig_dir = os.path.join(a.outdir, "figures")
    os.makedirs(bench_dir, exist_ok=True)
    os.makedirs(fig_dir, exist_ok=True)
    # The record: every run appends its rows (revision, date), so later changes can be set side by side.
    record = os.path.join(bench_dir, "performance.csv")
    keys = ["revision", "date", "exe"] + [k for k in rows[0] if k != "exe"]
    new = not os.path.exists(record)
    with open(record, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        if new:
            w.writeheader()
        for row in rows:
            w.writerow(dict(row, revision=rev, date=date))

    this = [r for r in rows if r["exe"] == "this"]
    # Charts: time per step per unknown against unknowns; phase split; strong scaling 1 -> 2 ranks.
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for r in ranks:
        sel = [x for x in this if x["ranks"] == r]
        ax[0].loglog([x["unknowns"] for x in sel], [x["us_per_step_per_unknown"] for x in sel], "o-", label=f"{r} rank(s)")
    ax[0].set_xlabel("unknowns")
    ax[0].set_ylabel("wall time per step per unknown (µs)")
    ax[0].set_title("gridshell: cost per step and unknown")
    ax[0].grid(True, which="both", alpha=0.3)
    ax[0].legend()
    phases = ["assembly", "factorization", "solve", "output", "other"]
    labels = [f"n={x['n']}\n{x['ranks']}r" for x in this]
    bottom = [0.0] * len(this)
    for ph in phases:
        vals = [x[ph + "_s"] / x["step_s"] * 100 for x in this]
        ax[1].bar(range(len(this)), vals, bottom=bottom, label=ph)
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax[1].set_xticks(range(len(this)))
    ax[1].set_xticklabels(labels, fontsize=7)
    ax[1].set_ylabel("share of the step (%)")
    ax[1].set_title("where a step's time goes")
    ax[1].legend(fontsize=7)
    if 1 in ranks and 2 in ranks:
        pairs = [(x, y) for x in this for y in this if x["n"] == y["n"] and x["ranks"] == 1 and y["ranks"] == 2]
        ax[2].semilogx([x["unknowns"] for x, _ in pairs], [x["step_s"] / y["step_s"] for x, y in pairs], "o-",
                       label="whole step")
        ax[2].semilogx([x["unknowns"] for x, _ in pairs], [x["assembly_s"] / y["assembly_s"] for x, y in pairs], "s--",
                       label="assembly")
        ax[2].semilogx([x["unknowns"] for x, _ in pairs],
                       [x["factorization_s"] / y["factorization_s"] for x, y in pairs], "^--", label="factorization")
        ax[2].axhline(2.0, color="k", lw=0.8, ls=":")
        ax[2].set_xlabel("unknowns")
        ax[2].set_ylabel("speed-up, 2 ranks over 1")
        ax[2].set_title("strong scaling on 2 cores")
        ax[2].grid(True, which="both", alpha=0.3)
        ax[2].legend()
    fig.tight_layout()
    chart = os.path.join(fig_dir, "performance_gridshell.png")
    fig.savefig(chart, dpi=110)

    # The page.
    lines = [
        "# Performance",
        "",
        f"Generated by `/usr/bin/python3 scripts/benchmark.py` (alphaflex `{rev}`, {date}, "
        f"{(time.time() - t_start) / 60:.0f} min). Scene `inputs/gridshell.yaml` (flexible laths with swivel joints, "
        "ρ∞ = 0.8, h = 0.01 s) at n laths per direction; every case is the difference of a 2-step and a "
        f"{2 + steps}-step run, so the figures are per time step without the start-up (partition, preallocation, "
        "consistent start). Wall-clock times on a shared 2-core machine: read the ratios. Rows are also appended "
        "to `docs/benchmarks/performance.csv`.",
        "",
        f"![performance](figures/{os.path.basename(chart)})",
        "",
        "| n | ranks | unknowns | s/step | µs/step/unknown | Newton/step | assembly | factorization | solve | output | other | iteration / (factor+solve) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for x in this:
        pct = lambda k: f"{100 * x[k + '_s'] / x['step_s']:.0f} %"  # noqa: E731
        lines.append(f"| {x['n']} | {x['ranks']} | {x['unknowns']} | {x['step_s']:.3f} | {x['us_per_step_per_unknown']:.2f} | "
                     f"{x['newton_per_step']:.2f} | {pct('assembly')} | {pct('factorization')} | {pct('solve')} | "
                     f"{pct('output')} | {pct('other')} | {x['iteration_over_factor_solve']:.2f} |")
    lines += ["", "Memory (peak resident set of all ranks, MUMPS' own figure for its factorization):", "",
              "| n | ranks | unknowns | resident (MB) | largest rank (MB) | bytes/unknown | scene's whole model per rank (MB) | MUMPS (MB) | factor entries | Gflop/factorization | start (s) | setup (s) |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for x in this:
        lines.append(f"| {x['n']} | {x['ranks']} | {x['unknowns']} | {x['rss_mb']:.0f} | {x['rss_max_mb']:.0f} | "
                     f"{x['bytes_per_unknown']:.0f} | {x['scene_mb']:.0f} | {x['mumps_mb']:.0f} | {x['mumps_entries']:.3g} | {x['mumps_gflop']:.3g} | "
                     f"{x['start_s']:.2f} | {x['setup_s']:.2f} |")
    if a.baseline:
        lines += ["", "Side by side with the baseline executable (time per step, this / baseline):", "",
                  "| n | ranks | this (s) | baseline (s) | ratio |", "|---|---|---|---|---|"]
        for x in this:
            b = [y for y in rows if y["exe"] == "baseline" and y["n"] == x["n"] and y["ranks"] == x["ranks"]][0]
            lines.append(f"| {x['n']} | {x['ranks']} | {x['step_s']:.3f} | {b['step_s']:.3f} | {x['step_s'] / b['step_s']:.2f} |")
    notes = os.path.join(a.outdir, "performance_notes.md")
    if os.path.exists(notes):
        lines += ["", open(notes).read().rstrip()]
    with open(os.path.join(a.outdir, "performance.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {os.path.join(a.outdir, 'performance.md')}, {chart}, {record}")


if __name__ == "__main__":
    sys.exit(main())
