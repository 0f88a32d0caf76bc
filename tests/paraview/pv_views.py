"""pv_views.py SCENES OUT_DIR SUFFIX: renders each scene of the comma-separated SCENES from 24
cameras (azimuths 0, 45, ..., 315 at elevations -60, 0 and 60: from the front, behind, above and
below) and writes OUT_DIR/<scene>-SUFFIX-a<azimuth>-e<elevation>.png for each. Run by pvbatch on
1, 2 or 4 MPI ranks, all scenes in one run (a pvbatch start costs about as much as a scene's 24
views); run_mpi_compare.sh SCENES OUT views compares the ranks' images view by view.

Scenes (files written by mfadvr_paraview_test_data, a CT-like head with field 'scalars' on a
36 x 23.1 x 35.1 box with spacing 0.9, 0.7, 1.3 and origin 12, -7, 30):
  scan-1, scan-x, scan-y, scan-z, scan-xy   the MFA reader on one model, and on blocks split
                                            along x, y, z and 2 x 2 x 1;
  scan-encode                               MFA Encode of scan.vti, partitioned among the ranks
                                            by ParaView's XML image reader;
  scan-nrrd                                 MFA Encode of scan.nrrd (uint8 samples, gzip),
                                            each rank's piece read by MFA Volume Reader.
"""
import os
import sys

import pv_scene
import paraview.simple as pvs

SIZE = [160, 160]
AZIMUTHS = range(0, 360, 45)
ELEVATIONS = (-60, 0, 60)


def source(scene):
    data = os.environ["MFADVR_TEST_DATA"]
    if scene == "scan-encode":
        image = pvs.XMLImageDataReader(FileName=[os.path.join(data, "scan.vti")])
        encoded = pvs.MFAEncode(Input=image)
        encoded.Degree = 2
        return encoded, "scalars"
    if scene == "scan-nrrd":
        image = pvs.MFAVolumeReader(FileName=os.path.join(data, "scan.nrrd"))
        encoded = pvs.MFAEncode(Input=image)
        encoded.Degree = 2
        # The name VTK's NRRD reader gives gzip samples.
        return encoded, "ImageScalars"
    return pvs.MFAModelReader(FileName=os.path.join(data, scene + ".mfa")), "scalars"


def render_views(scene, prefix):
    """The scene's 24 views, written as prefix-a<azimuth>-e<elevation>.png; the scene's source,
    view and display are deleted afterwards, so that the next scene starts from nothing."""
    src, array = source(scene)
    view = pvs.CreateRenderView()
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    display = pvs.Show(src, view)
    display.Representation = "MFA Volume"
    pvs.ColorBy(display, ("POINTS", array))
    lut = pvs.GetColorTransferFunction(array)
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(0.0, 255.0)
    # As for a CT scan: air transparent, soft tissue faint, bone the most opaque.
    pvs.GetOpacityTransferFunction(array).Points = [0, 0, 0.5, 0, 60, 0, 0.5, 0,
                                                        255, 0.6, 0.5, 0]
    display.ScalarOpacityUnitDistance = 2.0
    display.Shade = 1
    camera = view.GetActiveCamera()
    for elevation in ELEVATIONS:
        for azimuth in AZIMUTHS:
            view.CameraPosition = [0, 0, 1]
            view.CameraFocalPoint = [0, 0, 0]
            view.CameraViewUp = [0, 1, 0]
            view.ResetCamera()
            camera.Azimuth(azimuth)
            camera.Elevation(elevation)
            camera.OrthogonalizeViewUp()
            view.ResetCamera()
            pvs.Render(view)
            pvs.SaveScreenshot("%s-a%d-e%d.png" % (prefix, azimuth, elevation), view,
                               ImageResolution=SIZE)
    pvs.Hide(src, view)
    pvs.Delete(view)
    pvs.Delete(src)


def main():
    scenes, out_dir, suffix = sys.argv[1].split(","), sys.argv[2], sys.argv[3]
    pv_scene.load_plugin()
    for scene in scenes:
        render_views(scene, os.path.join(out_dir, "%s-%s" % (scene, suffix)))


if __name__ == "__main__":
    main()
