#!/usr/bin/env python3
"""How far a mesh's model is from the mesh's own field between its points: the model is queried
(`mfadvr query`) at the four points of the degree-2 rule inside every tetrahedron and compared
with the field linear in that tetrahedron (docs/encoding.md, cell samples).

    /usr/bin/python3 bench/mesh_fit_between_points.py MESH FIELD MODEL.mfa [MFADVR]

FIELD: the point array ('-': the active scalars). MFADVR: the command-line tool (default
build/release/src/app/mfadvr). Prints, as fractions of the field's range: the largest and RMS
error against the linear field, and the overshoot beyond each tetrahedron's own vertex range
(largest, and the share of points past 1 % and 5 %). Needs VTK's and numpy's Python modules.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

# Barycentric weights of the symmetric 4-point rule (exact for quadratics).
A, B = 0.5854101966249685, 0.1381966011250105
RULE = np.array([[A, B, B, B], [B, A, B, B], [B, B, A, B], [B, B, B, A]])


def read_tetrahedra(path, field):
    reader = vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtkUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    split = vtkDataSetTriangleFilter()
    split.SetInputConnection(reader.GetOutputPort())
    split.TetrahedraOnlyOn()
    split.Update()
    grid = split.GetOutput()
    data = grid.GetPointData()
    array = data.GetScalars() if field == "-" else data.GetArray(field)
    if array is None or grid.GetNumberOfCells() == 0:
        sys.exit("%s: no point array '%s' or no 3-D cells" % (path, field))
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    values = vtk_to_numpy(array).astype(float)
    tets = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    return points, values, tets


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    mesh, field, model = sys.argv[1:4]
    tool = sys.argv[4] if len(sys.argv) == 5 else "build/release/src/app/mfadvr"
    points, values, tets = read_tetrahedra(mesh, field)
    at = np.einsum("sk,tkd->tsd", RULE, points[tets]).reshape(-1, 3)
    linear = np.einsum("sk,tk->ts", RULE, values[tets]).reshape(-1)
    low = np.repeat(values[tets].min(axis=1), len(RULE))
    high = np.repeat(values[tets].max(axis=1), len(RULE))
    with tempfile.TemporaryDirectory() as tmp:
        query = os.path.join(tmp, "points.txt")
        np.savetxt(query, at)
        out = subprocess.run([tool, "query", model, "--points", query], capture_output=True,
                             text=True, check=True).stdout.splitlines()
    header = out[0].split(",")
    model_values = np.loadtxt(out[1:], delimiter=",", ndmin=2)[:, header.index("value")]
    span = values.max() - values.min()
    error = np.abs(model_values - linear) / span
    overshoot = np.maximum(model_values - high, low - model_values) / span
    print("%s: %d points, %d tetrahedra, %d query points" % (mesh, len(values), len(tets), len(at)))
    print("error against the linear field: max %.4f, rms %.5f (of the range)" %
          (error.max(), np.sqrt(np.mean(error ** 2))))
    print("overshoot beyond the tetrahedron's vertex range: max %.4f; past 1%%: %.3f %%, past "
          "5%%: %.4f %%" % (max(overshoot.max(), 0.0), 100 * np.mean(overshoot > 0.01),
                            100 * np.mean(overshoot > 0.05)))


if __name__ == "__main__":
    main()
