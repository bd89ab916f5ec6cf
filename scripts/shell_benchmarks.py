#!/usr/bin/python3
"""Shell benchmarks of issue 5 (Sze, Liu & Lo 2004) from alphaflex's own output: charts and the page.

    /usr/bin/python3 scripts/shell_benchmarks.py [--exe build/alphaflex] [--quick]

Runs inputs/shell_cantilever_shear.yaml, shell_rollup.yaml, slit_annular_plate.yaml and
hemisphere_hole.yaml on the paper's meshes (and, for the convergence columns, on meshes twice as
fine), with the default linear director interpolation and, on the paper's meshes (the roll-up also
twice as fine), with `director_interpolation: geodesic`, and with geodesic directors and
`membrane_edges: arc` (also twice as fine, but for the slit plate), compares their load-deflection paths with the paper's ABAQUS S4R tables
(tests/reference/sze_*.csv) and the roll-up with the exact circle, and writes
docs/figures/shell_sze.png and docs/benchmarks/shells.md. --quick skips the finer meshes.
"""
import argparse
import os
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from script_runs import FIG, REF, ROOT, run_scene  # noqa: E402  (also puts python/ on the path)
import alphaflex_results as ar  # noqa: E402

OUT = os.path.join(tempfile.gettempdir(), "alphaflex_shell_benchmarks")

# scene, reference table, sensors, paper's mesh parameters, the same twice as fine, title
CASES = [
    ("shell_cantilever_shear", "sze_cantilever_shear.csv", ["tip_u", "tip_w"], {}, {"mesh.parameters.nx": 32, "mesh.parameters.ny": 2},
     "cantilever strip, end shear (16 x 1)"),
    ("shell_rollup", "sze_rollup.csv", ["tip_u", "tip_w"], {}, {"mesh.parameters.nx": 32, "mesh.parameters.ny": 2},
     "strip rolled up by an end moment (16 x 1)"),
    ("slit_annular_plate", "sze_slit_annular_plate.csv", ["wA", "wB"], {}, {"mesh.parameters.nr": 20, "mesh.parameters.nt": 160},
     "slit annular plate, lifting line force (10 x 80)"),
    ("hemisphere_hole", "sze_hemisphere.csv", ["uA", "vB"], {}, {"mesh.parameters.n": 32},
     "hemisphere with 18 deg hole, point loads (16 x 16 quarter)"),
]


def read_ref(name):
    """A reference table: '#' lines (source), then a header row and numbers."""
    lines = [l for l in open(os.path.join(REF, name)) if not l.startswith("#")]
    cols = lines[0].strip().split(",")
    values = np.array([[float(x) for x in l.split(",")] for l in lines[1:] if l.strip()])
    return {c: values[:, k] for k, c in enumerate(cols)}


# (director_interpolation, membrane_edges, line style, label)
VARIANTS = [("linear", "chord", "-", "linear"), ("geodesic", "chord", "--", "geodesic"),
            ("geodesic", "arc", "-.", "geodesic + arc")]


def run(exe, scene, sets, tag, interp="linear", edges="chord"):
    """Run a scene with the given director interpolation and membrane edges; return (sensor table, output directory)."""
    out = os.path.join(OUT, f"{scene}_{tag}_{interp}_{edges}")
    run_scene(exe, scene, out, {**sets, "shells.0.director_interpolation": interp, "shells.0.membrane_edges": edges})
    return np.genfromtxt(os.path.join(out, scene + ".csv"), delimiter=",", names=True), out


def stats(out, scene):
    """Figures of a run's summary (OUTDIR/NAME.summary.json, python/alphaflex_results.py)."""
    j = ar.load_summary(out, scene)
    return {"steps": j["steps"], "newton": j["newton"]["total"], "newton_mean": j["newton"]["mean_per_step"],
            "newton_max": j["newton"]["max"], "unknowns": j["unknowns"], "wall": j["wall_time"]["s"],
            "assembly": j["wall_time"]["assembly"]["s"]}


