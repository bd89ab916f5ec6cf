"""Opens an XDMF index with ParaView's reader (under pvpython) and reads every time step it lists:
each must give the first drawn block (bodies, beams or shells) with its points (in the deformed
configuration of that step).
Prints steps=N. usage: pvpython paraview_all_steps.py ABSOLUTE/PATH/NAME.xdmf"""
import sys

from paraview import servermanager as sm
from paraview.simple import XDMFReader

reader = XDMFReader(FileNames=[sys.argv[1]])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) or [0.0]
npoints = None
for t in times:
    reader.UpdatePipeline(t)
    data = sm.Fetch(reader)
    blocks = {data.GetMetaData(i).Get(data.NAME()): data.GetBlock(i) for i in range(data.GetNumberOfBlocks())}
    drawn = [k for k in ("bodies", "beams", "shells") if k in blocks]
    assert drawn, blocks.keys()
    n = blocks[drawn[0]].GetNumberOfPoints()
    assert n > 0 and (npoints is None or n == npoints), (t, n)
    npoints = n
print(f"steps={len(times)} points={npoints}")
