#!/usr/bin/env python3
"""Resamples a tetrahedral mesh's own field (linear in each tetrahedron) onto a fine regular
grid, so that our ray caster can render the mesh's field with the same rays, step and transfer
function as the MFA model of the mesh (`render GRID --method trilinear`): a reference that
isolates the fit from the differences between renderers (docs/encoding.md, cell samples).

    /usr/bin/python3 bench/mesh_reference_grid.py MESH FIELD OUT.vti [N]

N nodes along the longest axis (default 768), the spacing equal on all axes. Nodes outside the
mesh get the field's minimum, which a ramp transfer function leaves transparent. Prints the grid
dims, the spacing, the field's range (pass it to --range) and the share of nodes outside. Needs
VTK's Python module (python3-vtk9); FIELD may be '' for the mesh's active scalars.
"""
import os
import sys

import vtk
from vtk.util import numpy_support


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    source, field, out = sys.argv[1:4]
    n = int(sys.argv[4]) if len(sys.argv) == 5 else 768
    if n < 2:
        sys.exit("N must be at least 2")
    reader = (vtk.vtkXMLUnstructuredGridReader() if source.endswith(".vtu")
              else vtk.vtkUnstructuredGridReader())
    reader.SetFileName(source)
    reader.Update()
    mesh = reader.GetOutput()
    if mesh.GetNumberOfCells() == 0:
        sys.exit(f"{source}: no cells")
    if field:
        mesh.GetPointData().SetActiveScalars(field)
    scalars = mesh.GetPointData().GetScalars()
    if scalars is None:
        sys.exit(f"{source}: no point scalars {field!r}")
    vmin, vmax = scalars.GetRange()
    b = mesh.GetBounds()
    extent = [b[1] - b[0], b[3] - b[2], b[5] - b[4]]
    h = max(extent) / (n - 1)
    dims = [max(2, int(round(e / h)) + 1) for e in extent]
    spacing = [extent[a] / (dims[a] - 1) for a in range(3)]

    grid = vtk.vtkImageData()
    grid.SetDimensions(dims)
    grid.SetOrigin(b[0], b[2], b[4])
    grid.SetSpacing(spacing)
    probe = vtk.vtkProbeFilter()
    probe.SetInputData(grid)
    probe.SetSourceData(mesh)
    probe.Update()
    probed = probe.GetOutput().GetPointData()
    values = numpy_support.vtk_to_numpy(probed.GetArray(scalars.GetName())).astype("float32")
    valid = numpy_support.vtk_to_numpy(probed.GetArray("vtkValidPointMask"))
    values[valid == 0] = vmin

    result = vtk.vtkImageData()
    result.SetDimensions(dims)
    result.SetOrigin(b[0], b[2], b[4])
    result.SetSpacing(spacing)
    array = numpy_support.numpy_to_vtk(values, deep=1)
    array.SetName(scalars.GetName() or "value")
    result.GetPointData().SetScalars(array)
    writer = vtk.vtkXMLImageDataWriter()
    writer.SetFileName(out + ".part")
    writer.SetInputData(result)
    if not writer.Write():
        sys.exit(f"{out}: could not write")
    os.replace(out + ".part", out)
    print(f"dims {dims[0]} {dims[1]} {dims[2]} spacing {spacing[0]:.6g} {spacing[1]:.6g} "
          f"{spacing[2]:.6g} range {vmin:.9g},{vmax:.9g} outside {(valid == 0).mean():.3f}")


if __name__ == "__main__":
    main()
