"""pvpython: the rebuilt mesh of a reduced beam block opens in ParaView (issue 19; docs/results.md,
"Reduced bodies"). usage: paraview_reduced.py RESULTS.xdmf POINTS CELLS BODY MODES

The grid `reduced_beams` at the last step has POINTS points and CELLS line cells with the beam's
section results as cell data, its points at the HDF5 dataset reduced_beam_points of that step,
and the field data modal_coordinates_BODY with MODES values equal to the step's
modal_coordinates (read with h5py from the same file, through the XDMF's HDF path)."""
import re
import sys

import numpy as np
from paraview.simple import XDMFReader, servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

xdmf, npts, ncells, body, modes = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], int(sys.argv[5])
r = XDMFReader(FileNames=[xdmf])
r.UpdatePipelineInformation()
t = r.TimestepValues[-1]
r.UpdatePipeline(t)
d = servermanager.Fetch(r)
grid = None
it = d.NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    if it.GetCurrentMetaData().Get(d.NAME()) == "reduced_beams":
        grid = it.GetCurrentDataObject()
    it.GoToNextItem()
fail = []
if grid is None:
    sys.exit("no block reduced_beams in " + xdmf)
if grid.GetNumberOfPoints() != npts or grid.GetNumberOfCells() != ncells:
    fail.append(f"{grid.GetNumberOfPoints()} points and {grid.GetNumberOfCells()} cells, expected {npts} and {ncells}")
for name in ("N", "M2", "M3", "curvature_2"):
    if grid.GetCellData().GetArray(name) is None:
        fail.append(f"no cell data {name}")
xi = grid.GetFieldData().GetArray("modal_coordinates_" + body)
# The same step's datasets, found through the index's HDF path of the last step's points.
text = open(xdmf).read()
paths = re.findall(r">([^<>]+):/(step_\d+)/reduced_beam_points<", text)
part, step = paths[-1]
import h5py  # noqa: E402 (pvpython's own numpy and h5py)
import os  # noqa: E402
with h5py.File(os.path.join(os.path.dirname(xdmf), part), "r") as f:
    pts, ref_xi = f[step]["reduced_beam_points"][()], f[step]["modal_coordinates"][()]
got = vtk_to_numpy(grid.GetPoints().GetData())
if got.shape != pts.shape or np.max(np.abs(got - pts)) > 0:
    fail.append("the points are not the step's reduced_beam_points")
if xi is None or xi.GetNumberOfTuples() != modes:
    fail.append(f"field data modal_coordinates_{body}: {None if xi is None else xi.GetNumberOfTuples()} values, expected {modes}")
elif np.max(np.abs(vtk_to_numpy(xi).ravel() - ref_xi[:modes])) > 0:
    fail.append("the field data are not the step's modal_coordinates")
if fail:
    sys.exit("; ".join(fail))
print(f"reduced_beams: {npts} points, {ncells} cells, section results, modal_coordinates_{body} ({modes} values) at t = {t}")
