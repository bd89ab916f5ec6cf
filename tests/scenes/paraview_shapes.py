"""Opens the XDMF of a scene whose rigid bodies have shapes with ParaView's own reader (run under
pvpython) and checks what a user sees in the "shapes" block: triangles and quadrilaterals (one
XDMF Mixed topology) whose points are those of the HDF5 file, each shape moving rigidly with its
body: at every step its points are x + R·R0ᵀ·(p0 − x0), with x, R the body's position and axes in
the "bodies" block (axis, axis2, axis3 as the columns of R) and p0, x0, R0 those of the first step;
the point data displacement is p − p0. Each shape is found by its connected cells and matched to
the body at its centroid (the scenes' shapes are centred on their bodies).

usage: pvpython paraview_shapes.py ABSOLUTE/PATH/NAME.xdmf EXPECTED_SHAPES EXPECTED_POINTS EXPECTED_CELLS
"""
import sys

from paraview import servermanager as sm
from paraview.simple import XDMFReader
from vtk.util.numpy_support import vtk_to_numpy
import h5py
import numpy as np

VTK_TRIANGLE, VTK_QUAD = 5, 9
path, nshapes, npoints, ncells = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
assert len(times) > 1, times


def blocks_at(t):
    reader.UpdatePipeline(t)
    data = sm.Fetch(reader)
    return {data.GetMetaData(i).Get(data.NAME()): data.GetBlock(i) for i in range(data.GetNumberOfBlocks())}


def body_frames(b):
    x = vtk_to_numpy(b.GetPoints().GetData()).copy()
    axes = [vtk_to_numpy(b.GetPointData().GetArray(a)) for a in ("axis", "axis2", "axis3")]
    return x, np.stack(axes, axis=2)  # R[i] has the axes as columns


first = blocks_at(times[0])
assert "shapes" in first and "bodies" in first, sorted(first)
sh0 = first["shapes"]
assert sh0.GetNumberOfPoints() == npoints, f"{sh0.GetNumberOfPoints()} points, expected {npoints}"
assert sh0.GetNumberOfCells() == ncells, f"{sh0.GetNumberOfCells()} cells, expected {ncells}"
types = {sh0.GetCellType(c) for c in range(ncells)}
assert types <= {VTK_TRIANGLE, VTK_QUAD}, types
point_arrays = {sh0.GetPointData().GetArrayName(k) for k in range(sh0.GetPointData().GetNumberOfArrays())}
assert {"displacement", "velocity"} <= point_arrays, point_arrays

# The shapes: connected components of the cells (union-find over the point ids).
parent = list(range(npoints))


def root(i):
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


for c in range(ncells):
    ids = sh0.GetCell(c).GetPointIds()
    pts = [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
    for p in pts[1:]:
        parent[root(p)] = root(pts[0])
groups = {}
for i in range(npoints):
    groups.setdefault(root(i), []).append(i)
assert len(groups) == nshapes, f"{len(groups)} shapes, expected {nshapes}"

p0 = vtk_to_numpy(sh0.GetPoints().GetData()).copy()
x0, R0 = body_frames(first["bodies"])
size = max(np.abs(p0).max(), 1.0)
owner = {}
for g, members in groups.items():
    c = p0[members].mean(axis=0)
    d = np.linalg.norm(x0 - c, axis=1)
    assert d.min() < 1e-9 * size, f"shape of points {members[:4]}...: no body at its centroid {c}"
    owner[g] = int(np.argmin(d))

with h5py.File(path[:-5] + ".h5", "r") as f:
    steps = sorted(k for k in f.keys() if k.startswith("step_"))
    assert len(steps) == len(times)
    moved = 0.0
    for t, step in ((times[len(times) // 2], steps[len(steps) // 2]), (times[-1], steps[-1])):
        b = blocks_at(t)
        sh = b["shapes"]
        p = vtk_to_numpy(sh.GetPoints().GetData())
        assert p.dtype == np.float64, p.dtype
        assert np.array_equal(p, f[step]["shape_points"][()]), "the shape points differ from the HDF5 file"
        u = vtk_to_numpy(sh.GetPointData().GetArray("displacement"))
        assert np.allclose(u, p - p0, rtol=0, atol=1e-12 * size), "displacement is not p - p0"
        x, R = body_frames(b["bodies"])
        for g, members in groups.items():
            k = owner[g]
            want = x[k] + (R[k] @ R0[k].T @ (p0[members] - x0[k]).T).T
            err = np.abs(p[members] - want).max()
            assert err < 1e-10 * size, f"shape of body {k} at t = {t}: off its body's pose by {err}"
        moved = max(moved, np.abs(p - p0).max())
    assert moved > 1e-3 * size, f"the shapes do not move ({moved})"
print(f"ParaView read {path}: {nshapes} shapes, {npoints} points, {ncells} cells ({sorted(types)}), "
      f"each on its body's pose over {len(times)} steps; largest displacement {moved:.4g} m")
