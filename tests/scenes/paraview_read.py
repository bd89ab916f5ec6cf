"""Opens an alphaflex XDMF file with ParaView's own reader (run under pvpython) and checks what a
user sees: the time steps, the blocks (bodies, links, joints, shapes), their point arrays, and that
the values equal those in the HDF5 file; each link is the polyline body → joint → body.

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
# (and "shapes": the slider-crank's crank and rod are boxes; tests/scenes/paraview_shapes.py checks them)
assert set(blocks) == {"bodies", "links", "joints", "shapes"}, blocks.keys()
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
    # Links: 3 points per joint that holds a body, the middle one the joint's location, the ends
    # body centres or the joint itself (ground side).
    links = blocks["links"]
    lp = vtk_to_numpy(links.GetPoints().GetData())
    loc = f[last]["joint_location"][()]
    assert links.GetNumberOfCells() == len(loc) and lp.shape == (3 * len(loc), 3), (links.GetNumberOfCells(), lp.shape)
    for c in range(len(loc)):
        assert np.array_equal(lp[3 * c + 1], loc[c]), (c, lp[3 * c + 1], loc[c])
        for end in (lp[3 * c], lp[3 * c + 2]):
            assert np.array_equal(end, loc[c]) or any(np.array_equal(end, p) for p in pts), (c, end)
print(f"ParaView read {path}: {len(times)} steps, bodies {arrays['bodies']}, links {links.GetNumberOfCells()}, joints {arrays['joints']}")