def errors(data, ref, sensor):
    """At the table's load levels: max |ours − ref| / max |ref| over the path, and the final relative error."""
    ours = np.interp(ref["load_fraction"], data["t"], data[sensor])
    scale = np.max(np.abs(ref[sensor]))
    return np.max(np.abs(ours - ref[sensor])) / scale, (ours[-1] - ref[sensor][-1]) / abs(ref[sensor][-1]) if ref[sensor][-1] != 0 else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    ap.add_argument("--quick", action="store_true", help="skip the finer meshes")
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    os.makedirs(FIG, exist_ok=True)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    rows, conv = [], []
    for ax, (scene, refname, sensors, sets, fine, title) in zip(axes.flat, CASES):
        ref = read_ref(refname)
        for interp, edges, style, label in VARIANTS:
            data, out = run(exe, scene, sets, "paper", interp, edges)
            st = stats(out, scene)
            fine_data = None
            if not args.quick and ((interp, edges) == ("linear", "chord") or scene == "shell_rollup"
                                   or (edges == "arc" and scene != "slit_annular_plate")):
                fine_data, _ = run(exe, scene, fine, "fine", interp, edges)
            for k, s in enumerate(sensors):
                c = f"C{k}"
                if interp == "linear":
                    ax.plot(np.abs(ref[s]), ref["load_fraction"], "o", color=c, mfc="none", label=f"|{s}| Sze et al. (S4R)")
                    if scene == "shell_rollup":
                        ax.plot(np.abs(ref[s + "_exact"]), ref["load_fraction"], "x", color=c, ms=4, label=f"|{s}| exact")
                ax.plot(np.abs(data[s]), data["t"], style, color=c, label=f"|{s}| alphaflex, {label}")
                if fine_data is not None and (interp, edges) == ("linear", "chord"):
                    ax.plot(np.abs(fine_data[s]), fine_data["t"], ":", color=c, label=f"|{s}| alphaflex, {interp}, mesh x2")
                path_err, final_err = errors(data, ref, s)
                row = {"scene": scene, "interp": label, "sensor": s, "path": path_err, "final": final_err,
                       "ours": data[s][-1], "ref": ref[s][-1], **st}
                row["path_fine"] = errors(fine_data, ref, s)[0] if fine_data is not None else None
                if scene == "shell_rollup":
                    exact = {"load_fraction": ref["load_fraction"], s: ref[s + "_exact"]}
                    row["path_exact"], _ = errors(data, exact, s)
                    row["path_exact_fine"] = errors(fine_data, exact, s)[0] if fine_data is not None else None
                rows.append(row)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("displacement magnitude (m)")
        ax.set_ylabel("load fraction")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(FIG, "shell_sze.png"), dpi=110)
    write_page(rows, args.quick)


