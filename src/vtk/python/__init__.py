"""mfadvr: direct volume rendering of MFA models, from numpy and in VTK.

numpy in, numpy out (docs/python.md): encode(array) and encode_points(points, values) fit a
Model; load(path) reads one; model.query(points), model.decode(), model.save(path), model.info,
model.report; render(model_or_array) returns the image as an array.

The classes of the vtkMFA module: vtkMFAModelData (an MFA model in a pipeline), vtkMFAReader
(.mfa files), vtkMFAEncoder (fits a model to image data, meshes or point clouds) and
vtkMFAVolumeMapper (renders a model in an ordinary VTK scene). docs/vtk-module.md has examples.
"""
# Importing VTK's OpenGL modules registers their object factories (the render window and the
# volume rendering helpers) before the first window is made.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

from .vtkMFA import *  # noqa: F401,F403

from .numpy_api import Model, encode, encode_points, load, render  # noqa: F401,E402
