"""mfadvr: direct volume rendering of MFA models in VTK.

The classes of the vtkMFA module: vtkMFAModelData (an MFA model in a pipeline), vtkMFAReader
(.mfa files), vtkMFAEncoder (fits a model to image data, meshes or point clouds) and
vtkMFAVolumeMapper (renders a model in an ordinary VTK scene). docs/vtk-module.md has examples.
"""
# Importing VTK's OpenGL modules registers their object factories (the render window and the
# volume rendering helpers) before the first window is made.
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

from .vtkMFA import *  # noqa: F401,F403
