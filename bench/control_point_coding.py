#!/usr/bin/python3
"""Rate-distortion groundwork for compact models: ZFP on a volume's samples against ZFP on the
control points of MFA models of it, at equal footing (bits per input sample, volume PSNR over
the value range at every input sample).

    bench/control_point_coding.py [RAW] [--mfadvr build/release/src/app/mfadvr]
        RAW: an 8-bit raw volume NAME_XxYxZ_uint8.raw (default ../shared/data/fuel_64x64x64_uint8.raw)

For each control count it encodes the volume (`mfadvr encode --ctrl N`, degree 3), codes the
float32 control grid with ZFP's fixed-accuracy mode (tolerances 0.5 to 16, in data units) and
with byte shuffling + deflate (lossless), writes the decoded control points into a copy of the
model file (docs/model-format.md: header, knots, float32 control points, CRC-32), and measures
the decoded model with `mfadvr query` at every sample. An experiment, not a format: the .mfa
file does not code its control points yet. Needs python3-zfpy and python3-numpy (Debian).
"""
import argparse
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np

try:
    import zfpy
except ImportError:
    sys.exit("needs ZFP's Python module: apt-get install python3-zfpy")


def read_model(path):
    b = open(path, "rb").read()
    header_bytes = struct.unpack_from("<I", b, 14)[0]
    header = json.loads(b[18:18 + header_bytes])
    knots = sum(n + p + 1 for n, p in zip(header["control_counts"], header["degree"]))
    offset = 18 + header_bytes + 8 * knots
    count = int(np.prod(header["control_counts"]))
    ctrl = np.frombuffer(b, dtype="<f4", count=count, offset=offset).copy()
    return b, header, offset, ctrl


def write_model(b, offset, ctrl, path):
    body = b[:offset] + ctrl.astype("<f4").tobytes() + b[offset + 4 * ctrl.size:-4]
    open(path, "wb").write(body + struct.pack("<I", zlib.crc32(body) & 0xFFFFFFFF))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("raw", nargs="?",
                        default=os.path.join(here, "../../shared/data/fuel_64x64x64_uint8.raw"))
    parser.add_argument("--mfadvr", default=os.path.join(here, "../build/release/src/app/mfadvr"))
    parser.add_argument("--ctrl", default="64,48,32,24", help="control counts to try")
    args = parser.parse_args()
    m = re.search(r"_(\d+)x(\d+)x(\d+)_uint8\.raw$", args.raw)
    if not m:
        sys.exit(args.raw + ": expected an 8-bit raw volume NAME_XxYxZ_uint8.raw")
    nx, ny, nz = map(int, m.groups())
    data = np.fromfile(args.raw, dtype=np.uint8).astype(np.float32).reshape(nz, ny, nx)
    count = data.size

    def psnr(a, b):
        mse = float(np.mean((a.astype(np.float64) - b.astype(np.float64)) ** 2))
        return float("inf") if mse == 0 else 10 * np.log10(255.0 ** 2 / mse)

    work = tempfile.mkdtemp(prefix="mfadvr-rd-")
    points = os.path.join(work, "points.txt")
    zz, yy, xx = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    np.savetxt(points, np.stack([xx.ravel(), yy.ravel(), zz.ravel()], axis=1), fmt="%d")

    def evaluate(model):
        out = os.path.join(work, "values.csv")
        subprocess.run([args.mfadvr, "query", model, "--points", points, "-o", out], check=True,
                       capture_output=True)
        return np.loadtxt(out, delimiter=",", skiprows=1, usecols=3).reshape(nz, ny, nx)

    print("| representation | bits/sample | PSNR dB |\n|---|---|---|")
    for tol in (0.5, 1, 2, 4, 8, 16, 32):
        c = zfpy.compress_numpy(data, tolerance=tol)
        print("| ZFP samples, tolerance %g | %.3f | %.2f |" %
              (tol, 8 * len(c) / count, psnr(data, zfpy.decompress_numpy(c))))
    for n in map(int, args.ctrl.split(",")):
        model = os.path.join(work, "m%d.mfa" % n)
        subprocess.run([args.mfadvr, "encode", args.raw, "--ctrl", str(n), "-q", "-o", model],
                       check=True, capture_output=True)
        b, header, offset, ctrl = read_model(model)
        cx, cy, cz = header["control_counts"]
        shuffled = ctrl.astype("<f4").tobytes()
        shuffled = np.frombuffer(shuffled, dtype=np.uint8).reshape(-1, 4).T.copy().tobytes()
        base = psnr(data, evaluate(model))
        print("| MFA %d^3, float32 | %.3f | %.2f |" % (n, 32 * ctrl.size / count, base))
        print("| MFA %d^3, shuffle + deflate (lossless) | %.3f | %.2f |" %
              (n, 8 * len(zlib.compress(shuffled, 9)) / count, base))
        for tol in (0.5, 1, 2, 4, 8, 16):
            c = zfpy.compress_numpy(ctrl.reshape(cz, cy, cx), tolerance=tol)
            decoded = os.path.join(work, "decoded.mfa")
            write_model(b, offset, zfpy.decompress_numpy(c).ravel(), decoded)
            print("| MFA %d^3, ZFP control points, tolerance %g | %.3f | %.2f |" %
                  (n, tol, 8 * len(c) / count, psnr(data, evaluate(decoded))))


if __name__ == "__main__":
    main()
