#!/usr/bin/python3
"""A performance model of one time step of the gridshell past this machine (issue 22), calibrated
here on 1, 2 and 3 ranks, predicting the time per step and the memory per rank at 8-256 ranks for
1e6-1e8 unknowns. Writes a table and a chart into docs/performance.md (between the markers of the
section "Past this machine") and the calibration to docs/benchmarks/performance_model.json.

    /usr/bin/python3 scripts/performance_model.py [--exe build/alphaflex] [--sizes 12,16,24]
                                                  [--ranks 1,2,3] [--reuse] [--no-doc]

Calibration: inputs/gridshell.yaml at n laths per direction, each (n, ranks) run twice, with 2 and
4 steps (h = 0.01 s, output of every step), and the per-step figures are the differences
(scripts/benchmark.py's method: start-up, meshing and the consistent start cancel). One more
one-rank run per size with MUMPS' statistics printed (-mat_mumps_icntl_4 2) gives the largest front
(the root separator). --reuse reads the calibration JSON instead of running.

The model (every assumption named in ASSUMED, printed with the table):
  step         = N_it (assembly + factorization + solve + ghost exchange + reductions) + output
                 (full Newton, one factorization per iteration; modified Newton: N_it' iterations,
                 f' factorizations per step, measured on the gridshell in docs/performance.md)
  assembly     = a N / p                   (a: s per unknown and iteration, measured on 1 rank)
  factorization= F(N) / (p R)              F = c_F N^1.5 (nested dissection on a 2-D mesh: George
                                           1973), c_F from the measured flops (RINFOG(3)); R the
                                           flop rate of one core measured on 1 rank
               + contribution blocks       the fronts of the top log2 p levels of the tree send
                                           their Schur complements to the ranks of their parent:
                                           8 s_l^2 bytes at level l, s_l = c_s sqrt(N / 2^l), over
                                           the network (bandwidth B per rank)
               + dense root front          s_r = c_s sqrt(N) rows on all p ranks (ScaLAPACK, 2-D
                                           block cyclic, block nb): 8 s_r^2 / sqrt(p) bytes per rank
                                           and 3 (s_r / nb) log2 p messages of latency L
  solve        = 2 x 8 E(N) / (p M)        E = c_E N log2 N factor entries, M the memory
                                           bandwidth of one core measured by the 1-rank solve
               + 2 log2 p levels x L
  ghost        = 3 scatters x (6 L + 8 x 6 g / B), g = c_g sqrt(N / p) ghost nodes per rank
                                           (c_g fitted on the 2- and 3-rank partitions)
  reductions   = 4 x 2 log2 p x L          (the Newton norms, per iteration)
  output       = b N / W                   (b bytes per unknown of the fields, measured; W the
                                           file system's aggregate bandwidth, shared by all ranks)
  memory/rank  = libraries + m_scene N     (the scene's whole model, replicated on every rank)
               + m_dist N / p              (matrix, vectors, assembly maps: measured on 1 rank)
               + k_M 8 E(N) / p            (MUMPS: factors and work space, k_M measured)
               + 440 N bytes on rank 0     (MUMPS' sequential analysis, ICNTL(28) = 1, PETSc's
                                           default: the whole pattern on the host)
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchmark as bm  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = bm.ROOT
CALIBRATION = os.path.join(ROOT, "docs", "benchmarks", "performance_model.json")
FIGURE = os.path.join(ROOT, "docs", "figures", "performance_model.png")
BEGIN = "<!-- performance_model: begin -->"
END = "<!-- performance_model: end -->"

# Values that this machine cannot measure, named (a cluster with an InfiniBand HDR-100-class network
# and a parallel file system).
ASSUMED = {
    "latency_s": 2e-6,            # L: MPI latency between nodes
    "bandwidth_Bps": 10e9,        # B: network bandwidth per rank's link (HDR-100: 12.5 GB/s)
    "filesystem_Bps": 5e9,        # W: aggregate parallel file system bandwidth, all ranks together
    "memory_per_rank_GB": 4.0,    # a node of 128 GB with 32 cores, one rank per core
    "scalapack_block": 64,        # nb of the root front's 2-D block-cyclic layout
    "newton_full": 3.5,           # iterations per step, full Newton (measured: 3.5-4 at all sizes)
    "newton_modified": 5.75,      # modified Newton: iterations and factorizations per step on the
    "factorizations_modified": 0.25,  # gridshell at 2.2e5 unknowns (docs/performance.md)
    "flop_exponent": 1.5,         # nested dissection on a 2-D mesh (George 1973): F ~ N^1.5
    # MUMPS' sequential analysis gathers the matrix pattern on rank 0: ~55 nonzeros per row
    # (measured on the gridshell), two 4-byte indices each.
    "analysis_host_B_per_unknown": 440.0,
}
SIZES = (1e6, 1e7, 1e8)
RANKS = (8, 16, 32, 64, 128, 256)


def calibrate(exe, sizes, ranks):
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for n in sizes:
            for p in ranks:
                base = [f"mesh.parameters.n={n}", "output.every=1", "output.checkpoint_at_end=off"]
                a = bm.alphaflex(exe, "inputs/gridshell.yaml", os.path.join(work, f"a{n}_{p}"), base + ["solver.t_end=0.02"], p)
                b = bm.alphaflex(exe, "inputs/gridshell.yaml", os.path.join(work, f"b{n}_{p}"), base + ["solver.t_end=0.04"], p)
                row = bm.differential(a, b)
                j = bm.ar.load_summary(os.path.join(work, f"b{n}_{p}"), "gridshell")
                row.update(n=n, ranks=p, ghosts=j["partition"]["ghost_nodes_per_rank"],
                           elements=None, h5_mb=dir_mb(os.path.join(work, f"b{n}_{p}")), output_steps=b["steps"] + 1)
                rows.append(row)
                print(f"n = {n}, {p} ranks: {row['unknowns']} unknowns, {row['step_s']:.3f} s/step", flush=True)
            rows[-len(ranks)]["max_front"] = max_front(exe, n, work)
    return rows


def dir_mb(outdir):
    total = 0
    for dp, _, files in os.walk(outdir):
        for f in files:
            if ".h5" in f:
                total += os.path.getsize(os.path.join(dp, f))
    return total / 1e6


def max_front(exe, n, work):
    """The largest frontal matrix MUMPS' analysis reports (ICNTL(4) = 2 prints it)."""
    cmd = [exe, "run", "inputs/gridshell.yaml", "-o", os.path.join(work, f"front{n}"), "--set", f"mesh.parameters.n={n}",
           "--set", "solver.t_end=0.01", "--set", "output.hdf5=off", "-mat_mumps_icntl_4", "2"]
    p = subprocess.run(cmd, cwd=ROOT, env=bm.ENV, capture_output=True, text=True)
    m = re.findall(r"Maximum front(?:al)? size[^=]*=\s*(\d+)", p.stdout + p.stderr, re.I)
    return max(int(x) for x in m) if m else None


