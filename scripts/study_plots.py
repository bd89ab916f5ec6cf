#!/usr/bin/python3
"""Charts of an `alphaflex study` from its CSV (docs/study.md, docs/stability.md).

    /usr/bin/python3 scripts/study_plots.py OUTDIR/NAME_study.csv [--part I/N]

`alphaflex study` calls this after writing the CSV (on several ranks of one node, rank r of N
with --part r/N: each draws every N-th chart of the study); run it again by hand to restyle the charts
(it reads only the CSVs: NAME_study.csv and, when present, NAME_history.csv and NAME_energy.csv).
Writes next to the CSV, by the study's mode:
  convergence  NAME_work_precision.png  error vs CPU time, log-log, one line per setting (and peer)
               NAME_convergence.png     error vs h with the fitted slope in the legend
               NAME_cost.png            Newton iterations per step and CPU time per step vs h
               NAME_conditioning.png    condition number of S_t vs h (if the study computed it)
  oscillation  NAME_oscillation.png     sensor histories and total variation per unit time
  blow_up      NAME_blow_up.png         growth of the multipliers' second difference vs the predicted roots
  fidelity     NAME_fidelity.png        sensor differences vs CPU time, strain-energy shares
               NAME_fidelity_load.png   with a load axis (study.load): each rung's error vs the load
                                        scale, the tolerance and where the lightest acceptable rung changes
"""
import math
import os
import re
import sys
import textwrap

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, NullFormatter  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
import alphaflex_results as ar  # noqa: E402

MARKERS = "osD^v<>ph*"
# --part I/N: this process writes charts I, I+N, I+2N, ... of the study (and the budget table
# when I = 0), so that N ranks draw a study's charts at the same time. Building a figure is ~7 % of
# a chart's time; its layout and PNG (save) are the rest, so the other charts are built and dropped.
PART = (0, 1)
_charts_seen = [0]


def mine():
    """Whether the next chart is this part's (each save() asks once, in the study's chart order)."""
    k = _charts_seen[0]
    _charts_seen[0] += 1
    return k % PART[1] == PART[0]


def read(path):
    """The '#' comments and the rows (dicts of strings) of a study CSV (python/alphaflex_results.py)."""
    study = ar.load_study(path)
    return study.comments, study.rows


def f(x):
    try:
        v = float(x)
        return v if math.isfinite(v) else float("nan")
    except (TypeError, ValueError):
        return float("nan")


def labels_in_order(rows):
    out = []
    for r in rows:
        if r["label"] not in out:
            out.append(r["label"])
    return out


def slope(h, e):
    h, e = np.asarray(h, float), np.asarray(e, float)
    ok = np.isfinite(e) & (e > 0) & np.isfinite(h) & (h > 0)
    if ok.sum() < 2:
        return float("nan")
    return np.polyfit(np.log(h[ok]), np.log(e[ok]), 1)[0]


def error_names(rows):
    return [k[4:] for k in rows[0].keys() if k.startswith("err_")]


def style(i, peer):
    return dict(marker=MARKERS[i % len(MARKERS)], ls="--" if peer else "-", ms=5, lw=1.4 if peer else 1.2)


def grid_for(n):
    cols = min(3, n)
    rows = int(math.ceil(n / cols))
    return rows, cols


def plain_ticks(fig):
    """Tick labels as plain numbers (0.001, 1e-06) rather than powers of ten in mathtext."""
    plain = FuncFormatter(lambda v, _: f"{v:g}")
    for ax in fig.axes:
        for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
            if scale == "log":
                axis.set_major_formatter(plain)
                axis.set_minor_formatter(NullFormatter())


def grid_and_legend(*axes):
    """The log-log grid and the small legend every chart of several series has."""
    for a in axes:
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)


def suptitle(fig, text, fontsize=9):
    """A figure title wrapped to the figure's width (never cut off), with room kept for it."""
    width = int(fig.get_figwidth() * 72 / (0.55 * fontsize))  # characters per line at this size
    lines = [w for part in text.split("\n") for w in (textwrap.wrap(part, width) or [""])]
    fig.suptitle("\n".join(lines), fontsize=fontsize)
    fig._title_lines = len(lines)


def save(fig, path):
    if not mine():
        plt.close(fig)
        return
    plain_ticks(fig)
    lines = getattr(fig, "_title_lines", 0)
    top = 1.0 - (lines * 11 + 6) / (72 * fig.get_figheight()) if lines else 1.0
    fig.tight_layout(rect=(0, 0, 1, top))
    fig.savefig(path, dpi=90)
    plt.close(fig)
    print("wrote", path)


