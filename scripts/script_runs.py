"""What the benchmark and figure scripts share: the tree's folders and running alphaflex.

    from script_runs import ROOT, REF, FIG, run_scene, run_cached

Importing it also puts python/ on the path, for `import alphaflex_results`.
"""
import hashlib
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REF = os.path.join(ROOT, "tests", "reference")  # reference tables (their sources in each file)
FIG = os.path.join(ROOT, "docs", "figures")
sys.path.insert(0, os.path.join(ROOT, "python"))


def run_scene(exe, scene, out, sets):
    """Run inputs/SCENE.yaml into `out` with --set KEY=VALUE for each of `sets`; raise on failure."""
    cmd = [exe, "run", os.path.join(ROOT, "inputs", scene + ".yaml"), "-o", out]
    for k, v in sets.items():
        cmd += ["--set", f"{k}={v}"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")


def run_cached(exe, scene, cache, sets):
    """run_scene() once per executable, scene file and settings: into a folder of `cache` keyed on
    them (and on the two files' times), reused while its summary is there. Returns the folder."""
    scene_path = os.path.join(ROOT, "inputs", scene + ".yaml")
    key = hashlib.sha1(repr((exe, os.path.getmtime(exe), scene_path, os.path.getmtime(scene_path),
                             sorted(sets.items()))).encode()).hexdigest()[:16]
    out = os.path.join(cache, f"{scene}_{key}")
    if not os.path.exists(os.path.join(out, scene + ".summary.json")):
        run_scene(exe, scene, out, sets)
    return out
