"""Pictures of an alphaflex result (docs/results.md): PNG frames and an animated GIF, colored by a
field, with a camera that frames the model over the whole motion. Runs under ParaView's Python,
offscreen with a virtual X display:

    xvfb-run -a pvpython scripts/render.py OUTDIR/NAME.xdmf -o DIR [--field NAME] [--frames N]
        [--size 1280x720] [--time T] [--warp FACTOR] [--view iso|xy|xz|yz] [--no-annotations]

Writes DIR/NAME_0000.png ... (one per frame, times evenly spread over the output steps) and, with
more than one frame, DIR/NAME.gif. --field: a point or cell array of the result (displacement,
velocity, elastic_displacement, beam or shell results such as M2 or von_mises; default
displacement); a vector is colored by its magnitude. The color range covers the field over every
frame. --warp FACTOR: the points of beam and shell blocks moved by FACTOR × elastic_displacement
(when the result has it), so bending shows on a moving part. --time T: one frame at the output step
nearest to T. The camera looks along −z for a planar model (parallel projection) and from an
oblique direction, z up, otherwise; it is placed once for the bounds of every frame.
"""
import argparse
import math
import os
import sys

from paraview import simple as pv


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("result", help="NAME.xdmf written by alphaflex run or modes")
    ap.add_argument("-o", "--outdir", required=True)
    ap.add_argument("--field", default=None, help="array to color by (default: displacement)")
    ap.add_argument("--frames", type=int, default=24, help="number of frames (default 24; at most the output steps)")
    ap.add_argument("--time", type=float, default=None, help="one frame at the output step nearest to this time")
    ap.add_argument("--size", default="1280x720", help="image size WxH in pixels")
    ap.add_argument("--warp", type=float, default=0.0, help="magnify elastic_displacement of beams and shells by this")
    ap.add_argument("--view", choices=("auto", "iso", "xy", "xz", "yz"), default="auto")
    ap.add_argument("--no-annotations", action="store_true", help="no color bar, no title (tests)")
    a = ap.parse_args()
    try:
        w, h = (int(x) for x in a.size.lower().split("x"))
    except ValueError:
        ap.error(f"--size {a.size}: expected WxH, e.g. 1280x720")
    a.size = (w, h)
    if a.frames < 1:
        ap.error("--frames must be at least 1")
    return a


def arrays(source):
    """{name: (association, components)} of the point and cell arrays of the reader's output."""
    info = source.GetDataInformation().DataInformation
    out = {}
    for assoc, attr in (("POINTS", info.GetPointDataInformation()), ("CELLS", info.GetCellDataInformation())):
        for k in range(attr.GetNumberOfArrays()):
            ai = attr.GetArrayInformation(k)
            out.setdefault(ai.GetName(), (assoc, ai.GetNumberOfComponents()))
    return out


def frame_times(times, frames, at):
    if not times:
        return [0.0]
    if at is not None:
        return [min(times, key=lambda t: abs(t - at))]
    n = min(frames, len(times))
    if n == 1:
        return [times[-1]]
    return [times[round(k * (len(times) - 1) / (n - 1))] for k in range(n)]


def union_bounds(source, times):
    b = [math.inf, -math.inf] * 3
    for t in times:
        source.UpdatePipeline(t)
        bb = source.GetDataInformation().GetBounds()
        for k in range(3):
            b[2 * k] = min(b[2 * k], bb[2 * k])
            b[2 * k + 1] = max(b[2 * k + 1], bb[2 * k + 1])
    return b


def field_range(source, name, assoc, components, times):
    lo, hi = math.inf, -math.inf
    for t in times:
        source.UpdatePipeline(t)
        info = source.GetDataInformation().DataInformation
        attr = info.GetPointDataInformation() if assoc == "POINTS" else info.GetCellDataInformation()
        ai = attr.GetArrayInformation(name)
        if ai is None:
            continue
        r = ai.GetComponentRange(-1 if components > 1 else 0)  # -1: the magnitude of a vector
        lo, hi = min(lo, r[0]), max(hi, r[1])
    if not math.isfinite(lo):
        return 0.0, 1.0
    if hi - lo <= 1e-12 * max(1.0, abs(hi)):
        hi = lo + max(1e-12, 1e-6 * abs(lo))
    return lo, hi