def slope(rows, key_x, key_y):
    """Least-squares slope of y against x."""
    xs = [float(r[key_x]) for r in rows]
    ys = [float(r[key_y]) for r in rows]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def quiet_record():
    """The gridshell's one-rank, full-Newton row at the largest n in docs/benchmarks/performance.csv
    (scripts/benchmark.py's record, measured on a quiet machine): the rates of a core."""
    import csv
    with open(os.path.join(ROOT, "docs", "benchmarks", "performance.csv")) as fh:
        rows = [r for r in csv.DictReader(fh) if r["case"] == "gridshell" and r["ranks"] == "1" and r["newton"] == "full"
                and r["exe"] == "this"]
    largest = max(int(r["n"]) for r in rows)
    return [r for r in rows if int(r["n"]) == largest][-1]  # the newest: rows are appended


def fit(rows):
    one = [r for r in rows if r["ranks"] == 1]
    big = max(one, key=lambda r: r["unknowns"])
    N = lambda r: float(r["unknowns"])  # noqa: E731
    for r in one:
        r["log_n"], r["log_flops"] = math.log(N(r)), math.log(r["mumps_gflop"] * 1e9)
        r["rest_mb"] = r["rss_max_mb"] - r["scene_mb"] - r["mumps_mb"]
    e = ASSUMED["flop_exponent"]
    c = {
        # Measured exponent of the flops over the calibration sizes (the model uses ASSUMED's 1.5).
        "flop_exponent_measured": slope(one, "log_n", "log_flops"),
        "c_F": big["mumps_gflop"] * 1e9 / N(big) ** e,
        "c_E": big["mumps_entries"] / (N(big) * math.log2(N(big))),
        # Memory per unknown: slopes over the sizes (each has a fixed part: the process, the gmsh
        # module, PETSc's and MUMPS' own).
        "m_scene_B": 1e6 * slope(one, "unknowns", "scene_mb"),
        "m_dist_B": 1e6 * slope(one, "unknowns", "rest_mb"),
        "k_M": 1e6 * big["mumps_mb"] / (8 * big["mumps_entries"]),
        "libraries_MB": min(r["rest_mb"] for r in one),
        "output_B_per_unknown": 1e6 * big["h5_mb"] / big["output_steps"] / N(big),
    }
    # Rates of one core: from the quiet record (the calibration runs here shared 2 cores with a load
    # average of 13-25, which inflated their times 3-10 fold; their counts are load-free).
    q = quiet_record()
    nq = float(q["unknowns"])
    newton, nf = float(q["newton_per_step"]), float(q["factorizations_per_step"])
    c["R_flops"] = float(q["mumps_gflop"]) * 1e9 / (float(q["factorization_s"]) / nf)
    c["M_Bps"] = 2 * 8 * c["c_E"] * nq * math.log2(nq) / (float(q["solve_s"]) / newton)
    c["a_s_per_unknown"] = float(q["assembly_s"]) / newton / nq
    c["rates_from"] = f"gridshell n = {q['n']}, 1 rank, revision {q['revision']} ({q['date']})"
    fronts = [(N(r), r["max_front"]) for r in one if r.get("max_front")]
    c["c_s"] = (sum(f / math.sqrt(n) for n, f in fronts) / len(fronts)) if fronts else 6.0
    c["c_s_measured"] = bool(fronts)
    multi = [r for r in rows if r["ranks"] > 1]
    c["c_g"] = (sum(max(r["ghosts"]) / math.sqrt(N(r) / 6 / r["ranks"]) for r in multi) / len(multi)) if multi else 4.0
    return c


