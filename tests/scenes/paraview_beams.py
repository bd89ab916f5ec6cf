"""Opens the XDMF of a beam scene with ParaView's own reader (run under pvpython) and checks what a
user sees: the "beams" block as line cells in the deformed configuration, the node frames (axes,
quaternion), and the section forces and strains as cell data, equal to the HDF5 file's values.

usage: pvpython paraview_beams.py ABSOLUTE/PATH/NAME.xdmf EXPECTED_STEPS EXPECTED_BEAM_ELEMENTS
"""
import sys

from paraview import servermanager as sm
from paraview.simple import XDMFReader
from vtk.util.numpy_support import vtk_to_numpy
import h5py
import numpy as np

path, expected, nelem = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
assert len(times) == expected, f"{len(times)} time steps, expected {expected}"
reader.UpdatePipeline(times[-1])
data = sm.Fetch(reader)
blocks = {data.GetMetaData(i).Get(data.NAME()): data.GetBlock(i) for i in range(data.GetNumberOfBlocks())}
assert "beams" in blocks, blocks.keys()  # and "bodies" only if the model has nodes outside its mesh
beams = blocks["beams"]
assert beams.GetNumberOfCells() == nelem, beams.GetNumberOfCells()
assert all(beams.GetCellType(c) in (3, 4) for c in range(nelem)), "beam cells must be lines/polylines"
cell = {beams.GetCellData().GetArrayName(k) for k in range(beams.GetCellData().GetNumberOfArrays())}
for want in ("N", "V2", "V3", "T", "M2", "M3", "axial_strain", "curvature_3"):
    assert want in cell, cell
point = {beams.GetPointData().GetArrayName(k) for k in range(beams.GetPointData().GetNumberOfArrays())}
for want in ("displacement", "axis2", "axis3", "quaternion"):
    assert want in point, point
assert beams.GetPointData().GetArray("quaternion").GetNumberOfComponents() == 4

with h5py.File(path[:-5] + ".h5", "r") as f:
    last = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
    pts = vtk_to_numpy(beams.GetPoints().GetData())
    assert pts.dtype == np.float64, pts.dtype
    assert np.allclose(pts, f[last]["node_position"][()], rtol=0, atol=1e-15), "positions differ"
    m3 = vtk_to_numpy(beams.GetCellData().GetArray("M3"))
    assert np.allclose(m3, f[last]["beam_M3"][()], rtol=0, atol=1e-12), "section moments differ"
    q = vtk_to_numpy(beams.GetPointData().GetArray("quaternion"))
    assert np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-12), "node quaternions are not unit"
print(f"ParaView read {path}: {len(times)} steps, {nelem} beam cells, cell data {sorted(cell)}")
