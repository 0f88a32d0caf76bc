"""The Python bindings from Debian's /usr/bin/python3: import, encode, render off screen next to
an opaque sphere, read the window back and check what is on it; then the reader's output port on
the mapper's standard port, as every VTK program connects a pipeline. Run by ctest under xvfb-run
with the build's python folder on PYTHONPATH; the argument is the mfadvr executable (it writes the
model file the reader reads)."""
import os
import subprocess
import sys
import tempfile

import mfadvr
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderWindow, vtkRenderer, vtkVolume,
                                         vtkVolumeProperty, vtkWindowToImageFilter)


def check(condition, message):
    if not condition:
        print("FAILED:", message)
        sys.exit(1)


source = vtkRTAnalyticSource()
source.SetWholeExtent(-10, 10, -10, 10, -10, 10)
encoder = mfadvr.vtkMFAEncoder()
encoder.SetInputConnection(source.GetOutputPort())
encoder.SetNumberOfControlPoints(12, 12, 12)
encoder.Update()
model = encoder.GetOutput()
check(isinstance(model, mfadvr.vtkMFAModelData), "the encoder gives a vtkMFAModelData")
check(model.HasModel(), "the encoder made a model")
bounds = list(model.GetBounds())
check(bounds == [-10.0, 10.0, -10.0, 10.0, -10.0, 10.0], "bounds %s" % bounds)
check(0.0 < encoder.GetLastMaxRelativeError() < 0.2, "fit error %g" % encoder.GetLastMaxRelativeError())
# The model at a sample is within the reported maximum error of the sample.
sample = source.GetOutput().GetScalarComponentAsDouble(3, -4, 5, 0)
low, high = model.GetScalarRange()
value = model.EvaluateValue(3.0, -4.0, 5.0)
check(abs(value - sample) <= encoder.GetLastMaxRelativeError() * (high - low) + 1e-3,
      "model %g vs sample %g" % (value, sample))

mapper = mfadvr.vtkMFAVolumeMapper()
mapper.SetInputConnection(encoder.GetOutputPort())
color = vtkColorTransferFunction()
color.AddRGBPoint(40.0, 0.2, 0.3, 0.8)
color.AddRGBPoint(280.0, 0.9, 0.1, 0.1)
opacity = vtkPiecewiseFunction()
opacity.AddPoint(40.0, 0.0)
opacity.AddPoint(280.0, 0.5)
prop = vtkVolumeProperty()
prop.SetColor(color)
prop.SetScalarOpacity(opacity)
prop.ShadeOn()
volume = vtkVolume()
volume.SetMapper(mapper)
volume.SetProperty(prop)

sphere = vtkSphereSource()
sphere.SetCenter(0, 0, 0)
sphere.SetRadius(4)
sphere_mapper = vtkPolyDataMapper()
sphere_mapper.SetInputConnection(sphere.GetOutputPort())
actor = vtkActor()
actor.SetMapper(sphere_mapper)
actor.GetProperty().SetColor(0.0, 1.0, 0.0)

renderer = vtkRenderer()
renderer.AddVolume(volume)
renderer.AddActor(actor)
renderer.ResetCamera()
window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.AddRenderer(renderer)
window.SetSize(96, 96)
window.Render()
check(mapper.GetTimeToDraw() > 0.0, "the mapper rendered")
# The render device: auto by default, reported after the frame (the GPU or the CPU with a reason).
check(mapper.GetDevice() == mfadvr.vtkMFAVolumeMapper.DeviceAuto, "auto is the default device")
check(mapper.GetLastDevice() in (mfadvr.vtkMFAVolumeMapper.DeviceCPU,
                                 mfadvr.vtkMFAVolumeMapper.DeviceCUDA), "a device was used")
check(len(mapper.GetLastDeviceDescription()) > 0, "the device is described")

grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.Update()
image = grab.GetOutput()
scalars = image.GetPointData().GetScalars()
covered = 0
for i in range(scalars.GetNumberOfTuples()):
    if max(scalars.GetTuple(i)[:3]) > 8:
        covered += 1
check(covered > 0.3 * scalars.GetNumberOfTuples(), "the volume covers the view (%d)" % covered)
centre = scalars.GetTuple(48 * 96 + 48)
# The sphere (pure green) sits inside the volume: the volume in front tints it, so the centre
# is neither the bare sphere nor without it.
check(centre[1] > 40 and centre[0] > 10, "sphere seen through the volume: %s" % (centre,))
# A model file through vtkMFAReader, connected the standard way; the alias of the old MFA port
# gives the same picture.
def rendered_pixels():
    window.Render()
    grab.Modified()
    grab.Update()
    out = grab.GetOutput().GetPointData().GetScalars()
    return [out.GetTuple(i) for i in range(out.GetNumberOfTuples())]


with tempfile.TemporaryDirectory() as scratch:
    path = os.path.join(scratch, "wavelet.mfa")
    subprocess.run([sys.argv[1], "encode", "builtin:marschner-lobb:24", "--ctrl", "12", "-o", path,
                    "-q"], check=True)
    reader = mfadvr.vtkMFAReader()
    reader.SetFileName(path)
    mapper.SetInputConnection(reader.GetOutputPort())
    color.RemoveAllPoints()
    color.AddRGBPoint(0.0, 0.9, 0.9, 0.9)
    color.AddRGBPoint(1.0, 0.9, 0.4, 0.1)
    opacity.RemoveAllPoints()
    opacity.AddPoint(0.0, 0.0)
    opacity.AddPoint(1.0, 0.8)
    volume.SetScale(10, 10, 10)  # the model's box is [-1,1]^3
    renderer.ResetCamera()
    via_reader = rendered_pixels()
    check(mapper.GetMFAInput() is not None and mapper.GetMFAInput().HasModel(),
          "the mapper renders the reader's model")
    lit = sum(1 for p in via_reader if max(p[:3]) > 8)
    check(lit > 0.3 * len(via_reader), "the reader's model is drawn (%d pixels)" % lit)
    mapper.SetMFAInputConnection(reader.GetOutputPort())
    check(rendered_pixels() == via_reader, "SetMFAInputConnection is an alias")

print("python smoke test passed: %d of %d pixels covered, centre %s" %
      (covered, scalars.GetNumberOfTuples(), centre))