def write_page(rows, quick):
    path = os.path.join(ROOT, "docs", "benchmarks", "shells.md")
    with open(path, "w") as f:
        f.write("# Shell benchmarks (Sze, Liu & Lo 2004)\n\n")
        f.write("Made by `/usr/bin/python3 scripts/shell_benchmarks.py` (this page and "
                "`docs/figures/shell_sze.png`). Reference: the paper's ABAQUS S4R load-deflection tables on the "
                "paper's meshes, `tests/reference/sze_*.csv` (sources in their headers); the roll-up also against "
                "the exact circle. Static analysis, load stepping at the table's load levels, Newton to the "
                "default tolerance. Error over the path: max |ours - ref| at the table's load levels / max |ref|; "
                "final: relative error at the full load.\n\n")
        f.write("![load-deflection paths](../figures/shell_sze.png)\n\n")
        f.write("Each scene with the default `director_interpolation: linear` (chord membrane edges), with "
                "`geodesic`, and with `geodesic` and `membrane_edges: arc` (docs/theory/shell.md); the mesh x2 "
                "column for the default, the roll-up and geodesic + arc (but the slit plate).\n\n")
        pct = lambda v: "–" if v is None else f"{v:.2%}"  # noqa: E731
        f.write("| scene | setting | sensor | ours at P_max (m) | S4R (m) | final rel. error | path error |"
                + ("" if quick else " path error, mesh x2 |") + " unknowns | load steps | Newton its/step (max) | wall (s) |\n")
        f.write("|---|---|---|---|---|---|---|" + ("" if quick else "---|") + "---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['scene']} | {r['interp']} | {r['sensor']} | {r['ours']:.4f} | {r['ref']:.3f} | {r['final']:+.2%} | {r['path']:.2%} |"
                    + ("" if quick else f" {pct(r['path_fine'])} |")
                    + f" {r['unknowns']} | {r['steps']} | {r['newton_mean']:.1f} ({r['newton_max']}) | {r['wall']:.2f} |\n")
        roll = [r for r in rows if "path_exact" in r]
        if roll:
            f.write("\nRoll-up against the exact circle (path error / max |exact|): "
                    + ", ".join(f"{r['interp']} {r['sensor']} {r['path_exact']:.2%}"
                                + ("" if quick or r["path_exact_fine"] is None else f" (mesh x2: {r['path_exact_fine']:.2%})")
                                for r in roll) + ".\n")
            f.write("\nWith linearly interpolated directors a turn φ per element is seen as the curvature 2 sin(φ/2)/L_e "
                    "and the end moment as EI sin φ/L_e instead of EI φ/L_e: at the full circle (φ = 22.5° per element "
                    "on the paper's 16 × 1 mesh) the strip over-rolls by 2.8 % and the tip stops 0.33 m short of the "
                    "root; the error falls like h² (test SzeShellBenchmarks.RollUpConvergesToTheCircleWithOrderTwo). "
                    "The geodesic edge differences see the arc φ itself, so constant curvature is exact and the "
                    "roll-up closes on the paper's mesh (test SzeShellBenchmarks.GeodesicRollUpClosesTheCircleOnThePapersMesh). "
                    "They are not the default: on the hemisphere's 16 × 16 quarter they make the element stiffer "
                    "than the linear one and the S4R table, beyond the 1 % that the linear element keeps there. The "
                    "point loads fold the shell by up to 48° within one element there, and two thirds to four fifths of "
                    "the difference come from the two columns of elements at the folds; both interpolations converge "
                    "to the same path (48 × 48: path errors 0.54 % and 0.09 % geodesic, 0.50 % and 0.16 % linear): "
                    "docs/benchmarks/shell_hemisphere_folds.md, docs/theory/shell.md.\n")
            f.write("\nWith `membrane_edges: arc` the element measures each edge along the circular arc that its "
                    "nodes' directors define instead of its chord, in the membrane strains and in the tangents of the "
                    "bending and shear strains: a flat element rolled without stretching has no membrane strain and "
                    "κ = φ/L_e exactly (test ReissnerMindlinShell.ArcMembraneEdgesRollAFlatElementWithoutStretching). "
                    "With geodesic directors it keeps the roll-up closed and the cantilever and slit plate where they "
                    "were, and softens the hemisphere's pushed point A from 1.71 % to under 1 %; the pulled point B, "
                    "where the fold is sharpest, stays above 1 % (docs/theory/shell.md, \"Arc membrane edges\"). "
                    "No single setting is yet within 1 % on all eight paths together with the roll-up within 2 % "
                    "(issue 23). For scale: on the same model (NAFEMS 3DNLG-9, ABAQUS Benchmarks Manual 4.10.9) "
                    "ABAQUS' fully integrated S4 is -5.80 / 3.37 at half the load against S4R's -5.90 / 3.41, "
                    "1.22 % / 0.98 % in this page's path measure, where geodesic + arc is 0.74 % / 0.73 % "
                    "(docs/theory/shell.md).\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
