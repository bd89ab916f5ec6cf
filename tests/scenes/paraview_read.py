"""Opens an alphaflex XDMF file with ParaView's own reader (run under pvpython) and checks what a
user sees: the time steps, the two blocks (bodies, joints), their point arrays, and that the
values equal those in the HDF5 file.

usage: pvpython paraview_read.py ABSOLUTE/PATH/NAME.xdmf EXPECTED_STEPS
"""
import sys

from paraview import servermanager as sm
from paraview.simple import XDMFReader
from vtk.util.numpy_support import vtk_to_numpy
import h5py
import numpy as np

path, expected = sys.argv[1], int(sys.argv[2])
reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
assert len(times) == expected, f"{len(times)} time steps, expected {expected}"
assert abs(times[0]) < 1e-15 and times == sorted(times), times

reader.UpdatePipeline(times[-1])
data = sm.Fetch(reader)
blocks = {data.GetMetaData(i).Get(data.NAME()): data.GetBlock(i) for i in range(data.GetNumberOfBlocks())}
assert set(blocks) == {"bodies", "joints"}, blocks.keys()
arrays = {n: [b.GetPointData().GetArrayName(k) for k in range(b.GetPointData().GetNumberOfArrays())]
          for n, b in blocks.items()}
for want in ("velocity", "acceleration", "angle", "axis"):
    assert want in arrays["bodies"], arrays
for want in ("force", "moment"):
    assert want in arrays["joints"], arrays

# The values ParaView shows at the last time are those in the HDF5 file.
with h5py.File(path[:-5] + ".h5", "r") as f:
    last = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
    assert abs(f[last].attrs["time"][0] - times[-1]) < 1e-12
    pts = vtk_to_numpy(blocks["bodies"].GetPoints().GetData())
    assert np.allclose(pts, f[last]["node_position"][()], rtol=0, atol=1e-15), "positions differ"
    force = vtk_to_numpy(blocks["joints"].GetPointData().GetArray("force"))
    assert np.allclose(force, f[last]["joint_force"][()], rtol=0, atol=1e-12), "joint forces differ"
    assert pts.dtype == np.float64, pts.dtype
print(f"ParaView read {path}: {len(times)} steps, bodies {arrays['bodies']}, joints {arrays['joints']}")
