"""ParaView's Blend Mode reaches the MFA Volume representation's mapper: Isosurface (the mode
ParaView 5.11 offers besides Composite and Slice) with two Isosurface Values changes the image,
which is not empty, and Composite brings the composite image back. The representation's
curvature transfer function and contour width change the composite and isosurface images."""
import os
import sys

import pv_scene
import paraview.simple as pvs

os.makedirs(sys.argv[1], exist_ok=True)
pv_scene.load_plugin()
display = pv_scene.render("single", os.path.join(sys.argv[1], "blend-composite.png"))
view = pvs.GetActiveView()


def pixels(name):
    path = os.path.join(sys.argv[1], name + ".png")
    pvs.Render(view)
    pvs.SaveScreenshot(path, view, ImageResolution=pv_scene.SIZE)
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    r = vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).astype(float)


def differs(a, b):
    return abs(a - b).mean() > 2.0


composite = pixels("blend-composite")
available = display.GetProperty("BlendMode").Available
print("blend modes offered:", available)
if "Isosurface" not in available:
    sys.exit("ParaView offers no Isosurface blend mode: %s" % (available,))
display.BlendMode = "Isosurface"
display.IsosurfaceValues = [0.5, 0.7]
iso = pixels("blend-iso")
display.BlendMode = "Composite"
back = pixels("blend-composite-again")
if not differs(iso, composite):
    sys.exit("iso: the image is the composite one: the blend mode did not reach the mapper")
if iso.max() < 40:
    sys.exit("iso: the image is empty")
if differs(back, composite):
    sys.exit("back to Composite: the image is not the composite one")
display.MFACurvatureTransferFunction = "mean"
curvature = pixels("curvature-mean")
if not differs(curvature, composite):
    sys.exit("curvature transfer function: the composite image did not change")
display.MFACurvatureTransferFunction = ""
display.BlendMode = "Isosurface"
display.MFAContourWidth = 3.0
contours = pixels("iso-contours")
if not differs(contours, iso):
    sys.exit("contours: the isosurface image did not change")
display.MFAContourWidth = 0.0
display.BlendMode = "Composite"
print("blend modes, curvature and contours reach the mapper; ParaView offers", available)
