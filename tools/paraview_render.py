"""Render a run's snapshots with ParaView (pvbatch): the water coloured by a field, walls and solids
grey, one PNG per time.  Run through tools/paraview_render.sh (it supplies a virtual display when
there is none):

  tools/paraview_render.sh OUTDIR PNGBASE [t1 t2 ...] [--field p|rho|v] [--size 1200x600] [--3d]

--3d: an oblique perspective view, the walls faint (a 3D run's XYZ geometry).

Reads OUTDIR/particles.xmf (every snapshot) as ParaView's Xdmf reader does; writes PNGBASE_t<t>.png
for the snapshot nearest each time (default: the last one)."""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, GetScalarBar, Render,
                             ResetCamera, SaveScreenshot, Show, Threshold, XDMFReader)

args = sys.argv[1:]
field, size, three_d = "p", (1200, 600), "--3d" in args
args = [a for a in args if a != "--3d"]
if "--field" in args:
    i = args.index("--field"); field = args[i + 1]; del args[i:i + 2]
if "--size" in args:
    i = args.index("--size"); size = tuple(int(s) for s in args[i + 1].split("x")); del args[i:i + 2]
if len(args) < 2:
    sys.exit(__doc__)
outdir, base, times = args[0], args[1], [float(t) for t in args[2:]]
reader = XDMFReader(FileNames=[outdir + "/particles.xmf"])
reader.UpdatePipelineInformation()
steps = list(reader.TimestepValues) or [0.0]
if field not in reader.PointData.keys():
    sys.exit(f"no point field {field} in {outdir}/particles.xmf (fields: {', '.join(reader.PointData.keys())})")
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = list(size)
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 0
try:  # ParaView >= 5.10 keeps the background in a palette unless told
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
water = Threshold(Input=reader, Scalars=["POINTS", "kind"])
walls = Threshold(Input=reader, Scalars=["POINTS", "kind"])
try:  # the threshold's range: ParaView 5.10+ names it LowerThreshold / UpperThreshold
    water.LowerThreshold, water.UpperThreshold = -0.5, 0.5
    walls.LowerThreshold, walls.UpperThreshold = 0.5, 4.5
except AttributeError:
    water.ThresholdRange, walls.ThresholdRange = [-0.5, 0.5], [0.5, 4.5]
shown_walls = Show(walls, view)
shown_walls.SetRepresentationType("Points")
ColorBy(shown_walls, None)
shown_walls.AmbientColor = shown_walls.DiffuseColor = [0.5, 0.5, 0.5]
if three_d:
    shown_walls.Opacity = 0.15
shown_water = Show(water, view)
shown_water.SetRepresentationType("Points")
shown_water.PointSize = 2
ColorBy(shown_water, ("POINTS", field, "Magnitude") if field == "v" else ("POINTS", field))
shown_water.SetScalarBarVisibility(view, True)
lut = GetColorTransferFunction(field)
lut.ApplyPreset("Viridis (matplotlib)", True)
bar = GetScalarBar(lut, view)
bar.Title, bar.ComponentTitle = {"p": "p (Pa)", "rho": "rho (kg/m3)", "v": "|v| (m/s)"}.get(field, field), ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
for t in times or [steps[-1]]:
    near = min(steps, key=lambda s: abs(s - t))
    view.ViewTime = near
    reader.UpdatePipeline(near)
    water.UpdatePipeline(near)  # the colour range of this time's water, not the first time's
    shown_water.RescaleTransferFunctionToDataRange(False, True)
    if three_d:  # from the front left, above: x along the tank, z up
        b = reader.GetDataInformation().GetBounds()
        c = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
        span = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
        view.CameraFocalPoint = c
        view.CameraPosition = [c[0] - 0.25 * span, c[1] - 0.9 * span, c[2] + 0.6 * span]
        view.CameraViewUp = [0, 0, 1]
        ResetCamera(view)
    else:
        ResetCamera(view)
        view.CameraParallelProjection = 1
    Render(view)
    png = f"{base}_t{near:.3f}.png"
    SaveScreenshot(png, view, ImageResolution=list(size))
    print(f"{png}: {outdir} at t = {near:g} s, {field}")
