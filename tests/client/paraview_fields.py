"""Run by pvbatch (tests/client/paraview_test.sh): opens each fields.xdmf as ParaView does, lists
its time steps and arrays, checks them, and renders the first file's last time step to a PNG.
  pvbatch paraview_fields.py PARTICLE_XDMF CONTINUUM_XDMF OUT.png"""
import os
import sys

from paraview.simple import (ColorBy, CreateView, OpenDataFile, SaveScreenshot, Show)

particle, continuum, png = sys.argv[1:4]
failures = []


def open_fields(name, expected):
    reader = OpenDataFile(name)
    if reader is None:
        failures.append(f"{name}: ParaView has no reader for it")
        return None, []
    reader.UpdatePipelineInformation()
    times = reader.TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    reader.UpdatePipeline(times[-1])
    info = reader.GetDataInformation()
    cells = [reader.CellData[i].GetName() for i in range(len(reader.CellData))]
    points = [reader.PointData[i].GetName() for i in range(len(reader.PointData))]
    print(f"{name}: reader {reader.GetXMLName()}, {len(times)} time steps {times}, "
          f"{info.GetNumberOfCells()} cells; cell arrays {cells}; point arrays {points}")
    if info.GetNumberOfCells() == 0:
        failures.append(f"{name}: no cells at time {times[-1]}")
    for array in expected:
        if array not in cells + points:
            failures.append(f"{name}: no array {array}")
    return reader, times


reader, times = open_fields(particle, ["density", "temperature_kinetic", "velocity",
                                       "temperature_kinetic_stderr"])
if len(times) < 2:
    failures.append(f"{particle}: {len(times)} time steps, expected the run's snapshots")
open_fields(continuum, ["T", "velocity", "p"])

if reader is not None:
    view = CreateView("RenderView")
    view.ViewSize = [500, 500]
    view.ViewTime = times[-1]
    view.OrientationAxesVisibility = 0
    display = Show(reader, view)
    display.SetRepresentationType("Surface")
    ColorBy(display, ("CELLS", "temperature_kinetic"))
    display.RescaleTransferFunctionToDataRange(True)
    view.ResetCamera()
    SaveScreenshot(png, view)
    # The picture shows the field: many colours, not one.
    from vtkmodules.vtkIOImage import vtkPNGReader
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    colours = image.GetOutput().GetPointData().GetScalars()
    distinct = {colours.GetTuple(i) for i in range(0, colours.GetNumberOfTuples(), 7)}
    print(f"{png}: {len(distinct)} distinct colours")
    if len(distinct) < 10:
        failures.append(f"{png}: {len(distinct)} distinct colours: the field is not drawn")

for f in failures:
    print("FAIL:", f)
print("paraview: passed" if not failures else "paraview: failed", flush=True)
# Leave without ParaView's teardown: under Xvfb it ends with a GLX error after a good run.
os._exit(1 if failures else 0)
