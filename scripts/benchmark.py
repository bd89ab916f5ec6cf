#!/usr/bin/python3
"""Performance benchmarks of alphaflex, written to docs/performance.md with charts in docs/figures/
and every measured row appended to docs/benchmarks/performance.csv (the regression record).

    /usr/bin/python3 scripts/benchmark.py [--exe build/alphaflex] [--no-build]
                                          [--cases andrews,small,newton_default,beam,gridshell,large,policy,model,low_rank]
                                          [--sizes 8,16,32,48,64] [--ranks 1,2] [--baseline OTHER_EXE] [--quick]

Cases (each a section of the page; the targets are those of the issue "speed on one rank"):
  andrews    CPU time to 1e-4 relative error in beta at t = 0.03 s: generalized-alpha (full and
             modified Newton) against SciPy's Radau on the 7-coordinate formulation, in one study
             (inputs/studies/andrews_speed.yaml; also SUNDIALS IDA for context).
  small      the small-system path: dense LU against MUMPS on Andrews (61 unknowns) and on beams
             of 72 to 306 unknowns (-af_dense_lu 0 forces MUMPS).
  newton_default
             Newton's default (solver.newton.modified: auto) against full and modified Newton per step
             on the slider-crank (18 unknowns: full), Andrews (61) and the flexible-link slider-crank
             (56: modified); ~1 min.
  beam       a flexible beam spun up by a driven revolute joint (inputs/beam_spinup.yaml, spin-up
             in 1 s, rho_inf = 0.8, h = 1e-4 s) at ~1e3 to ~1e4 unknowns: steps measured from a
             checkpoint at t = 0.5 s (the beam in full motion), full and modified Newton.
  gridshell  the large scene inputs/gridshell.yaml at n laths per direction (~48 n^2 unknowns), 1 and
             2 ranks: time per step and its split, Newton iteration against one factorization +
             solve, memory per unknown, strong scaling; modified Newton on one rank.
  large      gridshell at n = 144 (~1e6 unknowns), 2 ranks, one step: does it fit in memory.
  policy     modified against full Newton on every scene of inputs/ (scripts/modified_newton_policy.py,
             ~5 min on a quiet machine)
  model      the performance model past this machine, calibrated on gridshell n = 12-24 on 1-3 ranks
             (scripts/performance_model.py, ~3 min on a quiet machine)
  low_rank   MUMPS' block low-rank factorization (solver.linear.low_rank) against the exact one on the
             gridshell and the clamped plate at 1e5-1e6 unknowns (scripts/low_rank_benchmark.py,
             ~1 h on a quiet machine; run alone: --cases low_rank --no-build)

It first builds build/alphaflex in Release (unless --no-build or another --exe). Every per-step
figure is the difference of two runs of 2 and 2 + S steps, so start-up (mesh,
partition, preallocation, consistent start) is not in it. With --baseline, the gridshell and
beam cases also run with another executable, alternating with this one, so a change can be set
side by side in one run. Times are wall-clock on a shared 2-core machine: read the ratios.
"""
import argparse
import csv
import datetime
import math
import os
import subprocess
import sys
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
import alphaflex_results as ar  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
PHASES = ("assembly", "factorization", "solve", "output", "other")


def parse(outdir, scene):
    """The numbers of an `alphaflex run` summary (OUTDIR/NAME.summary.json, python/alphaflex_results.py)."""
    j = ar.load_summary(outdir, os.path.splitext(os.path.basename(scene))[0])
    mumps = j.get("mumps", {})
    wall = j["wall_time"]
    out = {
        "unknowns": j["unknowns"],
        "steps": j["steps"],
        "newton": j["newton"]["total"],
        "factorizations": j["factorizations"]["numeric"],
        "wall": wall["s"],
        "mumps_entries": mumps.get("factor_entries", 0.0),
        "mumps_flops": mumps.get("flops_per_factorization", 0.0),
        "mumps_mb": mumps.get("memory_mb_all_ranks", 0.0),
        "rss_mb": j["memory_mb"]["peak_all_ranks"],
        "rss_max_mb": j["memory_mb"]["peak_largest_rank"],
        "scene_mb": j["memory_mb"].get("scene_per_rank", 0.0),
        "checkpoint_mb": j["checkpoints"]["bytes_each"] / 1e6 if j["checkpoints"]["written"] else 0.0,
        "checkpoint_s": wall["checkpoints"]["s"],
        "dense": j["linear_solver"]["dense"],
    }
    for phase in ("setup",) + PHASES:
        out[phase] = wall[phase]["s"]
    return out


def replace_between_markers(begin, end, text):
    """Puts `text` between the lines `begin` and `end` of docs/performance_notes.md (the hand-written
    part, which this script copies under its tables) and of docs/performance.md (the copy), so
    that scripts measuring one section (modified_newton_policy.py, performance_model.py) and a
    regeneration by this script keep each other's results."""
    for name in ("performance_notes.md", "performance.md"):
        path = os.path.join(ROOT, "docs", name)
        with open(path) as fh:
            doc = fh.read()
        if begin not in doc or end not in doc:
            raise SystemExit(f"{path}: no markers {begin} … {end}")
        head, rest = doc.split(begin, 1)
        _, tail = rest.split(end, 1)
        with open(path, "w") as fh:
            fh.write(head + begin + "\n" + text + "\n" + end + tail)


