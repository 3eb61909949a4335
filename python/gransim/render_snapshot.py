"""Draw one snapshot (DIR/snapshots/snap_NNNNNN.vtp) as ParaView would, with VTK's own renderer
off screen: each grain's outline filled and coloured by a cell array (speed, species, contacts
…), a scalar bar, the time in a corner. Needs python3-vtk9 and an X display (or xvfb-run):

    xvfb-run -a python3 -m gransim.render_snapshot RUN/snapshots/snap_000004.vtp out.png \\
        --color-by speed
"""
import argparse
import sys

from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)
from vtkmodules.vtkCommonCore import vtkLookupTable
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (registers the OpenGL window)
import vtkmodules.vtkRenderingFreeType  # noqa: F401  (text)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("vtp")
    ap.add_argument("png")
    ap.add_argument("--color-by", default="speed",
                    help="cell array: speed, species, contacts, omega, radius … (default speed)")
    ap.add_argument("--size", default="900x900", help="WxH in px")
    a = ap.parse_args(argv)
    width, height = (int(v) for v in a.size.split("x"))

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(a.vtp)
    reader.Update()
    data = reader.GetOutput()
    if data.GetNumberOfCells() == 0:
        sys.exit("render_snapshot: %s has no grains" % a.vtp)
    array = data.GetCellData().GetArray(a.color_by)
    if array is None:
        names = [data.GetCellData().GetArrayName(k)
                 for k in range(data.GetCellData().GetNumberOfArrays())]
        sys.exit("render_snapshot: no cell array %r (have %s)" % (a.color_by, ", ".join(names)))
    lo, hi = array.GetRange(-1 if array.GetNumberOfComponents() > 1 else 0)
    if hi <= lo:
        hi = lo + 1.0

    lut = vtkLookupTable()
    if a.color_by == "species":
        lut.SetNumberOfTableValues(max(2, int(hi) + 1))
        lo, hi = 0, max(1, int(hi))
    lut.SetHueRange(0.667, 0.0)  # blue → red, as ParaView's rainbow
    lut.Build()
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(data)
    mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectColorArray(a.color_by)
    mapper.SetLookupTable(lut)
    mapper.SetScalarRange(lo, hi)
    mapper.ScalarVisibilityOn()
    grains = vtkActor()
    grains.SetMapper(mapper)
    # the outlines drawn over the fill, so that touching grains stay apart
    edges = vtkActor()
    edge_mapper = vtkPolyDataMapper()
    edge_mapper.SetInputData(data)
    edge_mapper.ScalarVisibilityOff()
    edges.SetMapper(edge_mapper)
    edges.GetProperty().SetRepresentationToWireframe()
    edges.GetProperty().SetColor(0.1, 0.1, 0.1)
    edges.GetProperty().SetLineWidth(1.0)

    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(a.color_by)
    bar.SetNumberOfLabels(5)
    bar.SetWidth(0.08)
    bar.SetHeight(0.5)
    bar.SetPosition(0.9, 0.25)
    t = data.GetFieldData().GetArray("TimeValue")
    tap = data.GetFieldData().GetArray("Tap")
    label = "t = %.4g s" % t.GetValue(0) if t else ""
    if tap is not None and tap.GetValue(0) >= 0:
        label += "   tap %d" % tap.GetValue(0)
    text = vtkTextActor()
    text.SetInput(label)
    text.GetTextProperty().SetFontSize(20)
    text.GetTextProperty().SetColor(0, 0, 0)
    text.SetDisplayPosition(12, 12)

    ren = vtkRenderer()
    ren.SetBackground(1, 1, 1)
    for actor in (grains, edges, bar, text):
        ren.AddActor(actor)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(ren)
    ren.ResetCamera()
    ren.GetActiveCamera().ParallelProjectionOn()
    ren.ResetCamera()
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    png = vtkPNGWriter()
    png.SetFileName(a.png)
    png.SetInputConnection(grab.GetOutputPort())
    png.Write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
