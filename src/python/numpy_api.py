"""numpy in, numpy out: encode arrays and points into MFA models, query, decode and render them.

The functions take the command line's long options as keywords, `_` for `-` (max_error=0.01
is --max-error 0.01; per-axis values as (x, y, z) tuples; True for a flag), parsed by the same
code, so that defaults, checks and error messages are those of `mfadvr encode` and
`mfadvr render`. docs/python.md describes every function.
"""
import numpy as np

from . import _mfadvr
from ._mfadvr import Model, load  # noqa: F401


def encode(array, spacing=None, origin=None, **options):
    """Fits a model to a 3-D array indexed [z, y, x] (C order: x fastest, the layout of VTK's,
    PyVista's and raw files' arrays; other orders are read by index, an (nx, ny, nz) array must be
    transposed first: array.transpose(2, 1, 0)). Any numeric dtype; integer arrays get the
    CLI's integer-scan default coding. spacing and origin: one number or (x, y, z).
    Options: degree, ctrl, max_error, max_ctrl, max_rounds, smooth, coding, tolerance,
    bits_per_sample, psnr, rms_error, lossless (encode --help); blocks=(bx, by, bz) or "auto",
    ghost, memory_limit for a multi-block model (encode --blocks; also chosen when an in-core
    fit would not fit the memory limit). model.report is the fit report.
    A 4-D array indexed [t, z, y, x] is a time series: one 4-D model (docs/time-varying.md), with
    times=(t0, t1, ...) (default 0, 1, 2, ...), time_degree and time_ctrl (encode --times,
    --time-degree, --time-ctrl); each step is converted when the encoder reads it."""
    return _mfadvr._encode(np.asanyarray(array), spacing, origin, **options)


def encode_points(points, values, tets=None, **options):
    """Fits a model to scattered points: an (N, 3) array of x, y, z and (N,) values, with the
    CLI's options for meshes and point clouds (degree, ctrl, smooth, mask_res, no_mask, ...).
    With tets, an (M, 4) integer array of point indices, the points are a tetrahedral mesh and
    the model gets what `mfadvr encode` gives a mesh file: its exact boundary, a mask from its
    cells and samples of its linear field inside them (cell_samples)."""
    return _mfadvr._encode_points(np.asanyarray(points), np.asanyarray(values),
                                  None if tets is None else np.asanyarray(tets), **options)


_INTEGER_TYPES = ("uint8", "int8", "uint16", "int16", "uint32", "int32")


def _decode(model, shape=None, dtype=None):
    """The model's values on the grid it was encoded from (or `shape` = (nz, ny, nx) samples over
    its box), indexed [z, y, x], in the input's type by default (integers rounded and clamped, as
    `mfadvr decode` writes them; samples outside a domain mask NaN, 0 for integer types)."""
    values = model._decode_values(shape)
    if dtype is None:
        dtype = model.sample_type if model.sample_type in _INTEGER_TYPES else "float32"
    dtype = np.dtype(dtype)
    if dtype.kind in "iu":
        info = np.iinfo(dtype)
        values = np.clip(np.rint(np.nan_to_num(values, nan=0.0)), info.min, info.max)
    return values.astype(dtype)


Model.decode = _decode


def _to_vtk(model):
    """The model as a vtkMFAModelData (for vtkMFAVolumeMapper and VTK pipelines), sharing it:
    no copy."""
    from .vtkMFA import vtkMFAModelData
    data = vtkMFAModelData()
    model._into_vtk(data)
    return data


def _from_vtk(data):
    """The Model a vtkMFAModelData holds (vtkMFAReader's or vtkMFAEncoder's output), shared."""
    return Model._from_vtk(data)


Model.to_vtk = _to_vtk
Model.from_vtk = staticmethod(_from_vtk)


def render(model_or_array, size=(512, 512), method="mfa", spacing=None, origin=None,
           alpha=False, float=False, **options):
    """A rendered image as an (h, w, 3) uint8 array ((h, w, 4) with alpha=True; linear float RGBA
    with float=True): the pixels `mfadvr render` writes for the same scene options (tf, colormap,
    range, shade, blend, iso, step, azimuth, elevation, zoom, background, clip_plane, crop, ...).
    A model renders with method 'mfa'; an array with 'mfa' (encoded first, with the encoding
    options), or a grid filter: 'trilinear', 'tricubic', 'catmull-rom', 'bspline', 'nearest'."""
    if not isinstance(model_or_array, Model):
        model_or_array = np.asanyarray(model_or_array)
    return _mfadvr._render(model_or_array, size=size, spacing=spacing, origin=origin,
                           method=method, alpha=alpha, float=float, **options)
