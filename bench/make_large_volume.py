#!/usr/bin/env python3
"""Writes a large test volume to disk, z slab by z slab (never the whole volume in memory).

    bench/make_large_volume.py N OUT_DIR [--type uint8|float32]

The file is OUT_DIR/ml_NxNxN_TYPE.raw (the raw naming convention `mfadvr encode` reads):
the Marschner-Lobb test function (the paper's alpha = 0.25, f_M = 6) on [-1, 1]^3 at N^3
samples, scaled to 0..255 for uint8. Used by bench/large_volumes.sh; not part of the tests.
"""
import argparse
import os
import sys

import numpy as np


def marschner_lobb(x, y, z, alpha=0.25, fm=6.0):
    r = np.sqrt(x * x + y * y)
    rho = np.cos(2.0 * np.pi * fm * np.cos(np.pi * r / 2.0))
    return (1.0 - np.sin(np.pi * z / 2.0) + alpha * (1.0 + rho)) / (2.0 * (1.0 + alpha))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("n", type=int, help="samples per axis")
    p.add_argument("out_dir")
    p.add_argument("--type", choices=["uint8", "float32"], default="uint8")
    a = p.parse_args()
    if a.n < 2:
        sys.exit("make_large_volume: N must be at least 2")
    os.makedirs(a.out_dir, exist_ok=True)
    path = os.path.join(a.out_dir, f"ml_{a.n}x{a.n}x{a.n}_{a.type}.raw")
    tmp = path + ".part"
    u = np.linspace(-1.0, 1.0, a.n, dtype=np.float32)
    y, x = np.meshgrid(u, u, indexing="ij")  # one z plane, x fastest
    with open(tmp, "wb") as f:
        for k in range(a.n):
            v = marschner_lobb(x, y, u[k])
            if a.type == "uint8":
                v = np.clip(np.rint(v * 255.0), 0, 255).astype(np.uint8)
            else:
                v = v.astype(np.float32)
            f.write(v.tobytes())
    os.replace(tmp, path)
    print(path)


if __name__ == "__main__":
    main()
