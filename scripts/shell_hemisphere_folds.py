#!/usr/bin/python3
"""Why geodesic directors make the Sze hemisphere stiffer on the paper's 16 x 16 quarter (issue 23).

    /usr/bin/python3 scripts/shell_hemisphere_folds.py [--exe build/alphaflex] [--quick]

Runs inputs/hemisphere_hole.yaml (Sze, Liu & Lo 2004, Sec. 3.4) with `director_interpolation:
linear` and `geodesic` on n x n quarters (n = 16, the paper's; 24, 32, 48 for the convergence
columns, skipped with --quick), measures the largest turn of the director along an element edge at
the full load (from the nodes' rotations in the HDF5 output), and runs the paper's mesh split into
two blocks: the column of elements next to each symmetry plane, where the point loads fold the
shell, and the rest, each block with either interpolation. Writes docs/benchmarks/shell_hemisphere_folds.md.
Path error as in scripts/shell_benchmarks.py: max |ours - S4R| at the table's load levels / max |S4R|.
"""
import argparse
import os
import subprocess
import tempfile

import h5py
import numpy as np
import yaml

from script_runs import ROOT, run_scene  # noqa: E402
from shell_benchmarks import errors, read_ref  # noqa: E402  (the path error and the S4R tables as there)

OUT = os.path.join(tempfile.gettempdir(), "alphaflex_shell_hemisphere_folds")

# The quarter of meshes/hemisphere_hole.geo (same sphere, hole, points and symmetry curves) as three
# transfinite patches split along the meridians at one element from each symmetry plane: group
# "fold" (the two outer columns, 2n elements) and "shell" (the rest); n x n quadrilaterals in all,
# the nodes on the same meridians and parallels as the one-patch mesh.
SPLIT_GEO = """
R = 10; n = 16;
c18 = Cos(18 * Pi / 180); s18 = Sin(18 * Pi / 180);
l1 = Pi / 2 / n; l2 = Pi / 2 - Pi / 2 / n;
Point(1) = {0, 0, 0}; Point(2) = {R, 0, 0}; Point(3) = {0, R, 0};
Point(4) = {0, R * s18, R * c18}; Point(5) = {R * s18, 0, R * c18}; Point(6) = {0, 0, R * c18};
Point(7) = {R * Cos(l1), R * Sin(l1), 0}; Point(8) = {R * Cos(l2), R * Sin(l2), 0};
Point(9) = {R * s18 * Cos(l1), R * s18 * Sin(l1), R * c18}; Point(10) = {R * s18 * Cos(l2), R * s18 * Sin(l2), R * c18};
Circle(1) = {2, 1, 7}; Circle(2) = {7, 1, 8}; Circle(3) = {8, 1, 3};
Circle(4) = {3, 1, 4};
Circle(5) = {4, 6, 10}; Circle(6) = {10, 6, 9}; Circle(7) = {9, 6, 5};
Circle(8) = {5, 1, 2};
Circle(9) = {7, 1, 9}; Circle(10) = {8, 1, 10};
Curve Loop(1) = {1, 9, 7, 8}; Surface(1) = {1} In Sphere {1};
Curve Loop(2) = {2, 10, 6, -9}; Surface(2) = {2} In Sphere {1};
Curve Loop(3) = {3, 4, 5, -10}; Surface(3) = {3} In Sphere {1};
Transfinite Curve{1, 3, 5, 7} = 2;
Transfinite Curve{2, 6} = n - 1;
Transfinite Curve{4, 8, 9, 10} = n + 1;
Transfinite Surface{1, 2, 3};
Recombine Surface{1, 2, 3};
Physical Surface("shell") = {2};
Physical Surface("fold") = {1, 3};
Physical Curve("sym_x") = {4};
Physical Curve("sym_y") = {8};
Physical Point("A") = {2};
Physical Point("B") = {3};
Physical Point("top") = {4};
"""


def path_errors(out, name, ref):
    d = np.genfromtxt(os.path.join(out, name + ".csv"), delimiter=",", names=True)
    return {s: errors(d, ref, s)[0] for s in ("uA", "vB")}


def rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def largest_turn(out, name):
    """Largest angle (degrees) between the directors at the two ends of an element edge at the last
    step; the directors taken radial in the reference (the sphere's normals) and carried by the nodes'
    rotations."""
    with h5py.File(os.path.join(out, name + ".h5"), "r") as f:
        conn = f["topology/shell_connectivity"][:].reshape(-1, 5)[:, 1:]  # XDMF mixed: type, 4 nodes
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        first, last = f[steps[0]], f[steps[-1]]
        X = first["node_position"][:]
        D = X / np.linalg.norm(X, axis=1)[:, None]
        q0, q1 = first["node_quaternion"][:], last["node_quaternion"][:]
    d = np.array([rotation(q1[i]) @ rotation(q0[i]).T @ D[i] for i in range(len(X))])
    turns = [np.degrees(np.arccos(np.clip(d[e[a]] @ d[e[(a + 1) % 4]], -1, 1))) for e in conn for a in range(4)]
    return max(turns)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "alphaflex"))
    ap.add_argument("--quick", action="store_true", help="the paper's mesh only")
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    ref = read_ref("sze_hemisphere.csv")
    os.makedirs(OUT, exist_ok=True)

    conv = []
    for n in (16,) if args.quick else (16, 24, 32, 48):
        row = {"n": n}
        for interp in ("linear", "geodesic"):
            out = os.path.join(OUT, f"n{n}_{interp}")
            run_scene(exe, "hemisphere_hole", out, {"mesh.parameters.n": n, "shells.0.director_interpolation": interp})
            row[interp] = path_errors(out, "hemisphere_hole", ref)
            row[interp + "_turn"] = largest_turn(out, "hemisphere_hole")
        conv.append(row)

    # The split mesh: the scene of inputs/hemisphere_hole.yaml with two shell blocks.
    with open(os.path.join(ROOT, "inputs", "hemisphere_hole.yaml")) as f:
        scene = yaml.safe_load(f)
    geo = os.path.join(OUT, "hemisphere_hole_split.geo")
    with open(geo, "w") as f:
        f.write(SPLIT_GEO)
    scene["mesh"] = {"file": geo}
    scene["name"] = "hemisphere_split"
    split = []
    for inner, fold in (("linear", "linear"), ("geodesic", "geodesic"), ("geodesic", "linear"), ("linear", "geodesic")):
        shell = dict(scene["shells"][0], director_interpolation=inner)
        scene["shells"] = [shell, dict(shell, name="fold", group="fold", director_interpolation=fold)]
        path = os.path.join(OUT, f"split_{inner}_{fold}.yaml")
        with open(path, "w") as f:
            yaml.safe_dump(scene, f, sort_keys=False)
        out = os.path.join(OUT, f"split_{inner}_{fold}")
        p = subprocess.run([exe, "run", path, "-o", out], capture_output=True, text=True)
        if p.returncode != 0:
            raise RuntimeError(f"{path} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
        split.append((inner, fold, path_errors(out, "hemisphere_split", ref)))

    page = os.path.join(ROOT, "docs", "benchmarks", "shell_hemisphere_folds.md")
    with open(page, "w") as f:
        f.write("# The Sze hemisphere and the director interpolation\n\n")
        f.write("Made by `/usr/bin/python3 scripts/shell_hemisphere_folds.py` (issue 23; docs/theory/shell.md). "
                "inputs/hemisphere_hole.yaml (Sze, Liu & Lo 2004, Sec. 3.4) against the paper's ABAQUS S4R table "
                "on its 16 x 16 quarter (tests/reference/sze_hemisphere.csv); path error: max |ours - S4R| at the "
                "table's load levels / max |S4R|. Largest turn: the largest angle between the directors at the two "
                "ends of an element edge at the full load.\n\n")
        f.write("| n x n quarter | linear uA | linear vB | linear largest turn | geodesic uA | geodesic vB | geodesic largest turn |\n")
        f.write("|---|---|---|---|---|---|---|\n")
        for r in conv:
            f.write(f"| {r['n']} x {r['n']} | {r['linear']['uA']:.2%} | {r['linear']['vB']:.2%} | {r['linear_turn']:.0f}° "
                    f"| {r['geodesic']['uA']:.2%} | {r['geodesic']['vB']:.2%} | {r['geodesic_turn']:.0f}° |\n")
        f.write("\nThe paper's mesh split into the column of elements next to each symmetry plane (32 of the 256 "
                "elements, where the point loads fold the shell) and the rest, each block with its own "
                "`director_interpolation`:\n\n")
        f.write("| rest | fold columns | uA | vB |\n|---|---|---|---|\n")
        for inner, fold, e in split:
            f.write(f"| {inner} | {fold} | {e['uA']:.2%} | {e['vB']:.2%} |\n")
    print("wrote", page)


if __name__ == "__main__":
    main()
