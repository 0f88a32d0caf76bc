"""A time-varying model in ParaView: the MFA reader advertises its steps, the animation plays
them, and a time between two steps (t = 0.3; steps at 0, 0.2, ..., 1) renders the model at that
instant: the same image as the 3-D model of that instant (what `mfadvr render --time 0.3`
renders), and another one than the neighbouring steps'. MFA Encode with TimeSeries on, given the
same steps as a .pvd collection, builds that 4-D model: the same image at t = 0.3, and the
model file it writes."""
import os
import sys

import pv_scene
import paraview.simple as pvs

pv_scene.load_plugin()
# One fixed camera for every image (no reset to each source's bounds at the first render).
pvs._DisableFirstRenderCameraReset()
data = os.environ["MFADVR_TEST_DATA"]
out = sys.argv[1]
os.makedirs(out, exist_ok=True)

series = pvs.MFAModelReader(FileName=os.path.join(data, "blobs.mfa"))
series.UpdatePipelineInformation()
steps = list(series.TimestepValues)
if [round(t, 9) for t in steps] != [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]:
    sys.exit("blobs.mfa: the reader advertises the steps %s" % (steps,))
scene = pvs.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
if abs(scene.EndTime - 1.0) > 1e-9:
    sys.exit("the animation does not span the model's time range: ends at %s" % scene.EndTime)


def image(source, time, name):
    view = pvs.CreateRenderView()
    view.ViewSize = pv_scene.SIZE
    view.OrientationAxesVisibility = 0
    view.ViewTime = time
    display = pvs.Show(source, view)
    display.Representation = "MFA Volume"
    pvs.ColorBy(display, ("POINTS", "orbiting-blobs"))
    lut = pvs.GetColorTransferFunction("orbiting-blobs")
    lut.RescaleTransferFunction(0.0, 1.0)
    opacity = pvs.GetOpacityTransferFunction("orbiting-blobs")
    opacity.Points = [0.0, 0.0, 0.5, 0.0, 0.4, 0.0, 0.5, 0.0, 0.5, 0.8, 0.5, 0.0, 1.0, 0.8, 0.5, 0.0]
    display.ScalarOpacityUnitDistance = 0.1
    view.CameraPosition = [3.0, 2.0, 4.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraViewAngle = 30.0
    pvs.Render(view)
    path = os.path.join(out, name + ".png")
    pvs.SaveScreenshot(path, view, ImageResolution=pv_scene.SIZE)
    pvs.Delete(view)
    return path


# The data time of the reader's output at a time between the steps.
series.UpdatePipeline(0.3)
if abs(series.GetDataInformation().GetTime() - 0.3) > 1e-9:
    sys.exit("at t = 0.3 the output's DATA_TIME_STEP is %s" % series.GetDataInformation().GetTime())

between = image(series, 0.3, "time-0.3")
instant = image(pvs.MFAModelReader(FileName=os.path.join(data, "blobs-0.3.mfa")), 0.0, "instant-0.3")
step = image(series, 0.2, "time-0.2")

import compare_images  # noqa: E402

same = compare_images.psnr(between, instant)
other = compare_images.psnr(between, step)
print("t = 0.3 vs its 3-D instant: %.1f dB; vs the step t = 0.2: %.1f dB" % (same, other))
if same < 50.0:
    sys.exit("ParaView's t = 0.3 differs from the model's instant (%.1f dB)" % same)
if other > 40.0:
    sys.exit("ParaView rendered the same image at t = 0.3 and at the step t = 0.2 (%.1f dB)" % other)

# MFA Encode of the steps as a file series: one 4-D model, any instant.
collection = pvs.PVDReader(FileName=os.path.join(data, "blobs.pvd"))
written = os.path.join(out, "encoded.mfa")
if os.path.exists(written):
    os.remove(written)
encode = pvs.MFAEncode(Input=collection, TimeSeries=1, ModelFileName=written)
encode.UpdatePipelineInformation()
encode.UpdatePipeline(0.3)
if abs(encode.GetDataInformation().GetTime() - 0.3) > 1e-9:
    sys.exit("MFA Encode at t = 0.3: the output's DATA_TIME_STEP is %s"
             % encode.GetDataInformation().GetTime())
if not os.path.exists(written):
    sys.exit("MFA Encode did not write %s" % written)
encoded = image(encode, 0.3, "encoded-0.3")
same = compare_images.psnr(encoded, between)
print("MFA Encode of blobs.pvd at t = 0.3 vs the model's: %.1f dB" % same)
if same < 50.0:
    sys.exit("MFA Encode's 4-D model at t = 0.3 differs from the model of the same steps (%.1f dB)"
             % same)
print("time series test passed:", out)
