"""ctest scenes.render_picture: scripts/render.py renders a small result offscreen (xvfb-run +
pvpython) and the picture is checked: its size, that the model's pixels differ from the white
background, and that the default camera frames the model (its pixels cover a good part of the
picture and touch none of its edges). Two frames: the GIF has two images. Exits 77 (ctest: skipped)
with a message when pvpython or xvfb-run is missing.

usage: /usr/bin/python3 render_check.py REPO RESULT.xdmf OUTDIR
"""
import os
import random
import shutil
import subprocess
import sys

repo, result, outdir = sys.argv[1:4]
missing = [p for p in ("pvpython", "xvfb-run") if shutil.which(p) is None]
if missing:
    print(f"skipped: {' and '.join(missing)} not found (scripts/install-deps.sh installs paraview, python3-paraview and xvfb)")
    sys.exit(77)
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

name = os.path.splitext(os.path.basename(result))[0]
shutil.rmtree(outdir, ignore_errors=True)
# The X server: xvfb-run -a takes the first display number from 99 up whose lock file in /tmp is
# free. Two such runs at once (two ctest suites on one machine, or another job beside CI) can pick
# the same number, and pvpython then reaches the other run's server, whose cookie it lacks: "bad X
# server connection. DISPLAY=:99. Aborting." (seen once in CI, exit 134, before any of our code
# ran). So the search starts at a random number, and a run whose X connection failed is repeated
# (up to three times) with another; a failure of render.py itself is not retried.
x_failures = ("bad X server connection", "Xvfb failed to start", "cannot open display", "Can't open display")
for attempt in range(3):
    server = random.SystemRandom().randrange(100, 30000)
    cmd = ["xvfb-run", "-n", str(server), "-a", "pvpython", os.path.join(repo, "scripts/render.py"), result,
           "-o", outdir, "--frames", "2", "--size", "400x300", "--no-annotations"]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=240)
    if p.returncode == 0 or not any(m in p.stdout + p.stderr for m in x_failures):
        break
    print(f"attempt {attempt + 1}: no X server for pvpython (display :{server} and up), trying again")
assert p.returncode == 0, f"{' '.join(cmd)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}"
frames = sorted(f for f in os.listdir(outdir) if f.startswith(name + "_") and f.endswith(".png"))
assert frames == [f"{name}_0000.png", f"{name}_0001.png"], frames
for f in frames:
    img = np.asarray(Image.open(os.path.join(outdir, f)).convert("RGB")).astype(int)
    assert img.shape == (300, 400, 3), (f, img.shape)
    model = np.any(np.abs(img - 255) > 24, axis=2)  # differs from the white background
    share = model.mean()
    assert 0.002 < share < 0.6, (f, share)
    rows, cols = np.flatnonzero(model.any(axis=1)), np.flatnonzero(model.any(axis=0))
    # Framed: the model spans at least 40 % of the width or of the height and is not cut at an edge.
    assert rows[0] > 0 and cols[0] > 0 and rows[-1] < 299 and cols[-1] < 399, (f, rows[[0, -1]], cols[[0, -1]])
    assert (cols[-1] - cols[0]) > 160 or (rows[-1] - rows[0]) > 120, (f, rows[[0, -1]], cols[[0, -1]])
    print(f"{f}: {img.shape[1]}x{img.shape[0]}, model pixels {100 * share:.1f} %, "
          f"rows {rows[0]}-{rows[-1]}, columns {cols[0]}-{cols[-1]}")
gif = Image.open(os.path.join(outdir, name + ".gif"))
assert gif.n_frames == 2, gif.n_frames
print("render.py: frames and animation as expected")