def place_camera(view, b, mode):
    size = [b[1] - b[0], b[3] - b[2], b[5] - b[4]]
    diag = math.sqrt(sum(s * s for s in size)) or 1.0
    c = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    if mode == "auto":
        # Planar: flat, or only as thick as the bodies' shapes drawn about z = 0 (a box of a planar
        # body has a thickness; its centre stays in the plane).
        flat = size[2] <= 1e-9 * diag or (abs(c[2]) <= 1e-9 * diag and size[2] <= 0.1 * diag)
        mode = "xy" if flat else "iso"
    direction, up = {"xy": ((0, 0, 1), (0, 1, 0)), "xz": ((0, -1, 0), (0, 0, 1)),
                     "yz": ((1, 0, 0), (0, 0, 1)), "iso": ((1.0, -1.6, 0.9), (0, 0, 1))}[mode]
    n = math.sqrt(sum(d * d for d in direction))
    view.CameraFocalPoint = c
    view.CameraPosition = [c[k] + 3 * diag * direction[k] / n for k in range(3)]
    view.CameraViewUp = up
    view.CameraParallelProjection = 1 if mode != "iso" else 0
    # ResetCamera with the bounds of every frame: the model stays in the picture as it moves.
    pad = 0.04 * diag
    view.ResetCamera(b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad, b[4] - pad, b[5] + pad)
    if view.CameraParallelProjection:
        # ResetCamera fits the bounding sphere; the box itself, seen square on, fills more: its
        # extents across and up the picture, with a margin of 12 %.
        across, up_axis = {"xy": (0, 1), "xz": (0, 2), "yz": (1, 2)}[mode]
        aspect = view.ViewSize[0] / max(1, view.ViewSize[1])
        half = max(size[up_axis] / 2, size[across] / 2 / aspect) * 1.12
        view.CameraParallelScale = half if half > 0 else diag / 2



def main():
    a = parse_args()
    path = os.path.abspath(a.result)  # ParaView's XDMF reader resolves the HDF5 parts from it
    if not os.path.exists(path):
        sys.exit(f"render.py: {path}: no such file")
    name = os.path.splitext(os.path.basename(path))[0]
    os.makedirs(a.outdir, exist_ok=True)

    reader = pv.XDMFReader(FileNames=[path])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) if hasattr(reader.TimestepValues, "__len__") else [reader.TimestepValues]
    shown = reader
    if a.warp:
        reader.UpdatePipeline(times[0] if times else 0.0)
        if "elastic_displacement" not in arrays(reader):
            sys.exit(f"render.py: {path}: --warp needs the point field elastic_displacement, which this result has not")
        shown = pv.WarpByVector(Input=reader, Vectors=["POINTS", "elastic_displacement"], ScaleFactor=a.warp)
    ftimes = frame_times(times, a.frames, a.time)
    shown.UpdatePipeline(ftimes[0])
    have = arrays(shown)
    field = a.field or ("displacement" if "displacement" in have else next(iter(have), None))
    if field not in have:
        sys.exit(f"render.py: {path}: no field '{field}'; there are: {', '.join(sorted(have))}")
    assoc, comps = have[field]

    view = pv.CreateView("RenderView")
    pv.SetActiveView(view)
    view.ViewSize = list(a.size)
    view.OrientationAxesVisibility = 1
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    disp = pv.Show(shown, view)
    disp.Representation = "Surface"
    disp.PointSize = 9
    disp.LineWidth = 4
    disp.RenderPointsAsSpheres = 1
    disp.RenderLinesAsTubes = 1
    disp.AmbientColor = disp.DiffuseColor = [0.35, 0.35, 0.4]  # blocks without the field
    pv.ColorBy(disp, (assoc, field, "Magnitude") if comps > 1 else (assoc, field))
    lut = pv.GetColorTransferFunction(field)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lo, hi = field_range(shown, field, assoc, comps, ftimes)
    lut.RescaleTransferFunction(lo, hi)
    lut.AutomaticRescaleRangeMode = "Never"
    title = None
    if not a.no_annotations:
        disp.SetScalarBarVisibility(view, True)
        bar = pv.GetScalarBar(lut, view)
        bar.Title = field + (" (magnitude)" if comps > 1 else "")
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
        bar.RangeLabelFormat = "%-#.3g"
        title = pv.Text(Text=name)
        tdisp = pv.Show(title, view)
        tdisp.WindowLocation = "Upper Left Corner"
        tdisp.FontSize = 14
        tdisp.Color = [0.1, 0.1, 0.1]
    else:
        disp.SetScalarBarVisibility(view, False)
        view.OrientationAxesVisibility = 0
    place_camera(view, union_bounds(shown, ftimes), a.view)

    written = []
    for k, t in enumerate(ftimes):
        view.ViewTime = t
        if title is not None:
            title.Text = f"{name}   t = {t:.4g}" + (f"   (elastic displacement x{a.warp:g})" if a.warp else "")
        png = os.path.join(a.outdir, f"{name}_{k:04d}.png")
        pv.SaveScreenshot(png, view, ImageResolution=list(a.size))
        written.append(png)
    print(f"render.py: {len(written)} frame(s) of {field} in {a.outdir} ({os.path.basename(written[0])} ...)")
    if len(written) > 1:
        try:
            from PIL import Image  # Pillow (python3-pil, installed with python3-matplotlib)
        except ImportError:
            print("render.py: no animation: Pillow (python3-pil) is not installed")
            return
        images = [Image.open(p).convert("P", palette=Image.ADAPTIVE) for p in written]
        gif = os.path.join(a.outdir, name + ".gif")
        images[0].save(gif, save_all=True, append_images=images[1:], duration=100, loop=0)
        print(f"render.py: animation {gif}")


if __name__ == "__main__":
    main()