def alphaflex(exe, scene, outdir, sets, ranks=1, extra=()):
    cmd = [exe, "run", scene, "-o", outdir]
    for s in sets:
        cmd += ["--set", s]
    cmd += list(extra)
    if ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)] + cmd
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV)
    total = time.time() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    r = parse(outdir, scene)
    r["process"] = total  # includes reading the scene, meshing with gmsh, building the model
    return r


def differential(a, b):
    """Per-step figures from two runs that differ only in their number of steps."""
    s = b["steps"] - a["steps"]
    d = {k: (b[k] - a[k]) for k in ("newton", "factorizations", "wall") + PHASES}
    row = {"unknowns": b["unknowns"], "steps": s, "newton_per_step": d["newton"] / s,
           "factorizations_per_step": d["factorizations"] / s, "step_s": d["wall"] / s,
           "us_per_step_per_unknown": 1e6 * d["wall"] / s / b["unknowns"]}
    for phase in PHASES:
        row[phase + "_s"] = d[phase] / s
    row["factorization_share"] = d["factorization"] / d["wall"] if d["wall"] > 0 else 0.0
    # One Newton iteration (the step without its output) against one numeric factorization + solve
    # of the same matrix.
    per_iteration = (d["wall"] - d["output"]) / max(d["newton"], 1)
    per_factor_solve = d["factorization"] / max(d["factorizations"], 1) + d["solve"] / max(d["newton"], 1)
    row["iteration_over_factor_solve"] = per_iteration / per_factor_solve if per_factor_solve > 0 else float("nan")
    for k in ("rss_mb", "rss_max_mb", "scene_mb", "mumps_mb", "mumps_entries", "checkpoint_mb", "checkpoint_s", "setup"):
        row[k] = b[k]
    row["bytes_per_unknown"] = 1e6 * b["rss_mb"] / b["unknowns"]
    row["mumps_gflop"] = b["mumps_flops"] / 1e9
    row["start_s"] = b["process"] - b["wall"]
    return row


def pct(x, k):
    """Share of a phase in the step. A phase that does not grow with the steps (e.g. the one
    factorization modified Newton keeps for the whole run) has a difference within timing noise,
    possibly negative: shown as ~0."""
    if x["step_s"] <= 0:
        return "–"
    v = 100 * x[k + "_s"] / x["step_s"]
    return f"{v:.0f} %" if v >= 0.5 else "~0 %"


# ---------------------------------------------------------------------------------------------
# andrews: generalized-alpha against SciPy's Radau at 1e-4 in beta
def cpu_at(rows, err_key, target):
    """CPU at error `target`, log-log interpolated between the two runs that bracket it (runs in
    order of increasing cost); None if no run reaches it."""
    pts = sorted((float(r["cpu"]), float(r[err_key])) for r in rows if r.get("status", "ok") == "ok"
                 and r[err_key] not in ("", "nan"))
    for (c0, e0), (c1, e1) in zip(pts, pts[1:]):
        if e0 > target >= e1:
            w = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(c0) + w * (math.log(c1) - math.log(c0)))
    reached = [c for c, e in pts if e <= target]
    return min(reached) if reached else None


def case_andrews(exe, work):
    out = os.path.join(work, "andrews_speed")
    cmd = [exe, "study", os.path.join(ROOT, "inputs", "andrews.yaml"), "--study",
           os.path.join(ROOT, "inputs", "studies", "andrews_speed.yaml"), "-o", out, "--set", "study.plots=off"]
    p = subprocess.run(cmd, capture_output=True, text=True, env=ENV)
    if p.returncode != 0:
        # The study file has no `plots` key in older versions: retry without the override.
        p = subprocess.run(cmd[:-2], capture_output=True, text=True, env=ENV)
        if p.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed:\n{p.stdout}\n{p.stderr}")
    with open(os.path.join(out, "andrews_speed_study.csv")) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    labels = []
    for r in rows:
        if r["label"] not in labels:
            labels.append(r["label"])
    result = {"rows": rows, "labels": labels, "cpu_at": {}}
    for lab in labels:
        sel = [r for r in rows if r["label"] == lab]
        result["cpu_at"][lab] = cpu_at(sel, "err_beta", 1e-4)
    return result


