#!/usr/bin/python3
"""Campbell diagram of `alphaflex modes` with `modes.campbell` (docs/modes.md), from its CSV.

    /usr/bin/python3 scripts/campbell_plot.py OUTDIR/NAME_campbell.csv

`alphaflex modes` calls this after writing the CSV; run it again by hand to restyle the chart.
Writes OUTDIR/NAME_campbell.png: the frequencies (Hz, rotating frame) of the modes against the
speed (rad/s), one line per mode number, the marker telling the whirl (^ forward, v backward,
o none), and the 1x and 2x per-revolution lines f = k·Ω/2π, drawn like the study charts
(scripts/study_plots.py: title inside the figure, plain tick labels).
"""
import csv
import math
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

WHIRL_MARKER = {"forward": "^", "backward": "v", "": "o"}


def main(path):
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        sys.exit(f"{path}: no rows")
    name = os.path.basename(path)[: -len("_campbell.csv")] if path.endswith("_campbell.csv") else "modes"
    speeds = sorted({float(r["speed_rad_s"]) for r in rows})
    modes = sorted({int(r["mode"]) for r in rows})
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for i, k in enumerate(modes):
        pts = sorted((float(r["speed_rad_s"]), float(r["frequency_hz"]), r["whirl"]) for r in rows if int(r["mode"]) == k)
        color = f"C{i % 10}"
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-", color=color, lw=1.2, label=f"mode {k}")
        for s, fr, w in pts:
            ax.plot(s, fr, WHIRL_MARKER.get(w, "o"), color=color, ms=5)
    top = max(float(r["frequency_hz"]) for r in rows)
    smax = max(speeds) if max(speeds) > 0 else 1.0
    for mult, ls in ((1, ":"), (2, "--")):
        # Stop the per-rev line at the top of the modes so that it does not squash them.
        s_end = min(smax, 2 * math.pi * 1.05 * top / mult)
        ax.plot([0, s_end], [0, mult * s_end / (2 * math.pi)], ls, color="0.4", lw=1.0, label=f"{mult}× per rev")
    ax.set_xlabel("speed Ω (rad/s)")
    ax.set_ylabel("frequency in the rotating frame (Hz)")
    ax.ticklabel_format(style="plain", useOffset=False)
    ax.set_xlim(left=min(0.0, min(speeds)))
    ax.set_ylim(bottom=0.0)
    ax.grid(True, lw=0.4, alpha=0.6)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(f"{name}: Campbell diagram (markers: ^ forward, v backward whirl)", fontsize=9)
    fig.tight_layout()
    out = path[: -len(".csv")] + ".png"
    fig.savefig(out, dpi=90)
    plt.close(fig)
    print("wrote", out)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
