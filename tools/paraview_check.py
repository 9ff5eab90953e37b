"""Does ParaView draw a run's particles?  For each XDMF file, with the reader ParaView picks itself
(OpenDataFile: Xdmf3ReaderS in 5.11) and with the legacy XDMFReader, at the last time: the points
and cells the reader makes, and the pixels that are not background in a render of the default
representation.  Prints one line per file and reader; exit status 1 unless every reader gives N
points, N cells and a picture that is not blank.  Run by tests/check_paraview.sh:

  pvbatch tools/paraview_check.py PNG XMF N [XMF N ...]

PNG: the scratch screenshot (overwritten for every render)."""
import sys

from paraview.simple import (CreateRenderView, Delete, OpenDataFile, Render, ResetCamera, SaveScreenshot, Show,
                             XDMFReader)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

if len(sys.argv) < 4 or len(sys.argv) % 2:
    sys.exit(__doc__)
png, ok = sys.argv[1], True
view = CreateRenderView()  # one view for every render: a view costs about a second
view.ViewSize, view.OrientationAxesVisibility = [400, 300], 0
try:  # ParaView >= 5.10 takes the background from its palette unless told
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.Background = [0, 0, 0]
for xmf, n in zip(sys.argv[2::2], map(int, sys.argv[3::2])):
    for name in ("default", "XDMFReader"):
        reader = OpenDataFile(xmf) if name == "default" else XDMFReader(FileNames=[xmf])
        reader.UpdatePipelineInformation()
        t = reader.TimestepValues[-1] if reader.TimestepValues else 0.0
        reader.UpdatePipeline(t)
        info = reader.GetDataInformation()
        points, cells = info.GetNumberOfPoints(), info.GetNumberOfCells()
        view.ViewTime = t
        shown = Show(reader, view)
        ResetCamera(view)
        Render(view)
        SaveScreenshot(png, view, ImageResolution=[400, 300])
        image = vtkPNGReader()
        image.SetFileName(png)
        image.Update()
        lit = int((vtk_to_numpy(image.GetOutput().GetPointData().GetScalars())[:, :3].max(axis=1) > 0).sum())
        good = points == n and cells == n and lit > 0
        representation = shown.GetProperty("Representation").GetData()
        ok &= good
        print(f"{xmf}: {name} ({reader.GetXMLName()}) t = {t:g}: {points} points, {cells} cells of {n} particles, "
              f"{representation} view: {lit} pixels drawn{'' if good else '  <-- FAIL'}")
        Delete(shown)
        Delete(reader)
Delete(view)  # pvbatch crashes at exit when a render view is left
sys.exit(0 if ok else 1)
