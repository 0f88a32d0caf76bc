"""compare_images.py MIN_PSNR REFERENCE.png OTHER.png...: exit 1 unless every other image is
within MIN_PSNR dB of the reference (8-bit RGB) and the reference is not blank.

compare_images.py --scene-views MIN_PSNR DIR SCENES SUFFIXES: the same for every view of each
scene of the comma-separated SCENES (pv_views.py's files): DIR/<scene>-<first suffix>-a*-e*.png
the references, the files of the same view with the other suffixes of the comma-separated
SUFFIXES the others; one summary line per scene."""
import math
import os
import sys

import numpy
import pv_scene  # noqa: F401  (makes ParaView's modules importable)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader


def pixels(path):
    """The image's size and its RGB channels (alpha dropped), one row of floats per pixel."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    scalars = image.GetPointData().GetScalars()
    if scalars is None:
        sys.exit("cannot read " + path)
    values = vtk_to_numpy(scalars).reshape(scalars.GetNumberOfTuples(), -1)
    return image.GetDimensions(), values[:, :3].astype(numpy.float64)


def is_blank(values):
    """Whether fewer than 1 % of the pixels differ from the most common colour (the background):
    a scene that rendered nothing. Channels are compared as colours, not pooled: a uniform
    background of unequal channels is blank too."""
    _, counts = numpy.unique(values, axis=0, return_counts=True)
    return len(values) - counts.max() < 0.01 * len(values)


def psnr(reference_path, other_path):
    """PSNR in dB of other against reference (8-bit RGB); exits when the reference is blank or
    the sizes differ."""
    dims, ref = pixels(reference_path)
    if is_blank(ref):
        sys.exit("the reference image %s is blank" % reference_path)
    other_dims, other = pixels(other_path)
    if other_dims != dims:
        sys.exit("%s has another size than %s" % (other_path, reference_path))
    mse = numpy.mean((ref - other) ** 2)
    return math.inf if mse == 0 else 10 * math.log10(255.0 ** 2 / mse)


def compare_views(reference_prefix, others):
    """Each OTHER-<view>.png against REFERENCE-<view>.png, for every view of the reference;
    returns the worst PSNR and its file."""
    import glob
    references = sorted(glob.glob(reference_prefix + "-a*-e*.png"))
    if not references:
        sys.exit("no images %s-a*-e*.png" % reference_prefix)
    worst, where = math.inf, ""
    for ref_path in references:
        view = ref_path[len(reference_prefix):]
        for prefix in others:
            value = psnr(ref_path, prefix + view)
            print("%s vs %s: PSNR %.2f dB" % (prefix + view, ref_path, value))
            if value < worst:
                worst, where = value, prefix + view
    print("%d views x %d rank counts; worst %.2f dB (%s)" % (len(references), len(others), worst,
                                                           where))
    return worst, where


def require(minimum, worst, where):
    if worst < minimum:
        sys.exit("PSNR %.2f dB of %s is below %.1f dB" % (worst, where, minimum))


def main():
    if sys.argv[1] == "--scene-views":
        minimum, folder = float(sys.argv[2]), sys.argv[3]
        suffixes = sys.argv[5].split(",")
        results = []
        for scene in sys.argv[4].split(","):
            prefix = os.path.join(folder, scene + "-")
            results.append(compare_views(prefix + suffixes[0],
                                         [prefix + suffix for suffix in suffixes[1:]]))
        require(minimum, *min(results))
        return
    worst, where = math.inf, ""
    for path in sys.argv[3:]:
        value = psnr(sys.argv[2], path)
        print("%s vs %s: PSNR %.2f dB" % (path, sys.argv[2], value))
        if value < worst:
            worst, where = value, path
    require(float(sys.argv[1]), worst, where)


if __name__ == "__main__":
    main()
