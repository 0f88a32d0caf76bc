"""ParaView's Blend Mode reaches the MFA Volume representation's mapper: Isosurface (the mode
ParaView 5.11 offers besides Composite and Slice) with two Isosurface Values changes the image,
which is not empty, and Composite brings the composite image back. The representation's
curvature transfer function and contour width change the composite and isosurface images. Its
own MFA Blend Mode (maximum, minimum, average intensity, additive) overrides ParaView's and
gives it back with "As Blend Mode"; ParaView's cropping box crops (fewer lit pixels, the
uncropped image back when it is off); ParaView's 2-D transfer function (Use Transfer 2D, a box
of the 2-D editor) replaces the 1-D maps. MFA Device chooses where the mapper renders and MFA
Device In Use says where it did: CPU gives the automatic choice's image, on the CPU."""
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

# The representation's own blend modes: each image differs from the composite one and from the
# others, none is empty; "As Blend Mode" gives ParaView's back.
offered = display.GetProperty("MFABlendMode").Available
print("MFA blend modes offered:", offered)
images = {}
for mode in ("Maximum Intensity", "Minimum Intensity", "Average Intensity", "Additive"):
    display.MFABlendMode = mode
    images[mode] = pixels("mfa-blend-" + mode.split()[0].lower())
    if not differs(images[mode], composite):
        sys.exit(f"MFA Blend Mode {mode}: the image is the composite one")
    if images[mode].max() < 40:
        sys.exit(f"MFA Blend Mode {mode}: the image is empty")
if not differs(images["Maximum Intensity"], images["Minimum Intensity"]):
    sys.exit("maximum and minimum intensity give one image")
display.MFABlendMode = "As Blend Mode"
if differs(pixels("mfa-blend-as-paraview"), composite):
    sys.exit("MFA Blend Mode As Blend Mode: the composite image did not come back")


def lit(image):
    """Pixels that differ from the background (the first pixel, a corner)."""
    return int((abs(image - image[0]).max(axis=1) > 20).sum())


# ParaView's cropping box: the data bounds scaled by CroppingScale, then moved by CroppingOrigin
# (planes = origin + scale * bounds). Keep the half x >= centre: scale 1/2, origin xmax / 2.
bounds = display.GetRepresentedDataInformation().GetBounds()
display.UseCropping = 1
display.CroppingScale = [0.5, 1.0, 1.0]
display.CroppingOrigin = [0.5 * bounds[1], 0.0, 0.0]
cropped = pixels("cropped")
display.UseCropping = 0
uncropped = pixels("uncropped")
print("lit pixels: cropped", lit(cropped), "uncropped", lit(uncropped), "composite",
      lit(composite))
if not lit(cropped) < 0.8 * lit(composite):
    sys.exit("cropping: the image is not smaller than the uncropped one")
if differs(uncropped, composite):
    sys.exit("cropping off: the uncropped image did not come back")

# ParaView's 2-D transfer function: one opaque green box over the upper half of the values and
# every gradient; the image turns green where the 1-D maps were cool to warm.
array = display.ColorArrayName[1]
tf2d = pvs.GetTransferFunction2D(array, display)
lo, hi = display.LookupTable.RGBPoints[0], display.LookupTable.RGBPoints[-4]
tf2d.Range = [lo, hi, 0.0, 1.0]
tf2d.Boxes = [lo + 0.5 * (hi - lo), 0.0, 0.5 * (hi - lo), 1.0, 0.0, 1.0, 0.0, 0.8]
display.TransferFunction2D = tf2d
display.UseTransfer2D = 1
green = pixels("transfer-2d")
display.UseTransfer2D = 0
mean = green.reshape(-1, green.shape[-1])[:, :3].mean(axis=0)
print("2-D transfer function: mean colour", mean)
if not differs(green, composite) or not (mean[1] > mean[0] and mean[1] > mean[2]):
    sys.exit(f"2-D transfer function: the image is not the green box's (mean {mean})")
if differs(pixels("transfer-1d-again"), composite):
    sys.exit("Use Transfer 2D off: the composite image did not come back")


# The device: Auto (the default) and CPU render the same image; MFA Device In Use says where.
def device_in_use():
    display.UpdatePropertyInformation()
    return display.GetProperty("MFADeviceInUse").GetData()


print("MFA Device offered:", display.GetProperty("MFADevice").Available)
automatic = pixels("device-auto")
auto_in_use = device_in_use()
display.MFADevice = "CPU"
on_cpu = pixels("device-cpu")
cpu_in_use = device_in_use()
display.MFADevice = "Auto"
print("device in use: Auto ->", repr(auto_in_use), "; CPU ->", repr(cpu_in_use))
if not cpu_in_use.startswith("CPU"):
    sys.exit(f"MFA Device CPU: the device in use is {cpu_in_use!r}")
if not auto_in_use:
    sys.exit("MFA Device In Use is empty after an automatic frame")
if auto_in_use.startswith("CPU") and differs(automatic, on_cpu):
    sys.exit("MFA Device CPU: the image is not the automatic choice's (also on the CPU)")
print("blend modes, cropping, the 2-D transfer function, curvature, contours and the device "
      "reach the mapper; ParaView offers", available)
