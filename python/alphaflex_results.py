"""Results of alphaflex runs as numpy arrays (docs/results.md).

    import sys; sys.path.insert(0, "python")        # from the repository's root
    import alphaflex_results as ar

    s = ar.load_summary("out")                       # OUTDIR/NAME.summary.json as a dict
    sensors = ar.load_sensors("out/slider_crank.csv")   # {"t": array, "theta1": array, ...}
    r = ar.Results("out/slider_crank.xdmf")          # or the .h5
    r.times                                          # output times (load factors of a static run)
    x = r.field("node_position", t=0.5)              # (nodes, 3) at the output step nearest t = 0.5
    study = ar.load_study("out/NAME_study.csv")      # columns as arrays, comments, rows

Needs only numpy and h5py (Debian: python3-numpy, python3-h5py; /usr/bin/python3). Every loader
reads what the run wrote: the summary JSON carries every figure of the printed summary (the run
writes both from the same data), so scripts need no regular expressions on the printed text.
"""
import csv
import glob
import json
import math
import os

import numpy as np

__all__ = ["load_summary", "load_sensors", "Results", "Study", "load_study"]


def load_summary(path, name=None):
    """The summary of a run (`alphaflex run`: OUTDIR/NAME.summary.json) or of `alphaflex modes`
    (OUTDIR/NAME_modes.summary.json) as a dict. `path` is the JSON file, or an output directory
    with `name` (the scene's name: its `name` key, else its file name without .yaml), or an output
    directory that holds exactly one run summary."""
    if os.path.isdir(path) and name is not None:
        path = os.path.join(path, name + ".summary.json")
    elif os.path.isdir(path):
        found = sorted(p for p in glob.glob(os.path.join(path, "*.summary.json"))
                       if not p.endswith("_modes.summary.json"))
        if not found:
            found = sorted(glob.glob(os.path.join(path, "*_modes.summary.json")))
        if len(found) != 1:
            raise FileNotFoundError(f"{path}: expected one *.summary.json, found {len(found)}"
                                    + (": " + ", ".join(os.path.basename(f) for f in found) if found else "")
                                    + "; give the file")
        path = found[0]
    with open(path) as fh:
        return json.load(fh)


def _number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def load_sensors(path):
    """The sensor CSV of a run (OUTDIR/NAME.csv: t, then one column per sensor in scene order) as
    {column: float array}, in the file's column order."""
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        rows = [[_number(v) for v in row] for row in reader if row]
    data = np.array(rows, dtype=float).reshape(len(rows), len(header))
    return {name: data[:, k].copy() for k, name in enumerate(header)}


class Results:
    """The fields of a run (NAME.h5 and its parts; NAME.xdmf names the same file). Output steps are
    the groups step_NNNNNN, each with its time; datasets are in model order (node_position:
    (nodes, 3), beam_<field>/shell_<field>: (elements, components), joint_force: (joints, 3), q,
    v, qdd, lambda: the generalized state)."""

    def __init__(self, path):
        import h5py  # here, so that the summary and CSV loaders work without h5py
        if path.endswith(".xdmf"):
            path = path[:-len(".xdmf")] + ".h5"
        self.path = path
        self._file = h5py.File(path, "r")
        self.steps = sorted(k for k in self._file.keys() if k.startswith("step_"))
        self.times = np.array([float(np.ravel(self._file[s].attrs["time"])[0]) for s in self.steps])

    def close(self):
        self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def fields(self, step=0):
        """The dataset names of an output step."""
        return sorted(self._file[self.steps[step]].keys())

    def step_at(self, t):
        """The index of the output step nearest to time t."""
        if len(self.times) == 0:
            raise ValueError(f"{self.path}: no output step")
        return int(np.argmin(np.abs(self.times - t)))

    def field(self, name, t=None, step=None):
        """Dataset `name` at the output step nearest to t (or at index `step`; the last by default)."""
        if t is not None and step is not None:
            raise ValueError("give t or step, not both")
        k = self.step_at(t) if t is not None else (len(self.steps) - 1 if step is None else step)
        group = self._file[self.steps[k]]
        if name not in group:
            raise KeyError(f"{self.path}: no field '{name}' at {self.steps[k]}; there are: {', '.join(sorted(group))}")
        return np.array(group[name])

    def history(self, name):
        """Dataset `name` at every output step, stacked: (steps, ...)."""
        return np.stack([self.field(name, step=k) for k in range(len(self.steps))])

    def topology(self, name):
        """A connectivity of /topology (nodes, joints, beam_connectivity, shell_connectivity)."""
        return np.array(self._file["topology"][name])


class Study:
    """A study's CSV (OUTDIR/NAME_study.csv and the others it writes): `comments` (the '#' lines,
    without '#'), `rows` (one dict of strings per run, as csv.DictReader gives) and `columns`
    ({name: array}: float where every value is a number or empty, else str)."""

    def __init__(self, comments, rows):
        self.comments = comments
        self.rows = rows
        self.columns = {}
        for name in (rows[0].keys() if rows else []):
            values = [r[name] for r in rows]
            try:
                self.columns[name] = np.array([float(v) if v not in ("", None) else math.nan for v in values])
            except ValueError:
                self.columns[name] = np.array(values, dtype=object)

    def __getitem__(self, name):
        return self.columns[name]

    def select(self, **where):
        """The rows whose columns equal the given values (strings compared as written)."""
        return [r for r in self.rows if all(r[k] == str(v) for k, v in where.items())]


def load_study(path):
    """A CSV written by `alphaflex study` (NAME_study.csv, NAME_history.csv, NAME_energy.csv) as
    a Study."""
    comments, body = [], []
    with open(path, newline="") as fh:
        for line in fh:
            (comments.append(line[1:].strip()) if line.startswith("#") else body.append(line))
    return Study(comments, list(csv.DictReader(body)))
