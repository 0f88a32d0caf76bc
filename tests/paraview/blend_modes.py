"""ParaView's volume properties reach the MFA Volume representation's mapper: Blend Mode
(maximum intensity, isosurface with Isosurface Values) and the cropping box change the image,
and each image matches the one mfadvr's ray caster gives for the same settings only through the
mapper (so here: they differ from the composite image and from each other, and are not empty)."""
import os
import sys

import pv_scene
import paraview.simple as pvs

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
display.BlendMode = "Maximum Intensity"
mip = pixels("blend-max")
display.BlendMode = "Isosurface"
display.IsosurfaceValues = [0.5, 0.7]
iso = pixels("blend-iso")
display.BlendMode = "Composite"
display.Cropping = 1
display.CroppingOrigin = [-1.0, -1.0, -1.0]
display.CroppingScale = [0.6, 1.0, 1.0]
cropped = pixels("blend-cropped")
for name, image in (("max", mip), ("iso", iso), ("cropped", cropped)):
    if not differs(image, composite):
        sys.exit(name + ": the image is the composite one: the setting did not reach the mapper")
    if image.max() < 40:
        sys.exit(name + ": the image is empty")
if not differs(mip, iso):
    sys.exit("max and iso gave the same image")
print("blend modes and cropping reach the mapper")