def title_of(comments):
    head = comments[0] if comments else ""
    return head.split(":")[0].replace("alphaflex study ", "")


BUDGETS = (1e-3, 1e-2, 1e-1, 1.0)


def error_at_budget(rs, en, budget):
    """Error at a CPU budget along one line (runs in the order of h or tolerance), by log-log
    interpolation between the two runs that bracket the budget; None below the cheapest run, and the
    error of the costliest run above it ("<=")."""
    pts = [(f(r["cpu"]), f(r["err_" + en])) for r in rs]
    pts = [(a, b) for a, b in pts if a > 0 and b > 0]
    if not pts:
        return None, ""
    if budget < min(p[0] for p in pts):
        return None, ""
    best = None
    for (c0, e0), (c1, e1) in zip(pts, pts[1:]):
        lo, hi = sorted((c0, c1))
        if lo <= budget <= hi and c0 != c1:
            w = (math.log(budget) - math.log(c0)) / (math.log(c1) - math.log(c0))
            e = math.exp(math.log(e0) + w * (math.log(e1) - math.log(e0)))
            best = e if best is None else min(best, e)
    if best is not None:
        return best, ""
    return min(p[1] for p in pts if p[0] <= budget), "<="


def budget_table(rows, names, base):
    """NAME_budget.csv: the error each line reaches at CPU budgets of 1 ms to 1 s."""
    labels = labels_in_order(rows)
    out = ["label,method,error,budget_s,value,bound"]
    for lab in labels:
        rs = [r for r in rows if r["label"] == lab and r["status"] == "ok"]
        if not rs:
            continue
        rs = sorted(rs, key=lambda r: -(f(r["h"]) if r["h"] != "" else f(r["tol"])))
        for en in names:
            for b in BUDGETS:
                v, bound = error_at_budget(rs, en, b)
                out.append("%s,%s,%s,%g,%s,%s" % (lab, rs[0]["method"], en, b, "" if v is None else "%.3g" % v, bound))
    with open(base + "_budget.csv", "w") as fh:
        fh.write("\n".join(out) + "\n")
    print("wrote", base + "_budget.csv")