def section_andrews(res, fig_dir):
    rows, labels = res["rows"], res["labels"]
    fig, ax = plt.subplots(figsize=(7, 5))
    for lab in labels:
        sel = sorted(((float(r["cpu"]), float(r["err_beta"])) for r in rows if r["label"] == lab and r["err_beta"]))
        ax.loglog([c for c, _ in sel], [e for _, e in sel], "o-", label=lab)
    ax.axhline(1e-4, color="k", lw=0.8, ls=":")
    ax.set_xlabel("CPU time (s)")
    ax.set_ylabel("relative error in β at t = 0.03 s")
    ax.set_title("Andrews' mechanism: error against CPU time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    chart = os.path.join(fig_dir, "performance_andrews.png")
    fig.savefig(chart, dpi=110)
    plt.close(fig)
    radau = [lab for lab in labels if "Radau" in lab]
    best_ga = min(((res["cpu_at"][lab], lab) for lab in labels if lab.startswith("GA") and res["cpu_at"][lab]),
                  default=(None, None))
    full = res["cpu_at"].get("GA rho_inf=0.7")
    r_cpu = res["cpu_at"][radau[0]] if radau else None
    lines = ["## 1. Small rigid mechanism: Andrews against SciPy's Radau", "",
             "`build/alphaflex study inputs/andrews.yaml --study inputs/studies/andrews_speed.yaml` — the paper's "
             "absolute coordinates (61 unknowns), errors against the independent DOP853 solution; Radau (and IDA) on "
             "the test set's 7 relative coordinates in the same study, CPU time of each run (process CPU around the "
             "integration, interpreter and process start not counted, for all of them).", "",
             f"![Andrews work-precision](figures/{os.path.basename(chart)})", "",
             "| method | CPU to 1e-4 in β (interpolated) |", "|---|---|"]
    for lab in labels:
        c = res["cpu_at"][lab]
        lines.append(f"| {lab} | {'not reached' if c is None else f'{1e3 * c:.1f} ms'} |")
    lines += ["", "| method | h or tol | steps | Newton/step | CPU (ms) | µs/step | error in β |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        hs = f"h = {float(r['h']):.3g}" if r["h"] else f"tol = {float(r['tol']):.0e}"
        nm = f"{float(r['newton_mean']):.2f}" if r["newton_mean"] else "–"
        cps = f"{1e6 * float(r['cpu']) / float(r['steps']):.0f}" if r["steps"] and float(r["steps"]) > 0 else "–"
        lines.append(f"| {r['label']} | {hs} | {r['steps']} | {nm} | {1e3 * float(r['cpu']):.1f} | {cps} | {float(r['err_beta']):.2e} |")
    target = {"name": "Andrews: 1e-4 in β in less CPU than SciPy Radau"}
    if best_ga[0] and r_cpu:
        target["met"] = best_ga[0] < r_cpu
        target["figure"] = (f"{1e3 * best_ga[0]:.1f} ms ({best_ga[1]}) against {1e3 * r_cpu:.0f} ms (Radau): "
                            f"{r_cpu / best_ga[0]:.1f}× less; full Newton {1e3 * full:.1f} ms ({r_cpu / full:.1f}×)"
                            if full else "")
    else:
        target["met"] = False
        target["figure"] = "not reached"
    return lines, target


# ---------------------------------------------------------------------------------------------
# small: dense LU against MUMPS
def case_small(exe, work):
    rows = []
    andrews = os.path.join(ROOT, "inputs", "andrews.yaml")
    beam = os.path.join(ROOT, "inputs", "beam_spinup.yaml")
    # Full Newton (one factorization per iteration), as these rows have been measured from the
    # start: they compare the factorizations of the two paths.
    cases = [("andrews", andrews, ["output.hdf5=off", "solver.newton.modified=off"], 0.03 / 100, 100)]
    for el in (11, 17, 26, 34, 50):
        cases.append((f"beam {el} elements", beam, [f"mesh.elements={el}", "parameters.Ts=1", "output.hdf5=off",
                                                   "solver.h=1e-3", "solver.newton.modified=off"], 1e-3, 200))
    for name, scene, sets, h, steps in cases:
        for path, extra in (("dense", ()), ("MUMPS", ("-af_dense_lu", "0"))):
            a = alphaflex(exe, scene, os.path.join(work, "small"), sets + [f"solver.t_end={2 * h!r}"], extra=extra)
            b = alphaflex(exe, scene, os.path.join(work, "small"), sets + [f"solver.t_end={(2 + steps) * h!r}"], extra=extra)
            row = differential(a, b)
            row.update(case=name, path=path if (b["dense"] or path == "MUMPS") else "MUMPS (above the limit)")
            rows.append(row)
            print(f"small {name:18s} {row['path']:8s} {row['unknowns']:5d} unknowns  {1e6 * row['step_s']:.0f} us/step",
                  flush=True)
    return rows


def section_small(rows):
    lines = ["## Small systems: dense LU against MUMPS", "",
             "Per step (difference of two runs), one rank; `-af_dense_lu 0` forces MUMPS. The dense path is taken up to "
             "`LinearSolver::kDenseLimit` = 200 unknowns by default (LAPACK's getrf on the installed BLAS).", "",
             "| case | unknowns | dense (µs/step) | MUMPS (µs/step) | MUMPS / dense | factorization share, dense / MUMPS |",
             "|---|---|---|---|---|---|"]
    for name in dict.fromkeys(r["case"] for r in rows):
        d = [r for r in rows if r["case"] == name and r["path"] == "dense"]
        m = [r for r in rows if r["case"] == name and r["path"] == "MUMPS"]
        if not m:
            continue
        m = m[0]
        if d:
            d = d[0]
            lines.append(f"| {name} | {m['unknowns']} | {1e6 * d['step_s']:.0f} | {1e6 * m['step_s']:.0f} | "
                         f"{m['step_s'] / d['step_s']:.2f} | {100 * d['factorization_share']:.0f} % / "
                         f"{100 * m['factorization_share']:.0f} % |")
        else:
            lines.append(f"| {name} | {m['unknowns']} | (MUMPS above the limit) | {1e6 * m['step_s']:.0f} | – | – |")
    return lines


# ---------------------------------------------------------------------------------------------
# newton_default: the default Newton method (solver.newton.modified: auto) against both explicit
# settings, per step, on one scene below and two above its threshold, and one below it with a reduced
# body, which the default takes with modified Newton too (seconds, not minutes)
NEWTON_DEFAULT_CASES = [
    ("slider-crank (below the threshold)", "slider_crank.yaml", [], 5e-4, 1000),
    ("flexible arm with payload (below, a reduced body)", "flexible_arm_payload.yaml", [], 1e-3, 1000),
    ("Andrews (above)", "andrews.yaml", [], 0.03 / 100, 100),
    ("flexible slider-crank links (above)", "slider_crank_flexible_links.yaml", [], 1e-3, 400),
]


def case_newton_default(exe, work, repeat=3):
    """The three settings alternated `repeat` times; each keeps its median per-step figure (these
    runs last about a second, so the load of the machine is most of their spread)."""
    rows = []
    for name, scene_file, sets, h, steps in NEWTON_DEFAULT_CASES:
        scene = os.path.join(ROOT, "inputs", scene_file)
        best = {}
        for newton, key in [(n, k) for _ in range(repeat) for n, k in
                            (("full", ["solver.newton.modified=off"]), ("modified", ["solver.newton.modified=on"]),
                             ("default", []))]:
            base = sets + key + ["output.hdf5=off", "output.checkpoint_at_end=off", "output.progress=0",
                                 f"solver.h={h!r}"]
            stem = os.path.splitext(scene_file)[0]
            out = os.path.join(work, "newton_default_" + stem)
            a = alphaflex(exe, scene, out, base + [f"solver.t_end={2 * h!r}"])
            b = alphaflex(exe, scene, out, base + [f"solver.t_end={(2 + steps) * h!r}"])
            row = differential(a, b)
            # Which method the default took: the summary reports modified Newton's counters only
            # when it ran (summary_json.cpp).
            took = "modified" if "modified_newton" in ar.load_summary(out, stem) else "full"
            row.update(case="newton_default", exe="this", n=name, ranks=1,
                       newton=newton if newton != "default" else f"default ({took})")
            best.setdefault(newton, []).append(row)
        for runs in best.values():
            row = sorted(runs, key=lambda r: r["step_s"])[len(runs) // 2]
            rows.append(row)
            print(f"newton_default {name:38s} {row['newton']:20s} {row['unknowns']:5d} unknowns "
                  f"{1e6 * row['step_s']:.0f} us/step  Newton {row['newton_per_step']:.2f}/step", flush=True)
    return rows


def section_newton_default(rows):
    lines = ["## Newton's default: `solver.newton.modified: auto`", "",
             "Per step (difference of two runs), one rank: full Newton, modified Newton and the default, which takes "
             "modified Newton from `solver.newton.modified_from` = 30 unknowns or for a model with a reduced body or a "
             "joint motor that reads sensors (the measurements on every scene: "
             "section \"Modified Newton by default\" below).", "",
             "| scene | unknowns | full (µs/step) | modified (µs/step) | default (µs/step) | default took | full / default |",
             "|---|---:|---:|---:|---:|---|---:|"]
    for name in dict.fromkeys(r["n"] for r in rows):
        sel = {r["newton"].split(" ")[0]: r for r in rows if r["n"] == name}
        d = sel["default"]
        lines.append(f"| {name} | {d['unknowns']} | {1e6 * sel['full']['step_s']:.0f} | {1e6 * sel['modified']['step_s']:.0f} "
                     f"| {1e6 * d['step_s']:.0f} | {d['newton'][9:-1]} | {sel['full']['step_s'] / d['step_s']:.2f} |")
    return lines


# ---------------------------------------------------------------------------------------------
# beam: a flexible beam in motion, 1e3 - 1e4 unknowns
BEAM_H = 1e-4
BEAM_SETS = ["parameters.Ts=1", "solver.rho_inf=0.8", "output.hdf5=off", "output.progress=0"]


def case_beam(exes, work, elements, steps):
    scene = os.path.join(ROOT, "inputs", "beam_spinup.yaml")
    rows = []
    for el in elements:
        for label, exe in exes:
            # The state at t = 0.5 s (hub at 1.3 rad, beam lagging and bending): a coarse run writes its checkpoint.
            ckdir = os.path.join(work, f"beam_ck_{el}_{label}")
            alphaflex(exe, scene, ckdir, BEAM_SETS + [f"mesh.elements={el}", "solver.h=2.5e-3", "solver.t_end=0.5"])
            ck = os.path.join(ckdir, "beam_spinup.checkpoint.h5")
            for newton in ("full", "modified"):
                sets = BEAM_SETS + [f"mesh.elements={el}", f"solver.h={BEAM_H!r}",
                                    f"solver.newton.modified={'on' if newton == 'modified' else 'off'}"]
                a = alphaflex(exe, scene, os.path.join(work, "beam_run"), sets + [f"solver.t_end={0.5 + 2 * BEAM_H!r}"],
                              extra=("--restart", ck))
                b = alphaflex(exe, scene, os.path.join(work, "beam_run"),
                              sets + [f"solver.t_end={0.5 + (2 + steps) * BEAM_H!r}"], extra=("--restart", ck))
                row = differential(a, b)
                row.update(case="beam", elements=el, newton=newton, exe=label, n=el, ranks=1)
                rows.append(row)
                print(f"beam {label:8s} {el:5d} elements {row['unknowns']:6d} unknowns {newton:8s} "
                      f"{row['us_per_step_per_unknown']:.2f} us/step/unknown  Newton {row['newton_per_step']:.2f}/step",
                      flush=True)
    return rows


def section_beam(rows, fig_dir):
    this = [r for r in rows if r["exe"] == "this"]
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for newton in ("full", "modified"):
        sel = [x for x in this if x["newton"] == newton]
        ax[0].loglog([x["unknowns"] for x in sel], [x["us_per_step_per_unknown"] for x in sel], "o-",
                     label=f"{newton} Newton")
    ax[0].axhline(2.0, color="k", lw=0.8, ls=":")
    ax[0].set_xlabel("unknowns")
    ax[0].set_ylabel("wall time per step per unknown (µs)")
    ax[0].set_title("flexible beam in motion, h = 1e-4 s")
    ax[0].grid(True, which="both", alpha=0.3)
    ax[0].legend()
    labels = [f"{x['unknowns']}\n{x['newton'][:4]}" for x in this]
    bottom = [0.0] * len(this)
    for ph in PHASES:
        vals = [1e6 * x[ph + "_s"] / x["unknowns"] for x in this]
        ax[1].bar(range(len(this)), vals, bottom=bottom, label=ph)
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax[1].set_xticks(range(len(this)))
    ax[1].set_xticklabels(labels, fontsize=7)
    ax[1].set_ylabel("µs per step per unknown")
    ax[1].set_title("split by phase")
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    chart = os.path.join(fig_dir, "performance_beam.png")
    fig.savefig(chart, dpi=110)
    plt.close(fig)
    lines = ["## 2. Flexible beam in motion: µs per step per unknown", "",
             "`inputs/beam_spinup.yaml` with `mesh.elements` = N (geometrically exact beam, 6 N + 12 unknowns with the 6 "
             "multipliers of the driven revolute joint), spin-up in 1 s, ρ∞ = 0.8, h = 1e-4 s; the steps are measured "
             "after a restart from a checkpoint at t = 0.5 s (written by a run at h = 2.5e-3 s), where the beam turns at "
             "3 rad/s, lags and bends. Element evaluation is part of assembly.", "",
             f"![beam](figures/{os.path.basename(chart)})", "",
             "| elements | unknowns | Newton | µs/step/unknown | Newton/step | factorizations/step | assembly | factorization | solve | output | other |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for x in this:
        lines.append(f"| {x['elements']} | {x['unknowns']} | {x['newton']} | {x['us_per_step_per_unknown']:.2f} | "
                     f"{x['newton_per_step']:.2f} | {x['factorizations_per_step']:.2f} | {pct(x, 'assembly')} | "
                     f"{pct(x, 'factorization')} | {pct(x, 'solve')} | {pct(x, 'output')} | {pct(x, 'other')} |")
    sel = [x for x in this if 1e3 <= x["unknowns"] <= 1.2e4]
    best = {nt: max((x["us_per_step_per_unknown"] for x in sel if x["newton"] == nt), default=float("nan"))
            for nt in ("full", "modified")}
    target = {"name": "Beam, 1e3–1e4 unknowns: ≤ 2 µs per step per unknown",
              "met": best["modified"] <= 2.0 or best["full"] <= 2.0,
              "figure": f"worst over the sizes: {best['full']:.2f} (full Newton), {best['modified']:.2f} (modified Newton)"}
    return lines, target


# ---------------------------------------------------------------------------------------------
# gridshell: the large scene
GRID_H = 0.01


def case_gridshell(exes, work, sizes, ranks, steps, modified_sizes):
    scene = os.path.join(ROOT, "inputs", "gridshell.yaml")
    rows = []
    for n in sizes:
        for r in ranks:
            variants = ["full"] + (["modified"] if (r == 1 and n in modified_sizes) else [])
            for newton in variants:
                for label, exe in exes:  # alternating, so that both see the same machine load
                    sets = [f"mesh.parameters.n={n}", "output.every=1", "output.progress=0",
                            f"solver.newton.modified={'on' if newton == 'modified' else 'off'}"]
                    a = alphaflex(exe, scene, os.path.join(work, f"grid_{n}_{r}"), sets + [f"solver.t_end={2 * GRID_H!r}"], r)
                    b = alphaflex(exe, scene, os.path.join(work, f"grid_{n}_{r}"),
                                  sets + [f"solver.t_end={(2 + steps) * GRID_H!r}"], r)
                    row = differential(a, b)
                    row.update(case="gridshell", n=n, ranks=r, newton=newton, exe=label)
                    rows.append(row)
                    print(f"gridshell {label:8s} n={n:3d} ranks={r} {newton:8s} unknowns={row['unknowns']:7d}  "
                          f"{row['step_s']:.3f} s/step  {row['us_per_step_per_unknown']:.2f} us/step/unknown  Newton "
                          f"{row['newton_per_step']:.2f}/step  factorization {100 * row['factorization_share']:.0f} %  "
                          f"iteration/(factor+solve) {row['iteration_over_factor_solve']:.2f}  rss {row['rss_mb']:.0f} MB",
                          flush=True)
    return rows


def section_gridshell(rows, ranks, fig_dir, baseline):
    this = [r for r in rows if r["exe"] == "this" and r["newton"] == "full"]
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for r in ranks:
        sel = [x for x in this if x["ranks"] == r]
        ax[0].loglog([x["unknowns"] for x in sel], [x["us_per_step_per_unknown"] for x in sel], "o-", label=f"{r} rank(s)")
    mod = [x for x in rows if x["exe"] == "this" and x["newton"] == "modified"]
    if mod:
        ax[0].loglog([x["unknowns"] for x in mod], [x["us_per_step_per_unknown"] for x in mod], "s--",
                     label="1 rank, modified Newton")
    ax[0].set_xlabel("unknowns")
    ax[0].set_ylabel("wall time per step per unknown (µs)")
    ax[0].set_title("gridshell: cost per step and unknown")
    ax[0].grid(True, which="both", alpha=0.3)
    ax[0].legend()
    labels = [f"n={x['n']}\n{x['ranks']}r" for x in this]
    bottom = [0.0] * len(this)
    for ph in PHASES:
        vals = [x[ph + "_s"] / x["step_s"] * 100 for x in this]
        ax[1].bar(range(len(this)), vals, bottom=bottom, label=ph)
        bottom = [b + v for b, v in zip(bottom, vals)]
    ax[1].set_xticks(range(len(this)))
    ax[1].set_xticklabels(labels, fontsize=7)
    ax[1].set_ylabel("share of the step (%)")
    ax[1].set_title("where a step's time goes")
    ax[1].legend(fontsize=7)
    pairs = [(x, y) for x in this for y in this if x["n"] == y["n"] and x["ranks"] == 1 and y["ranks"] == 2]
    if pairs:
        u = [x["unknowns"] for x, _ in pairs]
        ax[2].semilogx(u, [x["step_s"] / y["step_s"] for x, y in pairs], "o-", label="whole step")
        ax[2].semilogx(u, [x["assembly_s"] / y["assembly_s"] for x, y in pairs], "s--", label="assembly")
        ax[2].semilogx(u, [x["factorization_s"] / y["factorization_s"] for x, y in pairs], "^--", label="factorization")
        ax[2].axhline(2.0, color="k", lw=0.8, ls=":")
        ax[2].set_xlabel("unknowns")
        ax[2].set_ylabel("speed-up, 2 ranks over 1")
        ax[2].set_title("strong scaling on 2 cores")
        ax[2].grid(True, which="both", alpha=0.3)
        ax[2].legend()
    fig.tight_layout()
    chart = os.path.join(fig_dir, "performance_gridshell.png")
    fig.savefig(chart, dpi=110)
    plt.close(fig)

    lines = ["## 3. The large scene: gridshell", "",
             "`inputs/gridshell.yaml` (flexible laths with swivel joints, ρ∞ = 0.8, h = 0.01 s) at n laths per "
             "direction, output of every step; the last column is the cost of one Newton iteration over that of one "
             "numeric factorization + solve of the same matrix (target ≤ 1.25).", "",
             f"![gridshell](figures/{os.path.basename(chart)})", "",
             "| n | ranks | unknowns | s/step | µs/step/unknown | Newton/step | assembly | factorization | solve | output | other | iteration / (factor+solve) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for x in this:
        lines.append(f"| {x['n']} | {x['ranks']} | {x['unknowns']} | {x['step_s']:.3f} | {x['us_per_step_per_unknown']:.2f} | "
                     f"{x['newton_per_step']:.2f} | {pct(x, 'assembly')} | {pct(x, 'factorization')} | {pct(x, 'solve')} | "
                     f"{pct(x, 'output')} | {pct(x, 'other')} | {x['iteration_over_factor_solve']:.2f} |")
    if pairs:
        lines += ["", "Strong scaling, 1 → 2 ranks on this 2-core machine (time per step, 1 rank / 2 ranks):", "",
                  "| n | unknowns | whole step | assembly | factorization | solve |", "|---|---|---|---|---|---|"]
        for x, y in pairs:
            lines.append(f"| {x['n']} | {x['unknowns']} | {x['step_s'] / y['step_s']:.2f} | {x['assembly_s'] / y['assembly_s']:.2f} | "
                         f"{x['factorization_s'] / y['factorization_s']:.2f} | "
                         f"{(x['solve_s'] / y['solve_s']) if y['solve_s'] > 0 else float('nan'):.2f} |")
    if mod:
        lines += ["", "Modified Newton (`solver.newton.modified: on`) against full Newton, one rank:", "",
                  "| n | unknowns | full (s/step) | modified (s/step) | full / modified | Newton/step, full / modified | factorizations/step, modified |",
                  "|---|---|---|---|---|---|---|"]
        for m in mod:
            f = [x for x in this if x["n"] == m["n"] and x["ranks"] == 1][0]
            lines.append(f"| {m['n']} | {m['unknowns']} | {f['step_s']:.3f} | {m['step_s']:.3f} | {f['step_s'] / m['step_s']:.2f} | "
                         f"{f['newton_per_step']:.2f} / {m['newton_per_step']:.2f} | {m['factorizations_per_step']:.2f} |")
    lines += ["", "Memory (peak resident set of all ranks; MUMPS' own figure for its factorization; the checkpoint "
              "written at the end of the run):", "",
              "| n | ranks | unknowns | resident (MB) | largest rank (MB) | bytes/unknown | scene's whole model per rank (MB) | MUMPS (MB) | factor entries | Gflop/factorization | checkpoint (MB, s) | start (s) | setup (s) |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for x in this:
        lines.append(f"| {x['n']} | {x['ranks']} | {x['unknowns']} | {x['rss_mb']:.0f} | {x['rss_max_mb']:.0f} | "
                     f"{x['bytes_per_unknown']:.0f} | {x['scene_mb']:.0f} | {x['mumps_mb']:.0f} | {x['mumps_entries']:.3g} | "
                     f"{x['mumps_gflop']:.3g} | {x['checkpoint_mb']:.2f}, {x['checkpoint_s']:.3f} | {x['start_s']:.2f} | {x['setup']:.2f} |")
    if baseline:
        lines += ["", "Side by side with the baseline executable (time per step, this / baseline):", "",
                  "| case | n | ranks | Newton | this (s) | baseline (s) | ratio |", "|---|---|---|---|---|---|---|"]
        for x in [r for r in rows if r["exe"] == "this"]:
            b = [y for y in rows if y["exe"] == "baseline" and y["case"] == x["case"] and y["n"] == x["n"]
                 and y["ranks"] == x["ranks"] and y["newton"] == x["newton"]]
            if b:
                lines.append(f"| {x['case']} | {x['n']} | {x['ranks']} | {x['newton']} | {x['step_s']:.4f} | {b[0]['step_s']:.4f} | "
                             f"{x['step_s'] / b[0]['step_s']:.2f} |")
    one = [x for x in this if x["ranks"] == 1]
    largest = max(one, key=lambda x: x["unknowns"]) if one else None
    targets = []
    if largest:
        targets.append({"name": "Large scene: one Newton iteration ≤ 1.25 × (one factorization + solve)",
                        "met": largest["iteration_over_factor_solve"] <= 1.25,
                        "figure": f"{largest['iteration_over_factor_solve']:.2f} at {largest['unknowns']} unknowns, 1 rank "
                                  f"(factorization {100 * largest['factorization_share']:.0f} % of the step)"})
    if mod:
        m = max(mod, key=lambda x: x["unknowns"])
        f = [x for x in this if x["n"] == m["n"] and x["ranks"] == 1][0]
        targets.append({"name": "Modified Newton: time per step gained (large scene, 1 rank)", "met": f["step_s"] > m["step_s"],
                        "figure": f"{f['step_s'] / m['step_s']:.2f}× at {m['unknowns']} unknowns"})
    if largest:
        targets.append({"name": "Memory per unknown reported (large scene)", "met": True,
                        "figure": f"{largest['bytes_per_unknown']:.0f} bytes/unknown resident at {largest['unknowns']} unknowns "
                                  f"(MUMPS {1e6 * largest['mumps_mb'] / largest['unknowns']:.0f} of them)"})
    return lines, targets


def case_large(exe, work, n, ranks):
    scene = os.path.join(ROOT, "inputs", "gridshell.yaml")
    r = alphaflex(exe, scene, os.path.join(work, "large"), [f"mesh.parameters.n={n}", f"solver.t_end={GRID_H!r}",
                                                           "output.progress=0", "solver.newton.modified=off"], ranks)
    r.update(n=n, ranks=ranks)
    print(f"large n={n} ranks={ranks}: {r['unknowns']} unknowns, {r['rss_mb']:.0f} MB, {r['wall']:.1f} s", flush=True)
    return r


def section_large(r):
    ratio = (r["assembly"] + r["factorization"] + r["solve"]) / (r["factorization"] + r["solve"])
    lines = ["## 5. About 10⁶ unknowns on this machine", "",
             f"Gridshell n = {r['n']} on {r['ranks']} ranks, one step of h = 0.01 s with output: {r['unknowns']} unknowns, peak "
             f"resident {r['rss_mb']:.0f} MB in all ranks ({r['rss_max_mb']:.0f} MB largest), {1e6 * r['rss_mb'] / r['unknowns']:.0f} "
             f"bytes per unknown; MUMPS {r['mumps_mb']:.0f} MB, {r['mumps_entries']:.3g} entries in the factors, "
             f"{r['mumps_flops'] / 1e9:.3g} Gflop per factorization; {r['newton']} Newton iterations; wall time of the run "
             f"{r['wall']:.1f} s (setup {r['setup']:.1f} s, assembly {r['assembly']:.1f} s, factorization {r['factorization']:.1f} s, "
             f"solve {r['solve']:.1f} s, output {r['output']:.1f} s), {r['process']:.0f} s with reading and meshing. "
             f"The scene's whole model, which every rank holds, took {r['scene_mb']:.0f} MB per rank "
             f"({1e6 * r['scene_mb'] / r['unknowns']:.0f} bytes per unknown). Over the run's linear systems (consistent "
             f"start and Newton iterations alike), assembly + factorization + solve over factorization + solve is "
             f"{ratio:.2f}."]
    targets = [{"name": "10⁶ unknowns fit in 24 GiB", "met": r["rss_mb"] < 24 * 1024,
                "figure": f"{r['unknowns']} unknowns in {r['rss_mb'] / 1024:.1f} GiB on 2 ranks, {r['wall']:.0f} s for the run of one step"},
               {"name": "At ~10⁶ unknowns: a linear system ≤ 1.25 × (factorization + solve)", "met": ratio <= 1.25,
                "figure": f"{ratio:.2f} at {r['unknowns']} unknowns, 2 ranks"}]
    return lines, targets


def git_revision():
    try:
        return subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip() or "unknown"
    except OSError:
        return "unknown"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    ap.add_argument("--baseline", help="another alphaflex executable to run side by side (gridshell and beam cases)")
    ap.add_argument("--cases", default="andrews,small,newton_default,beam,gridshell,large,policy,model,low_rank")
    ap.add_argument("--sizes", default="8,16,32,48,64")
    ap.add_argument("--modified-sizes", default="32,64", help="gridshell sizes also run with modified Newton (1 rank)")
    ap.add_argument("--beam-elements", default="170,500,1000,1700")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--steps", type=int, default=4, help="gridshell: steps measured (beam: 10x as many)")
    ap.add_argument("--large-n", type=int, default=144)
    ap.add_argument("--quick", action="store_true", help="small sizes, few steps (a check of the script)")
    ap.add_argument("--outdir", default=os.path.join(ROOT, "docs"))
    ap.add_argument("--no-build", action="store_true",
                    help="do not (re)build the Release executable in build/ first (default: build it when --exe is the default)")
    a = ap.parse_args()
    if not a.no_build and os.path.abspath(a.exe) == os.path.join(ROOT, "build", "alphaflex"):
        # The figures are of a Release build: configure and build it (incremental when it exists).
        for cmd in (["cmake", "-S", ROOT, "-B", os.path.join(ROOT, "build"), "-DCMAKE_BUILD_TYPE=Release"],
                    ["cmake", "--build", os.path.join(ROOT, "build"), "-j", str(os.cpu_count() or 2), "--target",
                     "alphaflex_exe"]):
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit(f"{' '.join(cmd)} failed:\n{p.stdout}\n{p.stderr}")
    cases = a.cases.split(",")
    sizes = [8, 16] if a.quick else [int(s) for s in a.sizes.split(",")]
    modified_sizes = [16] if a.quick else [int(s) for s in a.modified_sizes.split(",")]
    elements = [170, 340] if a.quick else [int(s) for s in a.beam_elements.split(",")]
    ranks = [int(r) for r in a.ranks.split(",")]
    steps = 2 if a.quick else a.steps
    exes = [("this", os.path.abspath(a.exe))] + ([("baseline", os.path.abspath(a.baseline))] if a.baseline else [])
    work = "/tmp/af_bench"
    os.makedirs(work, exist_ok=True)

    rev = git_revision()
    date = datetime.date.today().isoformat()
    bench_dir = os.path.join(a.outdir, "benchmarks")
    fig_dir = os.path.join(a.outdir, "figures")
    os.makedirs(bench_dir, exist_ok=True)
    os.makedirs(fig_dir, exist_ok=True)
    t_start = time.time()
    sections, targets, record_rows = [], [], []

    if "andrews" in cases:
        res = case_andrews(exes[0][1], work)
        lines, t = section_andrews(res, fig_dir)
        sections.append(lines)
        targets.append(t)
        for lab, c in res["cpu_at"].items():
            record_rows.append({"case": "andrews", "exe": "this", "newton": lab, "cpu_to_1e-4": c})
    if "beam" in cases:
        rows = case_beam(exes, work, elements, 10 * steps)
        lines, t = section_beam(rows, fig_dir)
        sections.append(lines)
        targets.append(t)
        record_rows += rows
    if "gridshell" in cases:
        rows = case_gridshell(exes, work, sizes, ranks, steps, modified_sizes)
        lines, ts = section_gridshell(rows, ranks, fig_dir, a.baseline)
        sections.append(lines)
        targets += ts
        record_rows += rows
    if "large" in cases and not a.quick:
        r = case_large(exes[0][1], work, a.large_n, 2)
        lines, ts = section_large(r)
        sections.append(lines)
        targets += ts
        record_rows.append({"case": "large", "exe": "this", "n": r["n"], "ranks": r["ranks"], "unknowns": r["unknowns"],
                            "rss_mb": r["rss_mb"], "mumps_mb": r["mumps_mb"], "step_s": r["wall"]})
    # The sections of the hand-written notes that scripts of their own measure (issue 22): they
    # write between their markers in docs/performance_notes.md, which is copied below.
    for case, script in (("policy", "modified_newton_policy.py"), ("model", "performance_model.py"),
                         ("low_rank", "low_rank_benchmark.py")):
        if case in cases:
            subprocess.run([sys.executable, os.path.join(ROOT, "scripts", script), "--exe", exes[0][1]], cwd=ROOT, env=ENV,
                           check=True)
    if "small" in cases:
        rows = case_small(exes[0][1], work)
        sections.append(section_small(rows))
        record_rows += rows
    if "newton_default" in cases:
        rows = case_newton_default(exes[0][1], work)
        sections.append(section_newton_default(rows))
        record_rows += rows

    # The record: every run appends its rows (revision, date), so later changes can be set side by side.
    record = os.path.join(bench_dir, "performance.csv")
    keys = ["revision", "date", "case", "exe", "n", "ranks", "newton", "elements", "unknowns", "steps", "step_s",
            "us_per_step_per_unknown", "newton_per_step", "factorizations_per_step"] + [p + "_s" for p in PHASES] + [
            "factorization_share", "iteration_over_factor_solve", "rss_mb", "bytes_per_unknown", "mumps_mb",
            "mumps_gflop", "checkpoint_mb", "checkpoint_s", "cpu_to_1e-4", "path"]
    new = not os.path.exists(record)
    with open(record, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        if new:
            w.writeheader()
        for row in record_rows:
            w.writerow(dict(row, revision=rev, date=date))

    lines = ["# Performance", "",
             f"Generated by `/usr/bin/python3 scripts/benchmark.py` (alphaflex `{rev}`, {date}, "
             f"{(time.time() - t_start) / 60:.0f} min, Release build). Per-step figures are differences of two runs "
             "(2 and 2 + S steps), so start-up is not in them. Wall-clock times on a shared 2-core machine: read the "
             "ratios. Every row is also appended to `docs/benchmarks/performance.csv`; `--baseline OTHER_EXE` runs "
             "another build side by side.", "",
             "## Targets", "", "| target | met | measured |", "|---|---|---|"]
    for t in targets:
        lines.append(f"| {t['name']} | {'yes' if t['met'] else '**no**'} | {t['figure']} |")
    for s in sections:
        lines += [""] + s
    notes = os.path.join(a.outdir, "performance_notes.md")
    if os.path.exists(notes):
        lines += ["", open(notes).read().rstrip()]
    with open(os.path.join(a.outdir, "performance.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {os.path.join(a.outdir, 'performance.md')}, charts in {fig_dir}, {record}")


if __name__ == "__main__":
    sys.exit(main())
