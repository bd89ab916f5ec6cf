"""Tests python/alphaflex_results.py on the output of small runs (ctest scenes.results_python):
the summary JSON against the printed summary and the state, the sensor CSV against the summary's
final sensors, the fields of the HDF5 file at a time, a beam's cell fields, and a study's CSV.

usage: /usr/bin/python3 results_python.py EXE REPO OUTDIR
"""
import math
import os
import re
import subprocess
import sys

exe, repo, outdir = sys.argv[1:4]
sys.path.insert(0, os.path.join(repo, "python"))
import alphaflex_results as ar  # noqa: E402
import numpy as np  # noqa: E402


def run(*args):
    p = subprocess.run([exe, *args], capture_output=True, text=True)
    assert p.returncode == 0, f"{' '.join(args)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}"
    return p.stdout


# 1. A rigid mechanism: 10 steps of h = 5 ms, fields every 2 steps.
out = os.path.join(outdir, "rigid")
text = run("run", os.path.join(repo, "inputs/slider_crank.yaml"), "-o", out, "--set", "solver.t_end=0.05",
           "--set", "output.every=2")
s = ar.load_summary(out)
assert s == ar.load_summary(os.path.join(out, "slider_crank.summary.json"))
assert s["command"] == "run" and s["scene"] == "slider_crank" and s["analysis"] == "dynamic", s
assert s["steps"] == 10 and s["h"] == 0.005 and s["t_end"] == 0.05 and s["final_time"] == 0.05, s
assert s["unknowns"] == s["coordinates"] + s["multipliers"] == 18, s
# The JSON and the printed summary are made from the same figures: each printed number is the
# JSON's, rounded as printed.
m = re.search(r"Newton iterations\s+total (\d+), mean (\S+) per step, max (\d+)", text)
assert (int(m.group(1)), int(m.group(3))) == (s["newton"]["total"], s["newton"]["max"]), (m.groups(), s["newton"])
assert float(m.group(2)) == float("%.4g" % s["newton"]["mean_per_step"]), (m.group(2), s["newton"])
m = re.search(r"wall time\s+([\d.]+) s \(([\d.]+) us per step\)", text)
assert m.group(1) == "%.3f" % s["wall_time"]["s"] and m.group(2) == "%.3f" % s["wall_time"]["us_per_step"], m.groups()
for phase in ("setup", "assembly", "factorization", "solve", "output", "other"):
    m = re.search(rf"\n    {phase}\s+([\d.]+) s \(([\d.]+) %\)", text)
    assert m.groups() == ("%.3f" % s["wall_time"][phase]["s"], "%.1f" % s["wall_time"][phase]["percent"]), (phase, m.groups())
assert f"  summary  {os.path.join(out, 'slider_crank.summary.json')}" in text

sensors = ar.load_sensors(s["results"]["sensors"])
assert list(sensors) == ["t", "theta1", "u4", "pivot_fx", "pivot_fy", "x3", "x4", "vx1"], list(sensors)
assert len(sensors["t"]) == 11 and np.allclose(sensors["t"], np.arange(11) * 0.005, rtol=0, atol=1e-15)
for name, value in s["final_sensors"].items():  # the CSV's 17 digits give the double back
    assert sensors[name][-1] == value, (name, sensors[name][-1], value)

with ar.Results(s["results"]["xdmf"]) as r:
    assert np.allclose(r.times, np.arange(6) * 0.01, rtol=0, atol=1e-15), r.times
    assert r.step_at(0.031) == 3 and r.step_at(0.0) == 0
    q = r.field("q", t=0.02)
    assert q.shape == (10,)
    # θ1 (the crank's angle, the third coordinate of the first body) at t = 0.02 s is the sensor's.
    assert q[2] == sensors["theta1"][4], (q[2], sensors["theta1"][4])
    pos = r.field("node_position")
    assert pos.shape == (5, 3) and np.all(pos[:, 2] == 0.0)
    assert r.history("node_position").shape == (6, 5, 3)
    assert "joint_force" in r.fields() and r.topology("joints").shape == (4,)
    try:
        r.field("no_such_field")
        raise AssertionError("no KeyError")
    except KeyError as e:
        assert "node_position" in str(e)

# 2. Beams: cell fields per element (the roll-up, 2 load steps of a static analysis).
out = os.path.join(outdir, "beam")
run("run", os.path.join(repo, "inputs/beam_rollup.yaml"), "-o", out, "--set", "solver.static.steps=2",
    "--set", "load.factor=0.25")
s = ar.load_summary(out)
assert s["analysis"] == "static" and s["steps"] == 2 and s["load_factor"] == 0.25, s
with ar.Results(s["results"]["fields"]) as r:
    assert np.allclose(r.times, [0.0, 0.125, 0.25], rtol=0, atol=1e-15), r.times  # load factors
    conn = r.topology("beam_connectivity")
    names = [f for f in r.fields() if f.startswith("beam_")]
    assert names, r.fields()
    for f in names:
        assert conn.size == 2 * r.field(f).shape[0], (f, r.field(f).shape, conn.shape)  # two nodes per segment

# 3. A study's CSV: two step sizes, no charts.
out = os.path.join(outdir, "study")
run("study", os.path.join(repo, "inputs/slider_crank.yaml"), "--study", os.path.join(repo, "tests/study/slider_crank_small.yaml"),
    "--study-set", "h=[4e-3,2e-3]", "--study-set", "t_end=0.1", "--no-plots", "-o", out)
st = ar.load_study(os.path.join(out, "small_study.csv"))
assert len(st.rows) == 4, len(st.rows)
assert st["h"].dtype == float and sorted(set(st["h"])) == [2e-3, 4e-3], st["h"]
assert st["label"].dtype == object and set(st["label"]) == {"GA rho_inf=0.7", "Newmark gamma=0.6"}
assert all(math.isfinite(e) and e > 0 for e in st["err_theta1"]), st["err_theta1"]
assert len(st.select(label="GA rho_inf=0.7")) == 2 and any(c.startswith("reference:") for c in st.comments)
# 4. `alphaflex modes`: NAME_modes.summary.json with the table's figures.
out = os.path.join(outdir, "modes")
run("modes", os.path.join(repo, "tests/modal/fourbar_modes.yaml"), "-o", out)
s = ar.load_summary(out)
assert s["command"] == "modes" and len(s["modes"]) == 1 and s["rigid_body_modes"] == 0, s
table = ar.load_study(s["results"]["table"])  # a plain CSV: the same reader
assert s["modes"][0]["frequency_hz"] == table["frequency_hz"][0] and s["modes"][0]["dominant_part"] == "coupler", s["modes"]
print("alphaflex_results: summary, sensors, fields, study CSV read as expected")
