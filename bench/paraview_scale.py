"""ParaView scale figures: encode + render of a large Wavelet with the MFA plugin, on however
many MPI ranks pvbatch runs with (bench/paraview_scale.sh drives it).

    pvbatch bench/paraview_scale.py N IMAGE_SIZE [RAW]

RAW (optional): an N^3 uint8 raw volume (x fastest, as bench/make_large_volume.py writes) read by
ParaView's Image Reader instead of the float Wavelet source, as a user's scan would be. With
MFADVR_VOLUME_READER=1, RAW is any volume file (a raw file named NAME_XxYxZ_TYPE.raw, NRRD, ...)
read by the plugin's MFA Volume Reader, each rank its piece; the transfer function is then set
from the file's value range.

Prints, per rank, the encode time, the first (still) render, a second render, and the peak
memory of the rank (max RSS), also as it was after encoding and after Show, and the memory
resident at those points and after the renders (VmRSS: what stays held, without the peaks of
the work in between).
"""
import os
import resource
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "paraview"))
import pv_scene  # noqa: E402
import paraview.simple as pvs  # noqa: E402
from paraview import servermanager as sm  # noqa: E402

n = int(sys.argv[1])
size = int(sys.argv[2])
rank = sm.vtkProcessModule.GetProcessModule().GetPartitionId()
ranks = sm.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()

raw = sys.argv[3] if len(sys.argv) > 3 else None
pv_scene.load_plugin()
if raw and os.environ.get("MFADVR_VOLUME_READER") == "1":
    source = pvs.MFAVolumeReader(FileName=raw)
    field = lo = hi = None  # from the encoder's output, once it is computed
    what = "volume file (MFA Volume Reader)"
elif raw:
    source = pvs.ImageReader(FileNames=[raw])
    source.DataScalarType = "unsigned char"
    source.DataExtent = [0, n - 1] * 3
    source.NumberOfScalarComponents = 1
    field, lo, hi, what = "ImageFile", 0.0, 255.0, "uint8 volume"
    hidden, rising = 120.0, 173.0
else:
    source = pvs.Wavelet()
    half = n // 2
    source.WholeExtent = [-half, n - 1 - half] * 3
    field, lo, hi, what = "RTData", 37.35, 276.8, "Wavelet"
    hidden, rising = 150.0, 200.0
encoded = pvs.MFAEncode(Input=source)
encoded.Degree = 2
# MFADVR_PASS_INPUT_VALUES=1: the output's point values are the input's samples, not the model's.
encoded.PassInputValues = int(os.environ.get("MFADVR_PASS_INPUT_VALUES", "0"))
start = time.perf_counter()
encoded.UpdatePipeline()
encode = time.perf_counter() - start


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def resident_mib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


encode_peak = peak_mib()
encode_resident = resident_mib()
if field is None:
    field = encoded.PointData.keys()[0]
    lo, hi = encoded.PointData[field].GetRange()
    hidden, rising = lo + 0.47 * (hi - lo), lo + 0.68 * (hi - lo)  # as 120 and 173 of 0..255

view = pvs.CreateRenderView()
view.ViewSize = [size, size]
view.OrientationAxesVisibility = 0
start = time.perf_counter()
display = pvs.Show(encoded, view)
show = time.perf_counter() - start
show_peak = peak_mib()
show_resident = resident_mib()
display.Representation = "MFA Volume"
pvs.ColorBy(display, ("POINTS", field))
lut = pvs.GetColorTransferFunction(field)
lut.RescaleTransferFunction(lo, hi)
opacity = pvs.GetOpacityTransferFunction(field)
# Hidden below `hidden` (47 % of the range), then rising.
opacity.Points = [lo, 0.0, 0.5, 0.0, hidden, 0.0, 0.5, 0.0, rising, 0.3, 0.5, 0.0,
                  hi, 0.6, 0.5, 0.0]
display.ScalarOpacityUnitDistance = n / 16.0
display.Shade = 1
view.ResetCamera()
view.GetActiveCamera().Azimuth(30)
view.GetActiveCamera().Elevation(20)
view.ResetCamera()
times = []
for _ in range(2):
    start = time.perf_counter()
    pvs.Render(view)
    times.append(time.perf_counter() - start)
print("rank %d of %d: %d^3 %s, encode %.2f s, show %.2f s, render %.2f s then %.2f s "
      "(%dx%d), peak memory %.0f MiB (after encoding %.0f, after Show %.0f); resident after "
      "encoding %.0f, after Show %.0f, after the renders %.0f MiB"
      % (rank, ranks, n, what, encode, show, times[0], times[1], size, size, peak_mib(), encode_peak,
         show_peak, encode_resident, show_resident, resident_mib()), flush=True)