def step_model(c, N, p, modified=False):
    L, B = ASSUMED["latency_s"], ASSUMED["bandwidth_Bps"]
    levels = math.log2(p) if p > 1 else 0.0
    F = c["c_F"] * N ** ASSUMED["flop_exponent"]
    E = c["c_E"] * N * math.log2(N)
    s_r = c["c_s"] * math.sqrt(N)
    t = {}
    t["assembly"] = c["a_s_per_unknown"] * N / p
    cb = sum(8 * (c["c_s"] ** 2) * N / 2 ** l * 2 ** l / p / B for l in range(1, int(levels) + 1))
    nb = ASSUMED["scalapack_block"]
    root = (8 * s_r ** 2 / math.sqrt(p) / B + 3 * (s_r / nb) * levels * L) if p > 1 else 0.0
    t["factorization"] = F / (p * c["R_flops"]) + cb + root
    t["solve"] = 2 * 8 * E / (p * c["M_Bps"]) + 2 * levels * L
    g = c["c_g"] * math.sqrt(N / 6 / p)
    t["ghost"] = 3 * (6 * L + 8 * 6 * g / B) if p > 1 else 0.0
    t["reductions"] = 4 * 2 * levels * L
    t["output"] = c["output_B_per_unknown"] * N / ASSUMED["filesystem_Bps"]
    if modified:
        it, nf = ASSUMED["newton_modified"], ASSUMED["factorizations_modified"]
        step = it * (t["assembly"] / 2 + t["solve"] + t["ghost"] + t["reductions"]) + nf * (t["factorization"] + t["assembly"] / 2)
    else:
        it = ASSUMED["newton_full"]
        step = it * (t["assembly"] + t["factorization"] + t["solve"] + t["ghost"] + t["reductions"])
    t["step"] = step + t["output"]
    t["root_share"] = root / t["factorization"]
    mem = {
        "scene_GB": c["m_scene_B"] * N / 1e9,
        "distributed_GB": c["m_dist_B"] * N / p / 1e9,
        "mumps_GB": c["k_M"] * 8 * E / p / 1e9,
        "root_front_GB": 8 * s_r ** 2 / p / 1e9,
    }
    mem["rank_GB"] = c["libraries_MB"] / 1e3 + mem["scene_GB"] + mem["distributed_GB"] + mem["mumps_GB"]
    mem["rank0_GB"] = mem["rank_GB"] + ASSUMED["analysis_host_B_per_unknown"] * N / 1e9
    return t, mem, s_r, F, E


