#!/usr/bin/env python3
"""Writes a tetrahedral mesh shaped like a CFD domain around a post, for encode benchmarks of
10^5-point meshes (docs/encoding.md): a flat annulus (a disk 30 units across and 4.8 thick with a
post of radius 0.5 at its centre), points graded towards the post as a flow solver's grid is,
split into tetrahedra. The point field `Energy` has what makes such data hard to fit: a thin
curved front around the post, a narrow wake behind it and a smooth variation across the disk.

    /usr/bin/python3 bench/make_post_mesh.py OUT.vtu [NR NTHETA NZ]

Default 64 x 96 x 17 = 104,448 points, 580,608 tetrahedra. Needs VTK's Python module
(python3-vtk9).
"""
import math
import sys

import vtk


def energy(x, y, z):
    r = math.hypot(x, y)
    theta = math.atan2(y, x)
    # A front at r = 3 + 0.5 sin(3 theta), 0.15 thick.
    front = math.tanh((r - 3.0 - 0.5 * math.sin(3.0 * theta)) / 0.15)
    # A wake behind the post (x > 0), widening downstream.
    wake = math.exp(-y * y / (0.05 + 0.02 * max(x, 0.0))) if x > 0.0 else 0.0
    return 1.0 + 0.4 * front - 0.6 * wake + 0.2 * math.cos(math.pi * z / 4.8) + 0.05 * x / 15.0


def main():
    if len(sys.argv) not in (2, 5):
        sys.exit(__doc__)
    out = sys.argv[1]
    nr, nt, nz = (int(a) for a in sys.argv[2:5]) if len(sys.argv) == 5 else (64, 96, 17)
    if min(nr, nt, nz) < 2:
        sys.exit("each count must be at least 2")
    r0, r1, height = 0.5, 15.0, 4.8
    points = vtk.vtkPoints()
    values = vtk.vtkFloatArray()
    values.SetName("Energy")
    for k in range(nz):
        z = height * k / (nz - 1)
        for j in range(nt):
            theta = 2.0 * math.pi * j / nt
            for i in range(nr):
                # Geometric grading: spacing grows away from the post.
                r = r0 * (r1 / r0) ** (i / (nr - 1))
                x, y = r * math.cos(theta), r * math.sin(theta)
                points.InsertNextPoint(x, y, z)
                values.InsertNextValue(energy(x, y, z))
    # Hexahedra of the (r, theta, z) grid, theta closing the ring; split into tetrahedra by
    # vtkDataSetTriangleFilter, whose splits follow the point ids, so neighbours agree.
    index = lambda i, j, k: (k * nt + j % nt) * nr + i
    hexes = vtk.vtkUnstructuredGrid()
    hexes.SetPoints(points)
    hexes.GetPointData().SetScalars(values)
    hexes.Allocate((nr - 1) * nt * (nz - 1))
    for k in range(nz - 1):
        for j in range(nt):
            for i in range(nr - 1):
                ids = [index(i, j, k), index(i + 1, j, k), index(i + 1, j + 1, k),
                       index(i, j + 1, k)]
                ids += [v + nr * nt for v in ids]
                hexes.InsertNextCell(vtk.VTK_HEXAHEDRON, 8, ids)
    tets = vtk.vtkDataSetTriangleFilter()
    tets.SetInputData(hexes)
    tets.Update()
    mesh = tets.GetOutput()
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetFileName(out)
    writer.SetInputData(mesh)
    writer.SetDataModeToBinary()
    if not writer.Write():
        sys.exit("could not write " + out)
    print("%s: %d points, %d cells" % (out, mesh.GetNumberOfPoints(), mesh.GetNumberOfCells()))


if __name__ == "__main__":
    main()
