"""Shared by the ParaView plugin tests (run by pvpython and pvbatch): makes ParaView's Python
modules importable, loads the plugin, and renders one of the test scenes with a fixed camera.

Environment: MFADVR_PLUGIN (the plugin's .so), MFADVR_PARAVIEW_PYTHONPATH (ParaView's Python
modules when python3-paraview is unpacked rather than installed), MFADVR_TEST_DATA (the folder
written by mfadvr_paraview_test_data).
"""
import os
import sys

_extra = os.environ.get("MFADVR_PARAVIEW_PYTHONPATH")
if _extra and _extra not in sys.path:
    # Ahead of the system's dist-packages, which hold Debian's VTK 9.1 `vtkmodules`.
    sys.path.insert(0, _extra)

from paraview.simple import *  # noqa: E402,F401,F403
import paraview.simple as pvs  # noqa: E402

SIZE = [240, 240]


def load_plugin():
    """Loads the plugin; with MFADVR_PV_SERVER=host:port, connects to that pvserver first and
    loads it on both sides."""
    server = os.environ.get("MFADVR_PV_SERVER")
    if server:
        host, port = server.rsplit(":", 1)
        pvs.Connect(host, int(port))
        pvs.LoadPlugin(os.environ["MFADVR_PLUGIN"], remote=True)
        pvs.LoadPlugin(os.environ["MFADVR_PLUGIN"], remote=False)
    else:
        # Without ns, the plugin's proxies become functions of paraview.simple.
        pvs.LoadPlugin(os.environ["MFADVR_PLUGIN"])


def source(kind):
    """'encode': MFA Encode of a Wavelet (split among the ranks, with ghost layers);
    'encode-pass': the same with Pass Input Values (each rank's carrier keeps the input's array
    and its ghost layers, marked as ghost cells); 'single' / 'blocks': the MFA reader on a
    single or a 4-block model file."""
    if kind in ("encode", "encode-pass"):
        wavelet = pvs.Wavelet()
        wavelet.WholeExtent = [-20, 20, -20, 20, -20, 20]
        encoded = pvs.MFAEncode(Input=wavelet)
        encoded.Degree = 2
        encoded.PassInputValues = int(kind == "encode-pass")
        return encoded, "RTData", (37.35, 276.8)
    path = os.path.join(os.environ["MFADVR_TEST_DATA"], kind + ".mfa")
    # The array is named after the model's field: the built-in's name.
    return pvs.MFAModelReader(FileName=path), "marschner-lobb", (0.0, 1.0)


def check_cells_counted_once(src, cells):
    """The carriers' cells that are not ghost cells cover the data once, whatever the number of
    ranks: Integrate Variables (which skips ghost cells) gives the data's volume."""
    integrated = pvs.servermanager.Fetch(pvs.IntegrateVariables(Input=src))
    volume = integrated.GetCellData().GetArray("Volume").GetValue(0)
    if abs(volume - cells) > 1e-6 * cells:
        raise SystemExit(f"the carriers' cells add up to a volume of {volume}, not {cells}")


def render(kind, png):
    load_plugin()
    src, array, (lo, hi) = source(kind)
    if kind.startswith("encode"):
        check_cells_counted_once(src, 40 ** 3)
    view = pvs.CreateRenderView()
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    display = pvs.Show(src, view)
    display.Representation = "MFA Volume"
    pvs.ColorBy(display, ("POINTS", array))
    lut = pvs.GetColorTransferFunction(array)
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(lo, hi)
    opacity = pvs.GetOpacityTransferFunction(array)
    opacity.Points = [lo, 0.0, 0.5, 0.0, lo + 0.45 * (hi - lo), 0.0, 0.5, 0.0,
                      lo + 0.55 * (hi - lo), 0.8, 0.5, 0.0, hi, 0.8, 0.5, 0.0]
    # World units: the Wavelet spans 40, the models 2.
    display.ScalarOpacityUnitDistance = 2.0 if kind.startswith("encode") else 0.1
    display.Shade = 1
    view.ResetCamera()
    camera = view.GetActiveCamera()
    camera.Azimuth(30)
    camera.Elevation(20)
    view.ResetCamera()
    pvs.Render(view)
    pvs.SaveScreenshot(png, view, ImageResolution=SIZE)
    return display


if __name__ == "__main__":
    render(sys.argv[1], sys.argv[2])