def table(c):
    lim = ASSUMED["memory_per_rank_GB"]
    lines = ["| unknowns | ranks | step, full Newton (s) | step, modified (s) | factorization | of it: communication (root front, contribution blocks) | assembly | solve | ghost + reductions | output | memory/rank (GB) | of it: replicated scene | rank 0 with MUMPS' analysis (GB) | first limit |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for N in SIZES:
        for p in RANKS:
            t, m, s_r, F, E = step_model(c, N, p)
            tm, _, _, _, _ = step_model(c, N, p, modified=True)
            it = ASSUMED["newton_full"]
            share = lambda k: f"{100 * it * t[k] / t['step']:.0f} %"  # noqa: E731
            limits = []
            if m["rank_GB"] > lim:
                limits.append("memory: " + ("replicated scene" if m["scene_GB"] > max(m["mumps_GB"], m["distributed_GB"]) else "MUMPS factors"))
            if m["rank0_GB"] > lim and m["rank_GB"] <= lim:
                limits.append("rank 0: MUMPS' sequential analysis")
            if t["output"] > 0.25 * tm["step"]:
                limits.append("output ≥ 25 % of a modified-Newton step")
            if t["root_share"] > 0.5:
                limits.append("root front > 50 % of the factorization")
            lines.append(
                f"| {N:.0e} | {p} | {t['step']:.3g} | {tm['step']:.3g} | {share('factorization')} | {100 * t['root_share']:.0f} % "
                f"| {share('assembly')} | {share('solve')} | {100 * it * (t['ghost'] + t['reductions']) / t['step']:.1f} % "
                f"| {100 * t['output'] / t['step']:.1f} % | {m['rank_GB']:.2f} | {m['scene_GB']:.2f} | {m['rank0_GB']:.2f} | {'; '.join(limits) or '–'} |")
    return "\n".join(lines)


def chart(c):
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for N, style in zip(SIZES, ("-o", "-s", "-^")):
        ts = [step_model(c, N, p)[0]["step"] for p in RANKS]
        tm = [step_model(c, N, p, modified=True)[0]["step"] for p in RANKS]
        ms = [step_model(c, N, p)[1]["rank_GB"] for p in RANKS]
        ax[0].loglog(RANKS, ts, style, label=f"{N:.0e} unknowns, full Newton")
        ax[0].loglog(RANKS, tm, style[1:], mfc="none", ls="--", label=f"{N:.0e}, modified Newton")
        ax[1].loglog(RANKS, ms, style, label=f"{N:.0e} unknowns")
    ax[1].axhline(ASSUMED["memory_per_rank_GB"], color="k", lw=0.8, ls=":", label="memory per rank (assumed)")
    for a, yl in zip(ax, ("predicted time per step (s)", "predicted memory per rank (GB)")):
        a.set_xlabel("ranks")
        a.set_ylabel(yl)
        a.set_xticks(RANKS)
        a.set_xticklabels([str(r) for r in RANKS])
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle("gridshell: performance model calibrated on 1-3 ranks of this machine")
    fig.tight_layout()
    os.makedirs(os.path.dirname(FIGURE), exist_ok=True)
    fig.savefig(FIGURE, dpi=110)


def calibration_table(rows):
    lines = ["| n | ranks | unknowns | s/step | Newton/step | assembly (s) | factorization (s) | solve (s) | output (s) | Gflop/factorization | factor entries | largest front | ghost nodes (largest rank) | memory, largest rank (MB) |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['n']} | {r['ranks']} | {r['unknowns']} | {r['step_s']:.3f} | {r['newton_per_step']:.2f} | {r['assembly_s']:.3f} "
                     f"| {r['factorization_s']:.3f} | {r['solve_s']:.3f} | {r['output_s']:.3f} | {r['mumps_gflop']:.3g} "
                     f"| {r['mumps_entries']:.3g} | {r.get('max_front') or ''} | {max(r['ghosts'])} | {r['rss_max_mb']:.0f} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    ap.add_argument("--sizes", default="12,16,24")
    ap.add_argument("--ranks", default="1,2,3")
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--no-doc", action="store_true")
    a = ap.parse_args()
    if a.reuse:
        with open(CALIBRATION) as fh:
            rows = json.load(fh)["runs"]
    else:
        rows = calibrate(a.exe, [int(x) for x in a.sizes.split(",")], [int(x) for x in a.ranks.split(",")])
    c = fit(rows)
    os.makedirs(os.path.dirname(CALIBRATION), exist_ok=True)
    with open(CALIBRATION, "w") as fh:
        json.dump({"runs": rows, "fit": c, "assumed": ASSUMED}, fh, indent=1)
    # Check against the one measurement at 1e6 unknowns (docs/performance.md, section 5, 2 ranks).
    _, m, s_r, F, E = step_model(c, 1094688, 2)
    check = (f"At 1 094 688 unknowns (gridshell n = 144) the fit gives {F / 1e9:.1f} Gflop per factorization and "
             f"{E:.3g} factor entries; measured there: 34.7 Gflop, 9.68e+07 entries (docs/performance.md, section 5).")
    text = "\n\n".join([
        "Calibration runs (per step: differences of runs of 2 and 4 steps; output of every step). Their "
        "times were taken at a load average of 13–25 on the 2 cores: the 2- and 3-rank times (busy-polling "
        "ranks waiting for a core; negative differences) are not usable, and the model takes no time from "
        "them — only counts (flops, factor entries, fronts, ghost nodes, memory), which the load does not "
        "change. The rates of a core come from the quiet record (`rates_from`).",
        calibration_table(rows),
        "Fitted: " + ", ".join(f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}" for k, v in c.items()) + ".",
        "Assumed: " + ", ".join(f"{k} = {v:g}" for k, v in ASSUMED.items()) + ".",
        check,
        "![performance model](figures/performance_model.png)",
        table(c)])
    print(text)
    chart(c)
    if not a.no_doc:
        bm.replace_between_markers(BEGIN, END, text)

if __name__ == "__main__":
    main()
