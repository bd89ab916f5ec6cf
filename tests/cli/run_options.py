"""What the command-line test scripts of issue 24 share (disk_full.py, output_lock.py,
checkpoint_flips.py): their common options and the scene's name."""
import argparse
import re
import shutil


def parser(doc):
    """An argument parser with --exe, --scene, --out, --np, --mpirun and --set."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--mpirun", default="mpirun")
    ap.add_argument("--set", action="append", default=[])
    return ap


def prepare(a):
    """The scene's name (its `name:`), with the output directory emptied."""
    shutil.rmtree(a.out, ignore_errors=True)
    return re.search(r"^name:\s*(\S+)", open(a.scene).read(), re.M).group(1)