def convergence(csv_path, comments, rows, base):
    names = error_names(rows)
    if PART[0] == 0:
        budget_table(rows, names, base)
    labels = labels_in_order(rows)
    ref = next((c for c in comments if c.startswith("reference:")), "")
    cpu_note = next((c for c in comments if c.startswith("cpu:")), "")
    name = title_of(comments)

    # Work-precision: error vs CPU time.
    nr, nc = grid_for(len(names))
    fig, axes = plt.subplots(nr, nc, figsize=(5.2 * nc, 4.2 * nr), squeeze=False)
    for k, en in enumerate(names):
        ax = axes[k // nc][k % nc]
        for i, lab in enumerate(labels):
            rs = [r for r in rows if r["label"] == lab and r["status"] == "ok"]
            # in the order of h (or tolerance), so that timing noise does not fold the line
            rs = sorted(rs, key=lambda r: -(f(r["h"]) if r["h"] != "" else f(r["tol"])))
            pts = [(f(r["cpu"]), f(r["err_" + en])) for r in rs]
            pts = [(a, b) for a, b in pts if a > 0 and b > 0]
            if not pts:
                continue
            peer = rs[0]["method"] != "alphaflex"
            lab_txt = rs[0]["method"] if peer else lab
            ax.loglog(*zip(*pts), label=lab_txt, **style(i, peer))
        ax.set(xlabel="CPU time (s)", ylabel="error in " + en, title=en)
        ax.grid(True, which="both", alpha=0.3)
    for k in range(len(names), nr * nc):
        axes[k // nc][k % nc].axis("off")
    # one legend for the figure, with every line of every panel (peers have no state errors)
    seen = {}
    for a in axes.flat:
        for hnd, lab in zip(*a.get_legend_handles_labels()):
            seen.setdefault(lab, hnd)
    spare = len(names) < nr * nc
    where = axes[nr - 1][nc - 1] if spare else axes[0][0]
    where.legend(list(seen.values()), list(seen.keys()), fontsize=8 if spare else 7,
                 loc="center" if spare else "best")
    suptitle(fig, f"{name}: work–precision (error at t_end vs {cpu_note.split(';')[0][5:]})\n{ref}")
    save(fig, os.path.join(base + "_work_precision.png"))

    # Convergence: error vs h, fitted slopes in the legend — as the study fitted them
    # (NAME_slopes.csv): errors at round-off or at the reference's accuracy are no order.
    # Fixed-step runs only (adaptive runs, study.tol, have no h: they are in the work-precision chart).
    ours = [r for r in rows if r["method"] == "alphaflex" and r["h"] != ""]
    fits = {}
    if os.path.exists(base + "_slopes.csv"):
        fits = {(r["label"], r["error"]): r for r in ar.load_study(base + "_slopes.csv").rows}
    fig, axes = plt.subplots(nr, nc, figsize=(5.2 * nc, 4.2 * nr), squeeze=False)
    for k, en in enumerate(names):
        ax = axes[k // nc][k % nc]
        hmin, hmax, emin = float("inf"), 0, float("inf")
        for i, lab in enumerate(labels):
            rs = [r for r in ours if r["label"] == lab and r["status"] == "ok"]
            h = [f(r["h"]) for r in rs]
            e = [f(r["err_" + en]) for r in rs]
            pts = [(a, b) for a, b in zip(h, e) if b > 0]
            if not pts:
                continue
            fit = fits.get((lab, en))
            if fit is None:  # a CSV without NAME_slopes.csv (older studies): the plain fit
                fit = {"slope": "%.2f" % slope(h, e), "at_floor": "0", "meaning": "%.2f" % slope(h, e)}
            if fit["slope"] and fit["at_floor"] == "0":
                text = f"slope {f(fit['slope']):.2f}"
            elif fit["slope"]:
                text = f"slope {f(fit['slope']):.2f} for h > {f(fit['h_floor']):g}; below, the errors stop decreasing"
            else:
                text = "no order: " + fit["meaning"].replace("none: ", "")
            ax.loglog(*zip(*sorted(pts)), label="\n".join(textwrap.wrap(f"{lab} ({text})", 48)), **style(i, False))
            if fit["at_floor"] not in ("", "0") and f(fit.get("floor", "")) > 0:
                ax.axhline(f(fit["floor"]), color="C%d" % i, ls=(0, (1, 3)), lw=0.8)
            hmin, hmax = min(hmin, min(p[0] for p in pts)), max(hmax, max(p[0] for p in pts))
            emin = min(emin, min(p[1] for p in pts))
        if hmax > 0:
            # order-2 guide through the first setting's error at the largest h
            r_big = [r for r in ours if r["label"] == labels[0] and r["status"] == "ok" and f(r["h"]) == hmax]
            e_big = f(r_big[0]["err_" + en]) if r_big else float("nan")
            if e_big > 0:
                hh = np.array([hmin, hmax])
                ax.loglog(hh, e_big * (hh / hmax) ** 2, "k:", lw=1, label="order 2")
            # An error that grows again at the smallest h: the round-off of q amplified by β' ~ 1/h²
            # (eq. 34); a slope −2 guide through the smallest-h error shows it.
            rs0 = sorted([r for r in ours if r["label"] == labels[0] and r["status"] == "ok"], key=lambda r: f(r["h"]))
            errs0 = [f(r["err_" + en]) for r in rs0 if f(r["err_" + en]) > 0]
            if len(rs0) >= 3 and errs0 and f(rs0[0]["err_" + en]) > 3 * min(errs0):
                h0, e0 = f(rs0[0]["h"]), f(rs0[0]["err_" + en])
                hg = np.array([h0, 10 * h0])
                ax.loglog(hg, e0 * (hg / h0) ** -2, "k--", lw=1, label="∝ h⁻² (round-off, eq. 34)")
        ax.set(xlabel="h (s)", ylabel="error in " + en, title=en)
        grid_and_legend(ax)
    for k in range(len(names), nr * nc):
        axes[k // nc][k % nc].axis("off")
    suptitle(fig, f"{name}: convergence at t_end (least-squares slopes over the h whose errors are above round-off and the reference's accuracy)\n{ref}")
    save(fig, base + "_convergence.png")

    # Cost: Newton iterations per step and CPU per step vs h.
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for i, lab in enumerate(labels):
        rs = [r for r in ours if r["label"] == lab]
        if not rs:
            continue
        h = [f(r["h"]) for r in rs]
        nm = [f(r["newton_mean"]) for r in rs]
        cps = [f(r["cpu_per_step"]) * 1e6 for r in rs]
        failed = [r["status"] != "ok" for r in rs]
        ax[0].semilogx(h, nm, label=lab, **style(i, False))
        ax[1].loglog(h, cps, label=lab, **style(i, False))
        for a, b, c in zip(h, cps, failed):
            if c:
                ax[1].plot(a, b, "rx", ms=10, mew=2)
    ax[0].set(xlabel="h (s)", ylabel="Newton iterations per step (mean)", title="Newton iterations")
    ax[1].set(xlabel="h (s)", ylabel="CPU time per step (µs)", title="time per step (red x: run failed)")
    grid_and_legend(*ax)
    suptitle(fig, f"{name}: cost ({cpu_note})")
    save(fig, base + "_cost.png")

    if "cond_2norm" in rows[0]:
        fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
        for i, lab in enumerate(labels):
            rs = [r for r in ours if r["label"] == lab]
            h = [f(r["h"]) for r in rs]
            ax[0].loglog(h, [f(r["cond_2norm"]) for r in rs], label=lab, **style(i, False))
            ax[1].loglog(h, [f(r["cond_mumps1"]) for r in rs], label=lab, **style(i, False))
        hs = np.array(sorted({f(r["h"]) for r in ours}))
        c0 = max(f(r["cond_2norm"]) for r in ours if f(r["h"]) == hs[-1])
        ax[0].loglog(hs, c0 * (hs / hs[-1]) ** -4, "k:", lw=1, label="∝ h⁻⁴")
        ax[0].set(xlabel="h (s)", ylabel="σ_max/σ_min", title="2-norm condition number of S_t (dense SVD)")
        ax[1].set(xlabel="h (s)", ylabel="RINFOG(10)", title="MUMPS cond1 (componentwise, ICNTL(11)=1)")
        grid_and_legend(*ax)
        suptitle(fig, f"{name}: conditioning of the iteration matrix at t_end")
        save(fig, base + "_conditioning.png")


def read_history(base):
    path = base + "_history.csv"
    if not os.path.exists(path):
        return None
    return ar.load_study(path).rows


def oscillation(csv_path, comments, rows, base):
    name = title_of(comments)
    hist = read_history(base)
    tv_keys = [k for k in rows[0] if k.startswith("tv_") and not k.startswith("tv_ratio")]
    sensors = [k[3:] for k in tv_keys if k != "tv_lambda_max"]
    main = sensors[0] if sensors else None
    hs = sorted({f(r["h"]) for r in rows}, reverse=True)
    labels = labels_in_order(rows)
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.4), gridspec_kw={"width_ratios": [1.2, 1, 1.3]})
    if hist and main:
        h0 = hs[0]
        # the most oscillatory first, so that the damped histories are drawn on top
        tv = {lab: f(next((r for r in rows if r["label"] == lab and f(r["h"]) == h0), {}).get("tv_" + main)) for lab in labels}
        order = sorted(labels, key=lambda lab: -tv[lab] if math.isfinite(tv[lab]) else 0)
        series = {}
        for lab in order:
            hr = [r for r in hist if r["label"] == lab and abs(f(r["h"]) - h0) <= 1e-12 * h0]
            series[lab] = (np.array([f(r["t"]) for r in hr]), np.array([f(r[main]) for r in hr]))
        for i, lab in enumerate(order):
            t, x = series[lab]
            ax[0].plot(t, x, lw=1.0, color="C%d" % labels.index(lab), label=lab)
        ax[0].set(xlabel="t (s)", ylabel=main, title=f"{main}, h = {h0:g} s")
        ax[0].grid(alpha=0.3)
        ax[0].legend(fontsize=7)
        # zoom: 40 steps around the largest step-to-step oscillation of the most oscillatory setting
        t, x = series[order[0]]
        if len(x) > 42:
            d2 = np.abs(np.diff(x, 2))
            k = int(np.clip(np.nanargmax(d2) + 1, 20, len(x) - 21))
            for lab in order:
                tt, xx = series[lab]
                ax[1].plot(tt[k - 20:k + 21], xx[k - 20:k + 21], ".-", ms=3, lw=0.9, color="C%d" % labels.index(lab),
                           label=lab)
            ax[1].set(xlabel="t (s)", ylabel=main, title="zoom: 40 steps around the largest oscillation")
            ax[1].grid(alpha=0.3)
    width = 0.8 / max(1, len(labels))
    x = np.arange(len(tv_keys) * len(hs))
    for i, lab in enumerate(labels):
        vals = []
        for h in hs:
            r = next((r for r in rows if r["label"] == lab and f(r["h"]) == h), None)
            for k in tv_keys:
                vals.append(f(r[k]) if r else float("nan"))
        ax[2].bar(x + i * width, vals, width, label=lab, color="C%d" % i)
    ax[2].set_xticks(x + 0.4 - width / 2)
    ax[2].set_xticklabels([f"{k[3:]}\nh={h:g}" for h in hs for k in tv_keys], fontsize=7)
    ax[2].set_yscale("log")
    ax[2].set(ylabel="total variation per unit time", title="TV / T (smooth variation + oscillation)")
    ax[2].grid(alpha=0.3, axis="y")
    ax[2].legend(fontsize=7)
    ratio = ""
    if main and len(labels) > 1:
        r0 = [r for r in rows if r["label"] == labels[0] and f(r["h"]) == hs[0]]
        r1 = [r for r in rows if r["label"] == labels[1] and f(r["h"]) == hs[0]]
        if r0 and r1:
            ratio = f"; TV({main}) {labels[1]} / {labels[0]} = {f(r1[0]['tv_' + main]) / f(r0[0]['tv_' + main]):.2f} at h = {hs[0]:g} s"
    suptitle(fig, f"{name}: oscillations of the multipliers{ratio}")
    save(fig, base + "_oscillation.png")


def blow_up(csv_path, comments, rows, base):
    name = title_of(comments)
    hist = read_history(base)
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, r in enumerate(rows):
        lab, h = r["label"], f(r["h"])
        hr = [x for x in hist if x["label"] == lab and abs(f(x["h"]) - h) <= 1e-12 * h] if hist else []
        n = np.array([int(x["step"]) for x in hr])
        g = np.array([f(x["d2_lambda_inf"]) for x in hr])
        ok = np.isfinite(g) & (g > 0)
        gm, gp = f(r["growth_measured"]), f(r["growth_predicted"])
        line, = ax.semilogy(n[ok], g[ok], lw=1.2,
                            label=f"{lab}, h={h:g}: measured {gm:.3g}/step, predicted {gp:.3g}"
                            + ("" if r["status"] == "ok" else " (Newton failed)"))
        if ok.sum() > 2 and gp > 1:
            # the predicted rate through the middle of the measured growth
            k = np.flatnonzero(ok)[len(np.flatnonzero(ok)) // 2]
            nn = np.array([n[k] - 10, n[k] + 10])
            ax.semilogy(nn, g[k] * gp ** (nn - n[k]), ":", color=line.get_color(), lw=2)
    ax.set(xlabel="step n", ylabel="‖λ_{n+1} − 2λ_n + λ_{n−1}‖∞",
           title="growth of the multipliers' second difference (dotted: |ζ|ⁿ of the largest root of ϱ, σ)")
    grid_and_legend(ax)
    suptitle(fig, f"{name}: parameters outside the stability conditions (eq. 18, 20)")
    save(fig, base + "_blow_up.png")


def fidelity(csv_path, comments, rows, base):
    name = title_of(comments)
    names = error_names(rows)
    ref = next((c for c in comments if c.startswith("reference:")), "")
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.6))
    # err_max (the max over the sensors) bold, with every variant's label; the tolerance of the
    # recommendation as a line, the recommended variant ringed (a reference's error 0 is off a log axis).
    names = [en for en in names if en != "max"] + (["max"] if "max" in names else [])
    for k, en in enumerate(names):
        pts = [(f(r["cpu"]), f(r["err_" + en]), r["label"]) for r in rows]
        xs = [p[0] for p in pts if p[1] > 0]
        ys = [p[1] for p in pts if p[1] > 0]
        bold = en == "max"
        ax[0].loglog(xs, ys, marker="o" if bold else MARKERS[k % len(MARKERS)], ls="-" if bold else "none",
                     color="k" if bold else None, ms=7 if bold else 5, lw=1.4,
                     label="max over the sensors" if bold else en)
        if bold or (k == 0 and "max" not in names):
            for p in pts:
                if p[1] > 0:
                    ax[0].annotate(p[2], (p[0], p[1]), fontsize=7, xytext=(3, 3), textcoords="offset points")
    rec = next((c for c in comments if c.startswith("recommendation:")), "")
    m = re.search(r"tolerance ([0-9.eE+-]+)", rec)
    if m:
        ax[0].axhline(float(m.group(1)), color="tab:red", ls=":", lw=1.2, label=f"tolerance {m.group(1)}")
        for r in rows:
            if r.get("recommended") == "1" and f(r.get("err_max", "nan")) > 0:
                ax[0].plot([f(r["cpu"])], [f(r["err_max"])], "o", ms=14, mfc="none", mec="tab:red",
                           label=f"recommended: {r['label']}")
    ax[0].set(xlabel="CPU time (s)", ylabel="max over t of |difference| / range of the reference",
              title="difference to the reference variant vs cost")
    grid_and_legend(ax[0])
    epath = base + "_energy.csv"
    if os.path.exists(epath):
        er = ar.load_study(epath).rows
        variants = labels_in_order([{"label": r["variant"]} for r in er])
        parts = labels_in_order([{"label": r["part"]} for r in er])
        bottom = np.zeros(len(variants))
        for p in parts:
            vals = np.array([next((f(r["share_mean"]) for r in er if r["variant"] == v and r["part"] == p), 0.0)
                             for v in variants])
            vals = np.nan_to_num(vals)
            ax[1].bar(range(len(variants)), 100 * vals, bottom=100 * bottom, label=p)
            bottom += vals
        ax[1].set_xticks(range(len(variants)))
        ax[1].set_xticklabels(variants, fontsize=7, rotation=15)
        ax[1].set(ylabel="share of the time-mean strain energy (%)", title="strain energy by flexible part")
        ax[1].legend(fontsize=7)
    suptitle(fig, f"{name}: model fidelity against cost\n{ref}")
    save(fig, base + "_fidelity.png")


def fidelity_load(csv_path, comments, rows, base):
    """A ladder over a load axis (study.load): err_max of each rung against the load scale, log-log,
    the tolerance as a line, the change points of the lightest acceptable rung in the title (the
    CSV's `# load axis:` lines). The full rung, the reference at every scale (error 0), is left out."""
    name = title_of(comments)
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for k, label in enumerate(labels_in_order(rows)):
        pts = sorted((f(r["load_scale"]), f(r.get("err_max"))) for r in rows if r["label"] == label)
        pts = [(s, e) for s, e in pts if s > 0 and e > 0]
        if pts:
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=MARKERS[k % len(MARKERS)], lw=1.2, label=label)
    tol = next((m.group(1) for c in comments if c.startswith("recommendation at load scale")
                for m in [re.search(r": tolerance ([0-9.eE+-]+)", c)] if m), None)
    if tol:
        ax.axhline(float(tol), color="tab:red", ls=":", lw=1.2, label=f"tolerance {tol}")
    # Acceptable points ringed: the lightest acceptable rung at each scale is the first of them.
    acc = [(f(r["load_scale"]), f(r["err_max"])) for r in rows if r.get("acceptable") == "1" and f(r.get("err_max")) > 0]
    if acc:
        ax.plot([p[0] for p in acc], [p[1] for p in acc], "o", ms=11, mfc="none", mec="tab:green", label="acceptable")
    ax.set(xlabel="load scale (factor on study.load.keys)",
           ylabel="max over t of |rung - full| (as study.errors)", title="error of each rung against the load")
    grid_and_legend(ax)
    changes = [c[len("load axis: "):] for c in comments if c.startswith("load axis: lightest")]
    suptitle(fig, f"{name}: where the lightest acceptable rung changes\n" + "; ".join(changes))
    save(fig, base + "_fidelity_load.png")


def main():
    global PART
    args = sys.argv[1:]
    if len(args) == 3 and args[1] == "--part" and re.fullmatch(r"\d+/[1-9]\d*", args[2]):
        i, n = (int(x) for x in args[2].split("/"))
        if i >= n:
            sys.exit(f"--part {args[2]}: the part must be below the number of parts")
        PART = (i, n)
        args = args[:1]
    if len(args) != 1:
        sys.exit(__doc__)
    path = args[0]
    comments, rows = read(path)
    if not rows:
        sys.exit(f"{path}: no rows")
    base = path[:-len("_study.csv")] if path.endswith("_study.csv") else os.path.splitext(path)[0]
    mode = rows[0]["mode"]
    {"convergence": convergence, "oscillation": oscillation, "blow_up": blow_up,
     "fidelity": fidelity}[mode](path, comments, rows, base)
    if mode == "fidelity" and "load_scale" in rows[0]:
        fidelity_load(path, comments, rows, base)


if __name__ == "__main__":
    main()
