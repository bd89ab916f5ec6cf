"""Opens the XDMF of a shell scene with ParaView's own reader (run under pvpython) and checks what a
user sees: the "shells" block as triangles and quadrilaterals (one XDMF Mixed topology) in the
deformed configuration, with every shell result field as cell data equal to the HDF5 file's values,
the node motion as point data, and the geometry at the last step moved from the first by what a
displacement sensor of the CSV reports.

usage: pvpython paraview_shells.py ABSOLUTE/PATH/NAME.xdmf EXPECTED_STEPS EXPECTED_SHELL_CELLS
           EXPECTED_POINTS [SENSOR:X,Y,Z:COMPONENT ...]

SENSOR is a column of NAME.csv that measures the position or displacement of the mesh point that is
at (X, Y, Z) (m) at the first output step; COMPONENT is x, y or z. EXPECTED_SHELL_CELLS may be
TOTAL or TOTAL=QUADS+TRIANGLES.
"""
import csv
import sys

from paraview import servermanager as sm
from paraview.simple import XDMFReader
from vtk.util.numpy_support import vtk_to_numpy
import h5py
import numpy as np

FIELDS = ("n11", "n22", "n12", "m11", "m22", "m12", "q1", "q2", "von_mises_top", "von_mises_bottom")
VTK_TRIANGLE, VTK_QUAD = 5, 9

path, expected = sys.argv[1], int(sys.argv[2])
cells_arg, npoints = sys.argv[3], int(sys.argv[4])
ncells, nquad, ntri = int(cells_arg.split("=")[0]), None, None
if "=" in cells_arg:
    nquad, ntri = (int(v) for v in cells_arg.split("=")[1].split("+"))
    assert nquad + ntri == ncells, cells_arg
sensors = []
for arg in sys.argv[5:]:
    name, xyz, comp = arg.split(":")
    sensors.append((name, np.array([float(v) for v in xyz.split(",")]), "xyz".index(comp)))

reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
assert len(times) == expected, f"{len(times)} time steps, expected {expected}"


def shells_at(t):
    reader.UpdatePipeline(t)
    data = sm.Fetch(reader)
    blocks = {data.GetMetaData(i).Get(data.NAME()): data.GetBlock(i) for i in range(data.GetNumberOfBlocks())}
    assert "shells" in blocks, blocks.keys()  # and "bodies" only if the model has nodes outside its mesh
    return blocks["shells"]


first = vtk_to_numpy(shells_at(times[0]).GetPoints().GetData()).copy()
shells = shells_at(times[-1])
assert shells.GetNumberOfCells() == ncells, f"{shells.GetNumberOfCells()} shell cells, expected {ncells}"
assert shells.GetNumberOfPoints() == npoints, f"{shells.GetNumberOfPoints()} points, expected {npoints}"
types = [shells.GetCellType(c) for c in range(ncells)]
assert set(types) <= {VTK_TRIANGLE, VTK_QUAD}, f"shell cells must be triangles/quadrilaterals: {set(types)}"
if nquad is not None:
    assert types.count(VTK_QUAD) == nquad and types.count(VTK_TRIANGLE) == ntri, \
        f"{types.count(VTK_QUAD)} quadrilaterals and {types.count(VTK_TRIANGLE)} triangles, expected {nquad}+{ntri}"
cell = {shells.GetCellData().GetArrayName(k) for k in range(shells.GetCellData().GetNumberOfArrays())}
for want in FIELDS:
    assert want in cell, f"cell data {want} missing: {sorted(cell)}"
point = {shells.GetPointData().GetArrayName(k) for k in range(shells.GetPointData().GetNumberOfArrays())}
for want in ("displacement", "velocity", "acceleration", "quaternion"):
    assert want in point, f"point data {want} missing: {sorted(point)}"

pts = vtk_to_numpy(shells.GetPoints().GetData())
assert pts.dtype == np.float64, pts.dtype
with h5py.File(path[:-5] + ".h5", "r") as f:
    steps = sorted(k for k in f.keys() if k.startswith("step_"))
    last = steps[-1]
    assert abs(f[last].attrs["time"][0] - times[-1]) < 1e-12
    assert np.array_equal(pts, f[last]["node_position"][()]), "positions differ"
    assert np.array_equal(first, f[steps[0]]["node_position"][()]), "first positions differ"
    for name in FIELDS:
        v = vtk_to_numpy(shells.GetCellData().GetArray(name))
        assert v.dtype == np.float64, (name, v.dtype)
        assert np.array_equal(v, f[last]["shell_" + name][()]), f"{name} differs from the HDF5 file"
    disp = vtk_to_numpy(shells.GetPointData().GetArray("displacement"))
    assert np.array_equal(disp, f[last]["node_displacement"][()]), "displacements differ"
    # The cells ParaView built are those of the Mixed connectivity (type code 4 | 5, node ids).
    conn, k = f["topology"]["shell_connectivity"][()], 0
    for c in range(ncells):
        n = {4: 3, 5: 4}[int(conn[k])]
        assert types[c] == (VTK_TRIANGLE if n == 3 else VTK_QUAD), (c, types[c], conn[k])
        ids = shells.GetCell(c).GetPointIds()
        got = [ids.GetId(j) for j in range(ids.GetNumberOfIds())]
        assert got == list(conn[k + 1:k + 1 + n]), f"cell {c}: nodes {got}, HDF5 {list(conn[k + 1:k + 1 + n])}"
        k += 1 + n
    assert k == len(conn), (k, len(conn))
von_mises = vtk_to_numpy(shells.GetCellData().GetArray("von_mises_top"))
assert np.all(von_mises >= 0) and np.max(von_mises) > 0, "von Mises stresses must be non-negative and loaded"

# The geometry moved, from the first step to the last, by what the sensors measured.
moved = []
rows = []
if sensors:
    with open(path[:-5] + ".csv") as fcsv:
        rows = list(csv.DictReader(fcsv))
    assert abs(float(rows[-1]["t"]) - times[-1]) < 1e-12, (rows[-1]["t"], times[-1])
for name, xyz, comp in sensors:
    i = int(np.argmin(np.linalg.norm(first - xyz, axis=1)))
    assert np.linalg.norm(first[i] - xyz) < 1e-9, f"no point at {xyz} (nearest {first[i]})"
    want = float(rows[-1][name]) - float(rows[0][name])
    got = pts[i, comp] - first[i, comp]
    scale = max(abs(want), np.max(np.abs(pts - first)))
    assert abs(got - want) <= 1e-12 * max(scale, 1.0), f"{name}: geometry moved {got}, sensor {want}"
    assert abs(want) > 1e-9, f"{name}: the sensor does not move ({want}); choose a loaded point"
    moved.append(f"{name} {got:.6g}")
print(f"ParaView read {path}: {len(times)} steps, {ncells} shell cells, {npoints} points, moved {', '.join(moved)}, "
      f"cell data {sorted(cell)}")
