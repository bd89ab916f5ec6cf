"""Opens the XDMF files of the same run on one and on N ranks with ParaView's reader (run under
pvpython) and checks that ParaView sees the same thing: the same time steps, the same blocks
(bodies, beams, shells, joints) with the same numbers of points and cells, the same cell types
and connectivity, the same point and cell arrays (names, components) and the same point positions
(to 1e-10 of the model's size; the runs differ by round-off only, tests/scenes/compare_ranks.py
compares their values).

usage: pvpython paraview_compare.py ABSOLUTE/PATH/ONE_RANK.xdmf ABSOLUTE/PATH/N_RANKS.xdmf
"""
import sys

from paraview import servermanager as sm
from paraview.simple import XDMFReader
from vtk.util.numpy_support import vtk_to_numpy
import numpy as np


def read(path):
    reader = XDMFReader(FileNames=[path])
    reader.UpdatePipelineInformation()
    return reader, list(reader.TimestepValues)


def blocks(reader, t):
    reader.UpdatePipeline(t)
    data = sm.Fetch(reader)
    return {data.GetMetaData(i).Get(data.NAME()): data.GetBlock(i) for i in range(data.GetNumberOfBlocks())}


def arrays(attrs):
    return {attrs.GetArrayName(k): attrs.GetArray(k).GetNumberOfComponents() for k in range(attrs.GetNumberOfArrays())}


def cells(grid):
    out = []
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        out.append((grid.GetCellType(c), tuple(ids.GetId(k) for k in range(ids.GetNumberOfIds()))))
    return out


one_path, many_path = sys.argv[1], sys.argv[2]
one, t_one = read(one_path)
many, t_many = read(many_path)
assert t_one == t_many, f"time steps differ: {t_one} vs {t_many}"
assert len(t_one) > 1, "expected several output steps"
for t in (t_one[0], t_one[-1]):
    b1, bn = blocks(one, t), blocks(many, t)
    assert set(b1) == set(bn), f"blocks differ at t = {t}: {sorted(b1)} vs {sorted(bn)}"
    for name in b1:
        g1, gn = b1[name], bn[name]
        assert g1.GetNumberOfPoints() == gn.GetNumberOfPoints(), (name, "points")
        assert g1.GetNumberOfCells() == gn.GetNumberOfCells(), (name, "cells")
        assert cells(g1) == cells(gn), f"{name}: cell types or connectivity differ"
        assert arrays(g1.GetPointData()) == arrays(gn.GetPointData()), (name, "point arrays")
        assert arrays(g1.GetCellData()) == arrays(gn.GetCellData()), (name, "cell arrays")
        p1, pn = vtk_to_numpy(g1.GetPoints().GetData()), vtk_to_numpy(gn.GetPoints().GetData())
        size = max(np.abs(p1).max(), 1.0)
        assert np.abs(p1 - pn).max() <= 1e-10 * size, f"{name}: positions differ by {np.abs(p1 - pn).max()}"
print(f"ParaView opens {one_path} and {many_path} alike: {len(t_one)} steps, blocks {sorted(b1)}")
