"""ParaView's Blend Mode reaches the MFA Volume representation's mapper: Isosurface (the mode
ParaView 5.11 offers besides Composite and Slice) with two Isosurface Values changes the image,
which is not empty, and Composite brings the composite image back."""
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
print("blend modes reach the mapper; ParaView offers", available)
