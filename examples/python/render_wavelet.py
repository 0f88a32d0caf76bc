#!/usr/bin/python3
"""Encode VTK's wavelet source as an MFA model and render it with vtkMFAVolumeMapper next to an
opaque sphere that cuts into the volume.

Run with Debian's Python (which has python3-vtk9) and the build's Python folder on the path:
    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/render_wavelet.py out.png
Without a display, prefix `xvfb-run -a`. Without an output file it opens an interactive window.
"""
import sys

from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkInteractionStyle import vtkInteractorStyleTrackballCamera
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderWindow, vtkRenderWindowInteractor, vtkRenderer,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction

import mfadvr


def main(out=None):
    # A 31^3 sample of the wavelet; the encoder fits a cubic B-spline with 16^3 control points.
    source = vtkRTAnalyticSource()
    source.SetWholeExtent(-15, 15, -15, 15, -15, 15)
    encoder = mfadvr.vtkMFAEncoder()
    encoder.SetInputConnection(source.GetOutputPort())
    encoder.SetNumberOfControlPoints(16, 16, 16)
    encoder.Update()
    print("fit: max error %.4f of the range, RMS %.5f, %.2f s" %
          (encoder.GetLastMaxRelativeError(), encoder.GetLastRMSRelativeError(),
           encoder.GetLastFitSeconds()))

    mapper = mfadvr.vtkMFAVolumeMapper()
    mapper.SetInputConnection(encoder.GetOutputPort())

    color = vtkColorTransferFunction()
    color.AddRGBPoint(40.0, 0.23, 0.30, 0.75)
    color.AddRGBPoint(160.0, 0.87, 0.87, 0.87)
    color.AddRGBPoint(280.0, 0.71, 0.02, 0.15)
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(40.0, 0.0)
    opacity.AddPoint(280.0, 0.6)
    prop = vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(2.0)
    prop.ShadeOn()
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    sphere = vtkSphereSource()
    sphere.SetCenter(8, 0, 8)
    sphere.SetRadius(7)
    sphere.SetThetaResolution(48)
    sphere.SetPhiResolution(48)
    sphere_mapper = vtkPolyDataMapper()
    sphere_mapper.SetInputConnection(sphere.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(sphere_mapper)
    actor.GetProperty().SetColor(0.9, 0.8, 0.3)

    renderer = vtkRenderer()
    renderer.AddVolume(volume)
    renderer.AddActor(actor)
    renderer.SetBackground(0.1, 0.1, 0.12)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Azimuth(30)
    renderer.GetActiveCamera().Elevation(20)
    renderer.ResetCameraClippingRange()
    window = vtkRenderWindow()
    window.AddRenderer(renderer)
    window.SetSize(600, 600)

    if out:
        window.SetOffScreenRendering(1)
        window.Render()
        grab = vtkWindowToImageFilter()
        grab.SetInput(window)
        writer = vtkPNGWriter()
        writer.SetFileName(out)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
        print("wrote", out, "in %.3f s per frame" % mapper.GetTimeToDraw())
    else:
        interactor = vtkRenderWindowInteractor()
        interactor.SetInteractorStyle(vtkInteractorStyleTrackballCamera())
        interactor.SetRenderWindow(window)
        window.Render()
        interactor.Start()


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
