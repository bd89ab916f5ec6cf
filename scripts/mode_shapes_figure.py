#!/usr/bin/python3
"""Mode shapes of an `alphaflex modes` output, drawn from its HDF5 file (NAME_modeshapes.h5): for
each mode k the node positions at the two extreme phases (t = k and t = k + 1/2 of the animation)
over the undeformed model, in 3D, one panel per mode, titled with NAME_modes.csv's frequency.

usage: mode_shapes_figure.py OUTDIR NAME FIGURE.png [--modes N]   (docs/modes.md)"""
import argparse
import csv
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("name")
    ap.add_argument("figure")
    ap.add_argument("--modes", type=int, default=6)
    a = ap.parse_args()
    with open(os.path.join(a.outdir, a.name + "_modes.csv")) as f:
        rows = list(csv.DictReader(f))
    h5 = h5py.File(os.path.join(a.outdir, a.name + "_modeshapes.h5"), "r")
    steps = sorted(k for k in h5.keys() if k.startswith("step_"))
    times = np.array([h5[s].attrs["time"] for s in steps]).ravel()
    conn = h5["topology/beam_connectivity"][()].reshape(-1, 2) if "topology/beam_connectivity" in h5 else None
    n = min(a.modes, len(rows))
    fig = plt.figure(figsize=(3.2 * min(n, 3), 3.0 * ((n + 2) // 3)))
    for k in range(1, n + 1):
        ax = fig.add_subplot((n + 2) // 3, min(n, 3), k, projection="3d")
        for t, style in ((k, "-"), (k + 0.5, "--")):
            s = steps[int(np.argmin(np.abs(times - t)))]
            x = h5[s]["node_position"][()]
            x0 = x - h5[s]["node_displacement"][()]  # the state linearized about
            for seg in (conn if conn is not None else [[i, i + 1] for i in range(len(x) - 1)]):
                if style == "-":
                    ax.plot(*x0[seg].T, color="0.75", lw=1)
                ax.plot(*x[seg].T, style, color="C0" if style == "-" else "C3", lw=1.5)
        # Equal scales on the three axes around the model (round-off stays invisible).
        c = 0.5 * (x0.min(axis=0) + x0.max(axis=0))
        half = 0.5 * max(np.ptp(x0, axis=0).max(), 1e-12)
        ax.set_xlim(c[0] - half, c[0] + half)
        ax.set_ylim(c[1] - half, c[1] + half)
        ax.set_zlim(c[2] - half, c[2] + half)
        r = rows[k - 1]
        ax.set_title("mode %d: %.4g Hz, %s" % (k, float(r["frequency_hz"]), r["kind"]), fontsize=9)
        ax.set_xlabel("x (m)", fontsize=7)
        ax.set_ylabel("y (m)", fontsize=7)
        ax.set_zlabel("z (m)", fontsize=7)
        ax.tick_params(labelsize=6)
    fig.tight_layout()
    fig.savefig(a.figure, dpi=110)
    print("wrote", a.figure)


if __name__ == "__main__":
    main()
