"""The plugin in pvpython: its proxies, the MFA Volume representation type, both kinds of model
file, and a rendered image that is not empty."""
import os
import sys

import pv_scene
import paraview.simple as pvs
from paraview import servermanager as sm

pv_scene.load_plugin()
for name in ("MFAModelReader", "MFAEncode"):
    if not hasattr(pvs, name):
        sys.exit("the plugin did not define " + name)

reader = pvs.MFAModelReader(FileName=os.path.join(os.environ["MFADVR_TEST_DATA"], "single.mfa"))
reader.UpdatePipeline()
info = reader.GetDataInformation()
bounds = info.GetBounds()
if [round(b, 6) for b in bounds] != [-1, 1, -1, 1, -1, 1]:
    sys.exit("single.mfa: unexpected bounds %s" % (bounds,))
if info.GetNumberOfPoints() != 41 ** 3:
    sys.exit("single.mfa: the carrier should sample the model on its 41^3 data grid")
blocks = pvs.MFAModelReader(FileName=os.path.join(os.environ["MFADVR_TEST_DATA"], "blocks.mfa"))
blocks.UpdatePipeline()
if [round(b, 6) for b in blocks.GetDataInformation().GetBounds()] != [-1, 1, -1, 1, -1, 1]:
    sys.exit("blocks.mfa: unexpected bounds")

# MFA Encode of a point cloud with Auto Smoothing: the weight is chosen (and shown nowhere but in
# the fit); the encode succeeds and the model spans the points.
points = pvs.MaskPoints(Input=pvs.Wavelet(WholeExtent=[0, 15, 0, 15, 0, 15]), OnRatio=3,
                        GenerateVertices=1, MaximumNumberofPoints=100000)
encode = pvs.MFAEncode(Input=points)
if encode.GetProperty("AutoSmoothing") is None:
    sys.exit("MFAEncode has no AutoSmoothing property")
encode.AutoSmoothing = 1
encode.UpdatePipeline()
if encode.GetDataInformation().GetNumberOfPoints() == 0:
    sys.exit("MFA Encode with AutoSmoothing gave an empty model")

view = pvs.CreateRenderView()
display = pvs.Show(reader, view)
types = display.GetProperty("Representation").Available
if "MFA Volume" not in types:
    sys.exit("'MFA Volume' is not among the representation types %s" % (types,))
if display.Representation != "MFA Volume":
    sys.exit("the reader's default representation is %s, not MFA Volume" % display.Representation)

out = sys.argv[1]
pv_scene.render("single", out)
print("plugin smoke test passed:", out)
