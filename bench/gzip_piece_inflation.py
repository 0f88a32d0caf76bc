#!/usr/bin/env python3
"""Time and temporary disk of vtkMFAVolumeReader's inflation of a gzip volume, per piece.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/gzip_piece_inflation.py FILE [PIECES]

For each piece of PIECES (default 2) and for the whole extent, a new reader is updated: the
script prints the time of UpdateInformation (the header) and of the update (the inflation and
the read), the extent read, and how much the free space of TMPDIR (else /tmp) fell while the
reader holds its inflated samples. docs/benchmarks.md ("Each piece inflated alone").
"""
import os
import shutil
import sys
import time

import mfadvr


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    path = sys.argv[1]
    pieces = int(sys.argv[2]) if len(sys.argv) == 3 else 2
    if pieces < 1:
        sys.exit("gzip_piece_inflation: PIECES must be at least 1")
    tmp = os.environ.get("TMPDIR", "/tmp")
    for piece in list(range(pieces)) + [None]:
        reader = mfadvr.vtkMFAVolumeReader()
        reader.SetFileName(path)
        start = time.perf_counter()
        reader.UpdateInformation()
        header = time.perf_counter() - start
        free = shutil.disk_usage(tmp).free
        start = time.perf_counter()
        if piece is None:
            reader.Update()
        else:
            reader.UpdatePiece(piece, pieces, 0)
        update = time.perf_counter() - start
        held = free - shutil.disk_usage(tmp).free
        if reader.GetOutput().GetNumberOfPoints() == 0:
            sys.exit(f"gzip_piece_inflation: {path} could not be read (see the VTK error above)")
        label = "whole" if piece is None else f"piece {piece} of {pieces}"
        print(f"{label}: UpdateInformation {header * 1e3:.1f} ms, update {update:.2f} s, "
              f"extent {reader.GetOutput().GetExtent()}, temporary disk {held / 1e6:.1f} MB")
        del reader


if __name__ == "__main__":
    main()
